#pragma once
// The event-driven simulator loop (docs/MODEL.md, "How a run proceeds"). One step of the loop is a list
// of named stages:
//   1. Settle: decide which spheres rest on the plate and how (stick / slide), resolving
//      Painleve's paradox by an impact without collision.
//   2a. Flight (no sphere resting): analytic motion up to the earliest gap root of either
//      sphere (flight.h), then the impact law (impact_law.h) with every sphere touching.
//   2b. Persistent contact: integrate (contact_integrator.h) up to lift-off, a slip transition
//      or the other sphere's impact, then act on the event.
//   3. Record: output samples at --fps, the event log, per-period statistics.
// Work is chunked at period boundaries so progress, interruption and statistics line up.
#include <functional>
#include <string>
#include <vector>

#include "sim/events.h"
#include "common/modes.h"
#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim {

struct SimDiagnostics {
  long flight_steps = 0;       // safe steps of the impact finder
  long contact_steps = 0;      // accepted RK steps
  long contact_rejected = 0;   // rejected RK steps
  long impact_segments = 0;    // linear segments of all impacts
  long impact_failures = 0;    // impacts whose segment solve failed (should be 0)
  long capped_searches = 0;    // impact searches that hit their step cap (should be 0)
  long step_underflows = 0;    // contact steps accepted at the minimum size (should be 0)
  long painleve = 0;           // Painleve situations resolved by impact without collision
  long rest_stages = 0;        // stages skipped in the rest state that stays put (resting.h)
  long energy_capped = 0;      // impacts where plain Newton would have created energy
  double max_newton_gain = 0;  // largest such gain relative to the kinetic energy before
  double max_penetration_m = 0;  // deepest gap seen at any evaluated point, m
  long events = 0;
  int max_events_in_period = 0;
};

struct SimResult {
  Model model;
  double t_start = 0, t_end = 0;
  std::vector<double> t;       // output sample times, s
  std::vector<State> lab;      // lab-frame states at those times
  std::vector<EventRecord> events;
  std::vector<PeriodStats> periods;
  SimDiagnostics diag;
  ModeSummary mode;
  bool interrupted = false;
  std::string error;  // non-empty: the run stopped early (event storm); the rest is valid
};

struct RunControls {
  bool keep_events = true;                      // false: count only (benchmarks, sweeps)
  // Called with every event as it is logged, whether or not the log is kept: a sweep point
  // classifies its impacts on the fly instead of keeping the whole log (~200 bytes an event,
  // ~0.4 GB at a 10^5-period point; sim/sweep_point.cc).
  std::function<void(const EventRecord&)> on_event;
  // Called once per period with every sample so far (SimResult::t and ::lab, n of them): the
  // arrays hold all the run's samples from the start, so these addresses stay valid and the
  // first n rows final while the run goes on (RunSim compresses them meanwhile, run_sim.cc).
  std::function<void(const double* t, const State* lab, size_t n)> on_samples;
  std::function<void(double done, double total)> progress;  // called once per period
  std::function<bool()> should_stop;            // polled once per period (Ctrl-C)
  // The rest state that provably stays put (sim/resting.h) costs nothing per period; false
  // integrates it step by step (tests compare the two).
  bool skip_rest = true;
};

// Throws InputError for invalid options. An event storm stops the run and sets `error`.
SimResult RunSimulation(const SimOptions& options, const RunControls& controls = {});

}  // namespace dimer::sim
