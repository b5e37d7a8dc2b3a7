#pragma once
// The exact slip of a simulation beside compare's estimate of it: U = u - omega r_z of the
// resting sphere's contact point from the simulated state, relative to the plate (in the plate's
// frame; the lab's on a level plate), on the frames where the analysis measured a slip (analysed
// frame i is simulated sample i) within the settled window of its periods (t_start <= t <
// t_end, as periods.cc counts frames), phase-averaged into the analysis's own bins.
#include <algorithm>
#include <cmath>
#include <vector>

#include "compare/analysis.h"
#include "sim/reference_frames.h"
#include "sim/simulator.h"
#include "sim/state.h"

namespace dimer::compare {

struct ExactSlip {
  std::vector<double> centres, mean, sem;  // per phase bin
  std::vector<int> count;
  double peak = 0;  // largest |mean|
};

inline ExactSlip ExactSlipProfile(const Analysis& a, const sim::SimResult& r) {
  const int rs = a.slip.resting_sphere;
  const ModeWindow& w = a.periods.settled;
  std::vector<double> exact(a.run.n, NAN), phase(a.run.n);
  for (size_t i = 0; i < a.run.n && i < r.lab.size(); ++i) {
    phase[i] = a.plate.PhaseFraction(a.run.Time(i));
    const double t = a.run.Time(i);
    if (!std::isfinite(a.slip.U[i]) || w.count == 0 || t < w.t_start || t >= w.t_end) continue;
    const sim::State q = sim::PlateFromLab(r.model, r.t[i], r.lab[i]);
    exact[i] = a.slip.sign * sim::SlipU(sim::ContactArm(r.model, q.th, rs), q);
  }
  ExactSlip e;
  PhaseAverage(phase, exact, static_cast<int>(a.slip.phase.size()), &e.centres, &e.mean, &e.sem, &e.count);
  for (double v : e.mean)
    if (std::isfinite(v)) e.peak = std::max(e.peak, std::abs(v));
  return e;
}

}  // namespace dimer::compare
