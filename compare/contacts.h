#pragma once
// Contacts and impacts of each sphere with the plate, from a sampled trajectory.
//
// gap_s = z_s - z_plate - R is the height of sphere s's lowest point above the plate. A tracker
// may see it with a constant offset (lighting moves the apparent centre by a fraction of a
// pixel), so the level at which a sphere touches is measured, not assumed: the densest band of
// width 2 thr starting among the lowest 2 % of its gaps, when it holds >= 5 % of the frames
// gathered about its middle (a sphere that rests); a sphere that never rests takes the other
// sphere's level (same appearance), or 0.
// thr = max(4 sigma_gap, 1e-6 d), sigma_gap from the data (noise.h): every threshold follows
// the noise, so a simulation (noise-free) resolves micro-bounces a camera cannot.
//
//   on the plate: gap - level <= thr;   resting: on the plate for >= 3 consecutive frames,
//   unless the flights before and after them, fitted as a bounce, pass through each within thr.
//   impact: the end of a flight (a run of frames above level + thr that rose at least 2 thr)
//   at a frame on the plate, or at a local minimum of the gap within one frame's travel of the
//   plate (a bounce between two frames).
// Impact times are not frame times: quadratics fitted to the approach (and the departure, for a
// bounce) meet at the kink, or the approach meets the contact level (a landing). So the time is
// a fraction of a frame, independent of the level for bounces, and the fitted slopes give the
// normal velocities relative to the plate before and after. A second pass drops the frames
// within one frame of the impact (motion blur straddling it; the tracker next to the plate).
#include <array>
#include <cstdint>
#include <vector>

#include "compare/plate_fit.h"
#include "compare/sampled_run.h"

namespace dimer::compare {

inline constexpr double kContactSigmas = 4.0;       // thr in units of the gap noise
inline constexpr double kContactFloorRel = 1e-6;    // thr floor, fraction of d (noise-free data)
inline constexpr int kMinRestFrames = 3;            // a rest is this many frames on the plate
inline constexpr double kRestLevelMinFraction = 0.05;
// ... of which this fraction within thr / 2 of the band's middle (a rest: ~0.95 with Gaussian
// noise, 0.92 measured on a POV-Ray film; frames passing through the band: ~0.5, 0.45 there).
inline constexpr double kRestCoreMinFraction = 0.7;
inline constexpr int kImpactFitFrames = 20;         // frames fitted on each side of an impact
inline constexpr size_t kImpactMinFitFrames = 4;    // fewer: keep the first pass

struct Impact {
  int sphere = 0;             // 0 left, 1 right
  double t = kNaN;            // s (file time)
  double frame = kNaN;        // fractional frame index
  double plate_phase = kNaN;  // plate phase at t, [0, 1)
  double v_before = kNaN;     // normal velocity relative to the plate before (< 0), m/s
  double v_after = kNaN;      // after (> 0); NaN when it lands to rest
  // The fastest it can have approached, m/s: from rest at the flight's highest gap h above the
  // contact level (plus what the samples can miss of the apex), under the largest relative
  // fall acceleration (1 + Gamma) g: sqrt(2 (1 + Gamma) g h). NaN when Gamma is unknown.
  double speed_bound = kNaN;
  double level_m = kNaN;      // gap at the fitted contact point
  bool bounce = false;        // true: flight-kink-flight; false: landing to rest
};

struct SphereContacts {
  double noise_m = 0;         // sigma of the gap, m
  double level_m = 0;         // contact level of the gap, m
  double threshold_m = 0;     // thr, m
  std::vector<double> gap;    // per frame, m (NaN where unknown)
  std::vector<uint8_t> resting;  // per frame: 1 while resting
  std::vector<Impact> impacts;
};

struct Contacts {
  std::array<SphereContacts, 2> sphere;
  std::vector<Impact> AllImpacts() const;  // both spheres, by time
};

// `min_threshold_m` (NaN: none) raises each sphere's thr to at least that value.
Contacts FindContacts(const SampledRun& run, const PlateDrive& plate,
                      const std::array<double, 2>& min_threshold_m = {kNaN, kNaN});

}  // namespace dimer::compare
