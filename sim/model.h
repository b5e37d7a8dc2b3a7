#pragma once
// The immutable description of one simulated experiment: geometry of the dimer, the drive of the
// plate, friction and restitution (docs/MODEL.md), plus the numerical knobs that trade speed for
// accuracy. SimOptions is what the user gives (CLI flags of docs/FORMATS.md, SI units or fractions);
// Model is what the stages read (derived quantities, all SI).
//
// Frames: the simulator works in the plate frame (x' along the plate, z' along its normal,
// origin on the moving plate surface), where the plate is still and gravity becomes
// g_eff(t) = (-g sin(alpha), -g cos(alpha) - zddot_p(t)). Files and --init-state use the lab
// frame (reference_frames.h converts). Mass is 1 (nothing depends on it), forces are per unit mass.
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sim/constants.h"

namespace dimer::sim {

inline constexpr double kGravity = 9.81;  // m/s^2 (docs/MODEL.md)
// The paper's release lifts one end by "a fraction of the sphere diameter"; 0.3 d at its
// base frequency of 25 Hz (docs/MODEL.md, "Default lift").
inline constexpr double kDefaultLift = 0.3;
inline constexpr double kDefaultLiftFreqHz = 25.0;

enum class InitKind { kDrift, kJump, kFlutter, kRest };
enum class RestitutionLaw { kCappedNewton, kNewton };  // impact_law.h
const std::vector<std::pair<std::string, RestitutionLaw>>& RestitutionLawNames();
const std::vector<std::pair<std::string, InitKind>>& InitKindNames();
std::string ToString(InitKind k);

struct SimOptions {
  // Dimer.
  double ar = 3.9;             // aspect ratio A_r = length / diameter (> 1)
  double diameter_m = 9.5e-3;  // sphere diameter d, m
  // Drive.
  double freq_hz = 25.0;       // plate frequency f, Hz
  double gamma = 0.9;          // Gamma = 4 pi^2 a f^2 / g
  double tilt_deg = 0.0;       // plate inclination alpha, degrees (> 0: rising toward +x)
  double plate_phase = 0.0;    // plate phase at t = 0, fraction of a period
  // Contact laws (paper's values).
  double eps = 0.65;           // kinematic restitution coefficient, [0, 1]
  double mu = 0.2;             // persistent-contact sliding friction
  double mu_s = 0.4;           // persistent-contact static friction (>= mu)
  double mu_hat = 0.1;         // impact sliding friction
  double mu_hat_s = 0.2;       // impact static (stick) friction
  RestitutionLaw restitution = RestitutionLaw::kCappedNewton;  // see impact_law.h
  // Initial condition.
  InitKind init = InitKind::kDrift;
  // Drift release: lift of the bouncing end, fraction of d. NaN (the default) means
  // kDefaultLift at 25 Hz scaled by (25 Hz / f)^2, a release dynamically similar at every
  // frequency (the drift orbit's heights scale as g T^2); see EffectiveLift().
  double lift = std::numeric_limits<double>::quiet_NaN();
  double release_phase = 0.25; // plate phase of the release, fraction of a period
  std::optional<std::array<double, 6>> init_state;  // lab (x, z, theta, u, v, omega) at t = 0
  // Duration and output.
  double cycles = 100.0;       // plate periods to simulate (ignored if duration_s > 0)
  double duration_s = 0.0;     // s; 0: use cycles
  double fps = 2000.0;         // output sampling rate, samples/s; 0: events only
  // Numerical knobs (measured in bench/bench_sim_accuracy).
  double collapse_rel = 1e-4;  // v_c / (g/f): impacts slower than v_c are plastic (collapse)
  double contact_tol = 1e-9;   // persistent-contact RK45 tolerance (relative, on g/f and R)
  double gap_tol = kGapTol_m;  // impact-location tolerance: deepest penetration allowed, m
  double max_events_per_period = 5000;  // a run above this average stops with an error

  // Every invalid field at once, as "--flag: value: expected ..." lines; empty if valid.
  std::vector<std::string> Check() const;
  double Duration() const { return duration_s > 0 ? duration_s : cycles / freq_hz; }
  // Output samples of the run, defined once (docs/FORMATS.md, "Samples"): sample k is at
  // exactly t_start + k / fps for k = 0 .. n-1, n = floor(Duration() fps + kSampleCountSlack) + 1,
  // so the end time is included whenever Duration() fps is a whole number up to its rounding
  // (3 periods at 25 Hz and 2000/s give 240.00000000000003 or 239.99999999999997: 241
  // samples either way). 0 when fps == 0 (events only).
  long SampleCount() const;
  // Memory the run's results take (samples, statistics, event log), bytes: checked against the
  // machine's memory before a run starts, so that a long run is refused at once rather than
  // ending in bad_alloc.
  double EstimatedMemoryBytes(bool with_event_log = true) const;
  static constexpr double kSampleCountSlack = 1e-6;  // samples
  double EffectiveLift() const;
};

struct Model {
  // Geometry.
  double R;        // sphere radius, m
  double A;        // A_r - 1: half the centre distance is A R
  double inv_I;    // 1 / I, I = R^2 (A^2 + 2/5) for unit mass
  // Drive: z_p(t) = amp sin(omega_p t + phi0) along the plate normal.
  double amp, omega_p, phi0, period;
  double sin_a, cos_a;  // tilt
  // Laws.
  double eps, mu, mu_s, mu_hat, mu_hat_s;
  RestitutionLaw restitution;
  // Numerics.
  double v_collapse;  // m/s: collapse_rel g/f, floored at sqrt(2 g_max gap_tol)
  double contact_tol;
  double gap_tol;     // m
  double vel_scale;   // g/f, m/s: scale for relative velocity tolerances

  static Model FromOptions(const SimOptions& o);  // assumes o.Check() is empty
  // Plate position, velocity and acceleration along its normal (lab), at time t.
  double PlateZ(double t) const;
  double PlateV(double t) const;
  double PlateA(double t) const;
  // Effective gravity in the plate frame (tangential, normal).
  double Gx() const { return -kGravity * sin_a; }
  double Gz(double t) const { return -kGravity * cos_a - PlateA(t); }

  // The same quantities from sin and cos of the plate phase omega_p t + phi0, computed once
  // and shared by every quantity needed at one time (the hot loops). Each is the same
  // expression as its time overload, so both give bit-identical values.
  struct PlatePhase {
    double s, c;  // sin, cos of omega_p t + phi0
  };
  PlatePhase Phase(double t) const {
    const double arg = omega_p * t + phi0;
    return {std::sin(arg), std::cos(arg)};
  }
  // Only sin: enough for PlateA and Gz (the contact forces need nothing else); c is NaN.
  PlatePhase SinPhase(double t) const {
    return {std::sin(omega_p * t + phi0), std::numeric_limits<double>::quiet_NaN()};
  }
  double PlateZ(PlatePhase p) const { return amp * p.s; }
  double PlateV(PlatePhase p) const { return amp * omega_p * p.c; }
  double PlateA(PlatePhase p) const { return -amp * omega_p * omega_p * p.s; }
  double Gz(PlatePhase p) const { return -kGravity * cos_a - PlateA(p); }
};

}  // namespace dimer::sim
