#pragma once
// The plate's drive z_p(t) = offset + amp sin(2 pi f t + phase), t the file's own time axis,
// fitted to the tracked plate (or read from a sim file, or given by --freq/--gamma when the
// plate is not visible). Gamma = 4 pi^2 amp f^2 / g (docs/MODEL.md).
//
// The fit is variable projection: for a trial f the offset and the sine/cosine amplitudes are
// linear least squares, so only f is searched (a scan around the zero-crossing estimate, then
// golden-section refinement); the covariance of all four parameters comes from the Jacobian at
// the optimum scaled by the residual variance. Harmonics 2f..4f are fitted to the residual and
// reported relative to amp, so a non-sinusoidal drive is visible rather than silently averaged.
#include <array>
#include <string>
#include <vector>

#include "compare/sampled_run.h"

namespace dimer::compare {

inline constexpr double kGravity = 9.81;  // m/s^2 (docs/MODEL.md)

struct PlateDrive {
  std::string source = "none";  // fit | file (sim attributes) | options (--freq/--gamma)
  double freq_hz = kNaN, freq_err = kNaN;
  double amp_m = kNaN, amp_err = kNaN;
  double offset_m = 0;
  double phase_rad = kNaN, phase_err = kNaN;  // at t = 0 of the file's time axis, [0, 2 pi)
  double gamma = kNaN, gamma_err = kNaN;
  // The fitted plate's own Gamma where --gamma replaced it (an accelerometer's value); NaN else.
  double gamma_plate = kNaN, gamma_plate_err = kNaN;
  double residual_rms_m = kNaN;               // fit residual
  std::array<double, 3> harmonic_rel{kNaN, kNaN, kNaN};  // |2f|, |3f|, |4f| amplitude / amp
  int frames_used = 0;

  double period() const { return 1.0 / freq_hz; }
  double Z(double t) const;           // plate height at t, m (offset if the phase is unknown)
  double V(double t) const;           // plate velocity at t, m/s (0 if the phase is unknown)
  double PhaseFraction(double t) const;  // plate phase at t in [0, 1): 0 = mid-height rising
};

// Fits the plate of `run` (frames with a finite plate_z). `freq_guess_hz` (NaN: estimate from
// zero crossings, or where they are too few from the best sine over a frequency grid) seeds the
// search. Returns source "none" if the plate does not move detectably (amplitude below 5 times
// its error, or less than 1 period of plate data); a clip of 1-2 periods is fitted, and the
// analysis refuses it with its length in periods.
PlateDrive FitPlate(const SampledRun& run, double freq_guess_hz);

// The drive of a sim file, from its attributes (exact).
PlateDrive PlateFromSim(const SampledRun& run);

}  // namespace dimer::compare
