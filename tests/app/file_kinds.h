#pragma once
// One small file of every kind dimerlab writes, made through the same Run functions as the CLI:
// the schema and integrity tests run over all of them, so a new dataset cannot escape them.
#include <string>
#include <vector>

#include "sim/run_sim.h"
#include "tests/common/test_tmpdir.h"
#ifdef DIMERLAB_HAVE_COMPARE
#include "compare/run_compare.h"
#endif
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
#ifdef DIMERLAB_HAVE_COMPARE
  // compare with every optional part: a simulation beside it and a (small) coefficient fit.
  sim::SimRunArgs longer = sim;  // long enough to settle in drift, so that the fit runs
  longer.options.cycles = 8;
  longer.output = dir / "sim_for_compare.h5";
  sim::RunSim(longer);
  compare::CompareArgs cmp;
  cmp.input = longer.output;
  cmp.sim_path = longer.output;
  cmp.fit = true;
  cmp.fit_options.global_evaluations = 8;
  cmp.fit_options.max_evaluations = 8;
  cmp.fit_options.slice_points = 3;
  cmp.fit_options.transient_periods = 2;
  cmp.output = dir / "report";
  cmp.quiet = true;
  compare::RunCompare(cmp);
  files.push_back({"compare", cmp.output + "/compare.h5"});
#endif
  return files;
}

}  // namespace dimer::testing
