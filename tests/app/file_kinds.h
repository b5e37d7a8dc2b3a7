#pragma once
// One small file of every kind dimerlab writes, made through the same Run functions as the CLI:
// the schema and integrity tests run over all of them, so a new dataset cannot escape them.
#include <string>
#include <vector>

#include "sim/run_sim.h"
#include "sim/sweep_run.h"
#include "tests/common/test_tmpdir.h"
#ifdef DIMERLAB_HAVE_COMPARE
#include "compare/run_compare.h"
#endif
#ifdef DIMERLAB_HAVE_TRACKING
#include "render/render.h"
#include "tracking/run_track.h"
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
  // A sweep with a completed point and a failed one (jump below its Gamma threshold), so
  // that every column holds values and the error strings are both empty and not.
  sim::SweepRunArgs sweep;
  sim::SetSpecValue(&sweep.spec, "ar", "3.9", "");
  sim::SetSpecValue(&sweep.spec, "init", "jump", "");
  sim::SetSpecValue(&sweep.spec, "gamma", "0.1,0.9", "");
  sim::SetSpecValue(&sweep.spec, "periods", "3", "");
  sim::SetSpecValue(&sweep.spec, "transient", "1", "");
  sweep.output = dir / "sweep.h5";
  sweep.progress = false;
  sweep.threads = 1;
  sim::RunSweep(sweep);
  files.push_back({"sweep", sweep.output});
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
