#include "sim/contact_integrator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "sim/constants.h"

namespace dimer::sim {
namespace {

using Vec6 = std::array<double, 6>;
constexpr double kInf = std::numeric_limits<double>::infinity();

Vec6 ToVec(const State& q) { return {q.x, q.z, q.th, q.u, q.v, q.w}; }
State ToState(const Vec6& y) { return {y[0], y[1], y[2], y[3], y[4], y[5]}; }

Vec6 Deriv(const State& q, const ContactForces& f) { return {q.u, q.v, q.w, f.ax, f.az, f.aw}; }
Vec6 Deriv(const Model& m, const ContactConfig& cfg, Model::PlatePhase phase, const Vec6& y) {
  const State q = ToState(y);
  return Deriv(q, SolveContactForces(m, phase, q, cfg));
}

// One Dormand-Prince step; returns the 5th-order solution, the error estimate and the plate's
// phase at t + h (the last two stages and the event check at the step end share it). k0 is the
// derivative at (t, y), known from the event check at the step start (the same computation, so
// reusing it changes no bit).
struct RkStep {
  Vec6 y, err;
  Model::PlatePhase end_phase;
};
RkStep DormandPrince(const Model& m, const ContactConfig& cfg, double t, const Vec6& y,
                     double h, const Vec6& k0) {
  static constexpr double c[7] = {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1};
  static constexpr double a[7][6] = {
      {0, 0, 0, 0, 0, 0},
      {1.0 / 5, 0, 0, 0, 0, 0},
      {3.0 / 40, 9.0 / 40, 0, 0, 0, 0},
      {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0},
      {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0},
      {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0},
      {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
  static constexpr double e[7] = {71.0 / 57600,  0,           -71.0 / 16695, 71.0 / 1920,
                                  -17253.0 / 339200, 22.0 / 525, -1.0 / 40};
  std::array<Vec6, 7> k;
  k[0] = k0;
  RkStep out;
  for (int s = 1; s < 7; ++s) {
    Vec6 ys = y;
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < 6; ++i) ys[i] += h * a[s][j] * k[j][i];
    if (s < 6) out.end_phase = m.SinPhase(t + c[s] * h);  // stages 5 and 6 both at t + h
    k[s] = Deriv(m, cfg, out.end_phase, ys);
  }
  for (int i = 0; i < 6; ++i) {
    double y5 = y[i], er = 0;
    for (int s = 0; s < 6; ++s) y5 += h * a[6][s] * k[s][i];
    for (int s = 0; s < 7; ++s) er += h * e[s] * k[s][i];
    out.y[i] = y5;
    out.err[i] = er;
  }
  return out;
}

// Event functions, positive while nothing happens. Index: 0/1 the per-sphere contact event
// (lift-off or slip), 2/3 the per-sphere gap of a non-resting sphere. A second event per
// resting sphere (lift-off while sliding/sticking) is folded in by taking the minimum.
struct EventValues {
  std::array<double, 4> v;
  std::array<ContactEvent, 4> kind;
  Vec6 deriv;  // the state's derivative (the next step's first stage)
};
EventValues Events(const Model& m, const ContactConfig& cfg, Model::PlatePhase phase,
                   const State& q) {
  EventValues ev;
  const ContactForces f = SolveContactForces(m, phase, q, cfg);
  ev.deriv = Deriv(q, f);
  const double fscale = kGravity;  // makes force and velocity events comparable in size
  for (int s = 0; s < 2; ++s) {
    ev.v[s] = kInf;
    ev.kind[s] = ContactEvent::kEnd;
    ev.v[2 + s] = kInf;
    ev.kind[2 + s] = ContactEvent::kImpact;
    const Arm r = ContactArm(m, q.th, s);
    if (!cfg.resting[s]) {
      // Offset by the gap tolerance (constants.h): a sphere that starts exactly at the plate
      // (h = 0 after a collapse nearby) is still watched, and penetration stays < the gap tolerance.
      ev.v[2 + s] = q.z + r.rz + m.gap_tol;
      continue;
    }
    // Lift-off in the second slot (index 2+s is free for a resting sphere).
    ev.v[2 + s] = f.n[s] / fscale;
    ev.kind[2 + s] = ContactEvent::kLiftoff;
    if (cfg.slide[s] != 0) {
      ev.v[s] = cfg.slide[s] * SlipU(r, q) / m.vel_scale;
      ev.kind[s] = ContactEvent::kSlipStops;
    } else {
      ev.v[s] = (m.mu_s * f.n[s] - std::abs(f.f[s])) / fscale;
      ev.kind[s] = ContactEvent::kSlipStarts;
    }
  }
  return ev;
}

State Project(const Model& m, const ContactConfig& cfg, const Vec6& y) {
  State q = ToState(y);
  ProjectOnContacts(m, cfg, &q);
  return q;
}

// Illinois (modified regula falsi) on f over [0, h] with f(0) > 0 >= f(h).
template <typename F>
double LocateRoot(F&& f, double f0, double h, double fh) {
  double a = 0, b = h, fa = f0, fb = fh;
  int side = 0;
  for (int i = 0; i < kMaxLocateIterations && b - a > kEventTimeTol_s; ++i) {
    double c = (fa * b - fb * a) / (fa - fb);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double fc = f(c);
    if (fc > 0) {
      a = c, fa = fc;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = c, fb = fc;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return b;  // the event has happened at b (f <= 0)
}

// One accepted step [t, t + hs] from y0; states inside it come from a single RK step of the
// same method from y0 (no error control needed: tau <= hs was accepted).
struct StepView {
  const Model& m;
  const ContactConfig& cfg;
  double t;
  Vec6 y0, k0;
  double hs;
  // The step's end and the last point asked for: the event's final state is asked for again
  // at the point the root finder ended on (the same computation, so the same bits).
  State end{};
  bool has_end = false;
  mutable double last_tau = std::numeric_limits<double>::quiet_NaN();
  mutable State last{};
  State At(double tau) const {
    if (has_end && tau == hs) return end;
    if (tau == last_tau) return last;
    last = Project(m, cfg, DormandPrince(m, cfg, t, y0, tau, k0).y);
    last_tau = tau;
    return last;
  }
  double Event(int k, double tau) const {
    return Events(m, cfg, m.SinPhase(t + tau), At(tau)).v[k];
  }
};

// A slide that starts from U = 0 (sigma U = 0 at the start) may dip the right way and come back
// within the step (a slip reversal right after the start): find a point where sigma U > 0 by
// halving toward the start. Returns it (with its value in *f), or 0 if the slip went the wrong
// way at once, in which case the event is reported at the start and the caller chooses again.
double SlipRestartPoint(const StepView& st, int k, double* f) {
  double tau = st.hs;
  for (int i = 0; i < 40; ++i) {
    tau *= 0.5;
    *f = st.Event(k, tau);
    if (*f > 0) return tau;
  }
  *f = 0;
  return 0;
}

// A gap that is positive at both ends of [0, span] may still dip below zero inside it:
// look at the interior minimum of the cubic Hermite interpolant of (h, h'), whichever way the
// sphere moves at the ends (grazing on the way down and up; or a sphere that has just
// bounced, rising and falling back within the span, as at Gamma 1.4 in the mode map:
// Penetration.ShortFlightsNextToARestingSphereAreSeen). Returns the point where the gap event
// is <= 0 (and its value in *f), or span if there is none.
double GrazingPoint(const StepView& st, int k, const State& q0, const State& q1, double span,
                    double f0, double f1, double* f) {
  const int s = k - 2;
  const double d0 = NormalV(ContactArm(st.m, q0.th, s), q0) * span;
  const double d1 = NormalV(ContactArm(st.m, q1.th, s), q1) * span;
  const double c3 = 2 * f0 - 2 * f1 + d0 + d1, c2 = -3 * f0 + 3 * f1 - 2 * d0 - d1;
  const double disc = c2 * c2 - 3 * c3 * d0;
  *f = f1;
  // The minimum of f0 + d0 x + c2 x^2 + c3 x^3: where its second derivative is positive.
  double xm = -1;
  if (c3 != 0) {
    if (disc >= 0) xm = (-c2 + std::sqrt(disc)) / (3 * c3);
  } else if (c2 > 0) {
    xm = -d0 / (2 * c2);
  }
  if (!(xm > 0 && xm < 1)) return span;
  const double fm = st.Event(k, xm * span);
  if (fm > 0) return span;
  *f = fm;
  return xm * span;
}

// Time from the step start of event k inside [0, span] (f1, q1 at span), or +inf.
double EventTime(const StepView& st, int k, ContactEvent kind, double f0, double f1,
                 const State& q0, const State& q1, double span) {
  double lo = 0, hi = span;
  if (!(f0 > 0)) {
    if (kind != ContactEvent::kSlipStops || !(f1 < 0)) return kInf;
    lo = SlipRestartPoint(st, k, &f0);
    if (!(f0 > 0)) return 0.0;
  }
  if (f1 > 0 && kind == ContactEvent::kImpact) {
    hi = GrazingPoint(st, k, q0, q1, span, f0, f1, &f1);
  }
  if (f1 > 0) return kInf;
  return lo + LocateRoot([&](double x) { return st.Event(k, lo + x); }, f0, hi - lo, f1);
}

// The gap event fires at h = -gap_tol; Newton back to h = 0 so that the sphere leaves the
// impact from the plate surface and stays watched in the next phase.
double RefineImpactToSurface(const StepView& st, int sphere, double tau) {
  for (int i = 0; i < kMaxNewtonIterations; ++i) {
    const State qs = st.At(tau);
    const Arm r = ContactArm(st.m, qs.th, sphere);
    const double vn = NormalV(r, qs), gap = qs.z + r.rz;
    if (!(vn < 0)) break;
    const double step = std::clamp(-gap / vn, -tau, st.hs - tau);
    tau += step;
    if (std::abs(step) < kRootTimeTol_s) break;
  }
  return tau;
}

}  // namespace

// Stages of each step: (1) an adaptive RK5(4) step, retried smaller until its error is within
// tolerance; (2) projection onto the contact constraints; (3) the earliest event inside the
// step; (4) output samples up to the event or the step end; (5) stop at the event or go on.
ContactRun IntegrateContact(const Model& m, const ContactConfig& cfg, double t0, const State& q0,
                            double t_end, double* h, SampleSink* sink) {
  ContactRun run;
  const double tol = m.contact_tol;
  const double scale[6] = {m.R, m.R, 1.0, m.vel_scale, m.vel_scale, m.vel_scale / m.R};
  const double h_min = kMinStepRel * m.period, h_max = kMaxStepRel * m.period;
  double t = t0;
  State q = q0;
  EventValues ev0 = Events(m, cfg, m.SinPhase(t), q);
  *h = std::clamp(*h, h_min, h_max);
  while (t < t_end) {
    const double hs = std::min(*h, t_end - t);
    StepView st{m, cfg, t, ToVec(q), ev0.deriv, hs};
    const RkStep step = DormandPrince(m, cfg, t, st.y0, hs, st.k0);
    double err = 0;
    for (int i = 0; i < 6; ++i) err = std::max(err, std::abs(step.err[i]) / (tol * scale[i]));
    if (!(err <= 1.0) && hs > h_min) {
      ++run.rejected;
      *h = std::max(h_min, hs * std::clamp(0.9 * std::pow(err, -0.2), 0.1, 0.5));
      continue;
    }
    ++run.steps;
    if (!(err <= 1.0)) run.ok = false;  // accepted at h_min: tolerance could not be met
    const State q1 = Project(m, cfg, step.y);
    st.end = q1;  // = st.At(hs)
    st.has_end = true;
    const EventValues ev1 = Events(m, cfg, step.end_phase, q1);  // phase at t + 1.0 * hs
    // The resting contacts' events first (lift-off, slip): the step's motion holds only up to
    // the earliest of them, so the other sphere's impact is looked for before it, and wins a
    // tie (it would be below the plate there).
    double tau_ev = kInf;
    int which = -1;
    for (int k = 0; k < 4; ++k) {
      if (ev1.kind[k] == ContactEvent::kImpact) continue;
      const double tau = EventTime(st, k, ev1.kind[k], ev0.v[k], ev1.v[k], q, q1, hs);
      if (tau < tau_ev) tau_ev = tau, which = k;
    }
    const double span = which >= 0 ? tau_ev : hs;
    for (int k = 2; k < 4; ++k) {
      if (ev1.kind[k] != ContactEvent::kImpact) continue;
      const bool whole = span == hs;
      const State q_span = whole ? q1 : st.At(span);
      const double f_span = whole ? ev1.v[k] : st.Event(k, span);
      const double tau = EventTime(st, k, ContactEvent::kImpact, ev0.v[k], f_span, q, q_span, span);
      if (tau < kInf && tau <= tau_ev) tau_ev = tau, which = k;
    }
    if (which >= 0 && ev1.kind[which] == ContactEvent::kImpact) {
      tau_ev = RefineImpactToSurface(st, which - 2, tau_ev);
    }
    const double t_next = which >= 0 ? t + tau_ev : t + hs;
    while (sink && sink->Next() <= t_next) {
      const double ts = sink->Next();
      sink->Record(ts, ts == t ? q : st.At(ts - t));
    }
    if (which < 0) {
      for (int s = 0; s < 2; ++s) {
        if (!cfg.resting[s] && !(ev1.v[2 + s] > 0)) {  // gap + gap_tol: positive when watched
          run.t = t + hs;
          run.q = q1;
          run.event = ContactEvent::kPenetration;
          run.sphere = s;
          return run;
        }
      }
    }
    if (which >= 0) {
      run.t = t + tau_ev;
      run.q = st.At(tau_ev);
      run.event = ev1.kind[which];
      run.sphere = which % 2;
      return run;
    }
    t += hs;
    q = q1;
    ev0 = ev1;
    *h = std::min(h_max, hs * std::clamp(0.9 * std::pow(std::max(err, 1e-10), -0.2), 0.2, 5.0));
  }
  run.t = t_end;
  run.q = q;
  return run;
}

}  // namespace dimer::sim
