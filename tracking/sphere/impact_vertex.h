#pragma once
// Where a sphere that never rests touches the plate: the vertex of the V its gap draws at each
// impact (appearance_model.h, ContactRowOffset).
//
// A sphere's gap to the plate, (plate - R - reference row) per frame, is its template's offset
// while it rests. In the jump and flutter modes neither end rests: it touches the plate between
// two frames, at the bottom of a V whose arms are the approach and the rebound (the velocity
// reverses in the impact, sub-millisecond against a 0.5 ms frame period). The frames next to the
// impact lie anywhere up to a few tenths of a pixel above the contact, so the mean of the lowest
// frames leans off it (+0.09 to +0.18 px on POV-Ray films of the jump mode). The arms are
// straight over a few frames (gravity bends them by ~0.006 px per frame^2 at 0.4 mm/px), and
// where the two lines fitted to them meet is the contact: the vertex.
#include <cstddef>
#include <vector>

namespace dimer::tracking {

// Gravity, m/s^2 (docs/MODEL.md; the simulator's value).
inline constexpr double kGravity = 9.81;

// Frames in each arm of the V, the frame nearest the impact included in one of them. Measured on
// the POV-Ray jump film of PovrayTiltedPlate (dimer_compare_povray_test): with 3 the slopes
// at 0.2 px a frame are within their noise and no V is found; 4 and 5 agree within 0.04 px.
inline constexpr int kImpactArmFrames = 4;
// An arm's slope must be at least this many of its own standard errors (from the gap's noise)
// away from zero, downward before the impact and upward after: a sphere resting, or turning in
// flight, draws no V (4 sigmas on each of two arms: a 5-sigma trend over each arm's frames).
inline constexpr double kImpactMinSlopeSigmas = 4.0;
// The arms' residual may be at most this many times the gap's noise (RMS over both arms): a
// second impact or a lost frame inside an arm bends it.
inline constexpr double kImpactMaxResidualNoise = 3.0;

struct ImpactVertex {
  size_t frame = 0;       // the frame nearest the impact
  double time = 0;        // the impact, frames (where the two arms meet)
  double value = 0;       // the gap there, px
  double err = 0;         // its standard uncertainty from the arms' noise, px
  double approach = 0;    // the arms' slopes, px per frame (approach < 0 < rebound)
  double rebound = 0;
};

// The gap's noise per frame, px: the median absolute second difference over the finite
// triples, as a standard deviation (/ 0.6745 / sqrt(6)); flights curve it by far less. NaN with
// fewer than 3 triples.
double GapNoise(const std::vector<double>& gap);

// Every V in `gap` (frame order, NaN where the sphere was not found) whose arms are each
// kImpactArmFrames finite frames, straight within kImpactMaxResidualNoise × `noise` and sloped
// by kImpactMinSlopeSigmas, and whose lines meet within a frame of the lowest frame between
// them. Frame order; where two candidates share frames, the one that fits better. `bend`
// (empty, or per frame; NaN: 0): the gap's second difference in flight, px per frame^2, which
// bends the arms and lifts the meeting of straight lines by ~1.5 times it (GapBend).
std::vector<ImpactVertex> ImpactVertices(const std::vector<double>& gap, double noise,
                                         const std::vector<double>& bend = {});

// Half-width of the plate rows' window whose curvature is the plate's at a frame, frames (a
// quadratic over 17 frames, 8.5 ms of a 40 ms period: 0.0003 px per frame^2 from 0.013 px of
// noise).
inline constexpr int kPlateBendHalfWindow = 8;

// The gap's second difference in flight per frame (px per frame^2; rows grow downward): the
// plate row's, from a quadratic through the plate rows about the frame (0 where the window
// leaves the film or holds a NaN), less gravity's pull on the sphere, `gravity_px` = g / (m/px
// × fps^2) (NaN: unknown, left out). At 0.2 mm/px and 2000 frames/s gravity alone is 0.012.
// (A sphere of a spinning dimer also swings about its centre of mass: ~0.1 g, left out.)
std::vector<double> GapBend(const std::vector<double>& plate_rows, double gravity_px);

}  // namespace dimer::tracking
