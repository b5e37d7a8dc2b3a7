#include "sim/initial_conditions.h"

#include <cmath>
#include <sstream>

#include "common/error.h"
#include "sim/reference_frames.h"

namespace dimer::sim {

double PeriodOneImpactPhase(const Model& m) {
  const double vp = kGravity * m.period * (1 - m.eps) / (2 * (1 + m.eps));
  const double vmax = m.amp * m.omega_p;
  if (!(vmax > 0) || vp > vmax) return NAN;
  // cos(phase) = vp / vmax with sin(phase) > 0: plate above its mean and decelerating.
  return std::acos(vp / vmax);
}

namespace {

// Start time in [0, T) at which the plate phase equals `phase`.
double TimeAtPhase(const Model& m, double phase) {
  double t = (phase - m.phi0) / m.omega_p;
  t = std::fmod(t, m.period);
  return t < 0 ? t + m.period : t;
}

InitialCondition OnPeriodOneOrbit(const Model& m, const SimOptions& o) {
  const double phase = PeriodOneImpactPhase(m);
  if (std::isnan(phase)) {
    std::ostringstream s;
    s << "--init jump: no period-1 orbit at --gamma " << o.gamma << " with --eps " << o.eps
      << "; it needs Gamma >= pi(1-eps)/(1+eps) = " << M_PI * (1 - o.eps) / (1 + o.eps);
    throw UsageError(s.str());
  }
  InitialCondition ic;
  ic.t0 = TimeAtPhase(m, phase);
  const double takeoff = kGravity * m.period / 2;  // lab, along the plate normal
  ic.q.z = m.R;
  ic.q.v = takeoff - m.PlateV(ic.t0);
  return ic;
}

}  // namespace

InitialCondition MakeInitialCondition(const Model& m, const SimOptions& o) {
  InitialCondition ic;
  if (o.init_state) {
    const auto& s = *o.init_state;
    const State lab{s[0], s[1], s[2], s[3], s[4], s[5]};
    ic.t0 = 0;
    ic.q = PlateFromLab(m, 0, lab);
    for (int sp = 0; sp < 2; ++sp) {
      if (Gap(m, ic.q, sp) < -1e-9 * m.R) {
        throw UsageError("--init-state: sphere " + std::string(sp ? "right" : "left") +
                         " starts below the plate surface");
      }
    }
    return ic;
  }
  switch (o.init) {
    case InitKind::kDrift: {
      ic.t0 = TimeAtPhase(m, 2 * M_PI * o.release_phase);
      const double sin_th = o.EffectiveLift() / m.A;  // right centre lift * d = 2 R lift above the left
      ic.q.th = std::asin(sin_th);
      ic.q.z = m.R + m.A * m.R * sin_th;
      ic.q.x = m.A * m.R * std::cos(ic.q.th);  // left sphere centre at x = 0
      ic.q.v = -m.PlateV(ic.t0);               // at rest in the lab
      return ic;
    }
    case InitKind::kJump:
      return OnPeriodOneOrbit(m, o);
    case InitKind::kFlutter: {
      ic = OnPeriodOneOrbit(m, o);
      const double vl = kGravity * m.period, vr = 0.25 * kGravity * m.period;
      const double vp = m.PlateV(ic.t0);
      ic.q.v = 0.5 * (vl + vr) - vp;
      ic.q.w = (vr - vl) / (2 * m.A * m.R);
      return ic;
    }
    case InitKind::kRest:  // lying on the plate, moving with it
      ic.q.z = m.R;
      return ic;
  }
  return ic;
}

namespace {

// Why the asked-for mode was likely not reached, from the paper's ranges (docs/MODEL.md).
std::string LikelyReason(const SimOptions& o, const std::string& reached) {
  std::ostringstream why;
  switch (o.init) {
    case InitKind::kFlutter:
      why << "the flutter launch does not lead to the flutter mode at --gamma " << o.gamma;
      if (o.gamma < 1) {
        why << " (below Gamma 1, as at the paper's 0.9, flutter is not reachable from the "
               "default launch; at a larger --gamma start from a state on the flutter orbit "
               "with --init-state)";
      } else {
        why << " (the launch is outside the flutter orbit's basin here; try --init-state with "
               "a state on the orbit)";
      }
      break;
    case InitKind::kDrift:
      if (o.ar < 2.5) {
        why << "the drift mode is unstable below A_r 2.5 (paper)";
      } else if (o.gamma < 0.5) {
        why << "below Gamma 0.5 the drift mode collapses to rest (paper: drift from 0.5 to 1.1)";
      } else if (o.gamma > 1.1) {
        why << "above Gamma 1.1 the drift mode gives way to jump and flutter (paper)";
      } else {
        why << "the release (--lift " << o.EffectiveLift() << " d, --release-phase "
            << o.release_phase << ") does not lead to drift here; try another --lift";
      }
      break;
    case InitKind::kJump:
      why << "the period-1 bouncing orbit is not stable at --gamma " << o.gamma << " with --eps "
          << o.eps << "; the jump mode is the paper's Gamma < 1 regime";
      break;
    case InitKind::kRest:
      why << (o.gamma >= 1 ? "at Gamma >= 1 the plate accelerates down faster than gravity and "
                             "throws the dimer off"
                           : "the tilt is steeper than the friction angle (tan alpha > mu_s)");
      break;
  }
  if (reached == "irregular") why << "; irregular may also mean the run is still settling";
  return why.str();
}

}  // namespace

std::string ModeNote(const SimOptions& o, const std::string& settled_mode, long periods) {
  if (o.init_state || settled_mode == ToString(o.init)) return "";
  std::string note = "--init " + ToString(o.init) + " settled in " + settled_mode +
                     " mode, not " + ToString(o.init) + ": " + LikelyReason(o, settled_mode);
  if (periods < 20) {
    note += " (only " + std::to_string(periods) + " periods: the mode is judged on the last " +
            "half of the run; a longer run may settle)";
  }
  return note;
}

}  // namespace dimer::sim
