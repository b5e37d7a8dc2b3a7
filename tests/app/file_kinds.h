#pragma once
// One small file of every kind dimerlab writes, made through the same Run functions as the CLI:
// the schema and integrity tests run over all of them, so a new dataset cannot escape them.
#include <string>
#include <vector>

#include "sim/run_sim.h"
#include "tests/common/test_tmpdir.h"
#ifdef DIMERLAB_HAVE_TRACKING
#include "tracking/render.h"
#include "tracking/track.h"
#endif

namespace dimer::testing {

struct FileOfKind {
  std::string kind, path;
};

inline std::vector<FileOfKind> MakeEveryFileKind(const TempDir& dir) {
  std::vector<FileOfKind> files;
  sim::SimRunArgs sim;
  sim.options.cycles = 2;  // a drift run: impacts, stick and slip events
  sim.output = dir / "sim.h5";
  sim.progress = false;
  sim::RunSim(sim);
  files.push_back({"sim", sim.output});
#ifdef DIMERLAB_HAVE_TRACKING
  tracking::RenderArgs render;
  render.input = sim.output;
  render.output = dir / "frames";
  render.max_frames = 6;
  render.quiet = true;
  tracking::RunRender(render);
  tracking::TrackArgs track;
  track.input = render.output;
  track.output = dir / "track.h5";
  track.quiet = true;
  tracking::RunTrack(track);
  files.push_back({"track", track.output});
#endif
  return files;
}

}  // namespace dimer::testing
