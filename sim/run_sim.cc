#include "sim/run_sim.h"

#include <cstdio>
#include <sstream>

#include "common/atomic_output.h"
#include "common/check.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/memory_limit.h"
#include "common/progress.h"
#include "sim/event_rows.h"
#include "sim/initial_conditions.h"
#include "sim/sample_rows.h"
#include "sim/sim_file.h"
#include "sim/simulator.h"

namespace dimer::sim {

std::array<double, 6> ParseInitState(const std::string& text) {
  std::array<double, 6> v{};
  std::stringstream ss(text);
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (n >= 6 || end == item.c_str() || *end != '\0') {
      throw UsageError("--init-state: \"" + text +
                       "\": expected six comma-separated numbers x,z,theta,u,v,omega");
    }
    v[n++] = x;
  }
  if (n != 6) {
    throw UsageError("--init-state: \"" + text +
                     "\": expected six comma-separated numbers x,z,theta,u,v,omega");
  }
  return v;
}

int RunSim(const SimRunArgs& args) {
  // Check the output path before spending time on the run.
  if (args.output.empty()) throw UsageError("sim: -o/--output is required");
  {
    std::vector<std::string> errors = args.options.Check();
    if (!errors.empty()) {
      std::string msg = "invalid simulation parameters: ";
      for (size_t i = 0; i < errors.size(); ++i) msg += (i ? "; " : "") + errors[i];
      throw UsageError(msg);
    }
  }
  CheckRunMemory(args.options.EstimatedMemoryBytes(),
                 "use fewer --cycles, a shorter --duration or a lower --fps");
  CheckCanWrite(args.output, args.force);
  const double total = args.options.Duration() * args.options.freq_hz;
  ProgressMeter meter("sim", "periods", total, args.progress);
  RunControls controls;
  controls.progress = [&](double done, double) { meter.Update(done); };
  controls.should_stop = [] { return InterruptRequested(); };
  // The chunks of the samples and of the event log's numbers are compressed on worker threads
  // as the periods complete, while this thread simulates on, and the writer then takes them
  // (common/h5_chunks_ahead.h).
  H5WriteOptions storage;
  storage.threads = args.threads;
  const Model model = Model::FromOptions(args.options);
  SampleArrays samples;
  SimResult r;  // before `ahead`: its workers, which read r's samples, stop before r goes
  ChunksAhead ahead(storage);
  AddSampleDatasets(&ahead, model, &samples);
  EventRowsAhead events(&ahead, model);
  controls.on_event = [&](const EventRecord& e) { events.See(e); };
  controls.on_samples = [&](const double* t, const State* lab, size_t n) {
    if (!samples.t) samples = {t, lab};  // before any row is queued: no worker reads it yet
    DIMER_CHECK(samples.t == t && samples.lab == lab, "the samples' arrays never move");
    ahead.RowsReady(n);
    events.Flush();
  };
  r = RunSimulation(args.options, controls);  // moved: the samples keep their addresses
  meter.Finish(static_cast<double>(r.periods.size()));
  storage.ahead = &ahead;
  WriteSimFile(args.output, args.force, args.options, r, storage);
  const ModeSummary& ms = r.mode;
  std::printf("%s: %zu samples, %ld events (%.1f per period), settled in %s mode",
              args.output.c_str(), r.t.size(), r.diag.events,
              r.diag.events / std::max(1.0, (r.t_end - r.t_start) * args.options.freq_hz),
              ms.label.c_str());
  if (ms.label == "drift") {
    std::printf(" (bouncing %s end), drift speed %.4g m/s, <u> f/g = %.4g",
                ms.bouncing_sphere == 1 ? "right" : "left", ms.drift_speed,
                ms.drift_speed * args.options.freq_hz / kGravity);
  }
  std::printf("\n");
  if (r.error.empty() && !r.interrupted) {
    const std::string note = ModeNote(args.options, ms.label, static_cast<long>(r.periods.size()));
    if (!note.empty()) std::fprintf(stderr, "dimerlab: warning: %s\n", note.c_str());
  }
  if (!r.error.empty()) {
    throw std::runtime_error(r.error + " (partial run written to " + args.output + ")");
  }
  if (r.interrupted) throw Interrupted();
  return 0;
}

}  // namespace dimer::sim
