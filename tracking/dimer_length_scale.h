#pragma once
// `--ar`: the scale from the dimer's own length instead of its spheres' size.
//
// Why. Without --m-per-px the scale came from the sphere radius in pixels, and on mirror steel
// that radius is what the tracker measures worst: the grazing rim reflects the dark backdrop, so
// the outline recedes 0.2-0.7 px inside the true limb (the scale 2-4 % off on the POV-Ray
// footage), and where the two outlines disagree the silhouette methods' radius is used, 25 % off
// under a soft box and 2.2x under a one-sided lamp (see povray.dimer_length.CASE). The
// distance between the two centres is what it measures best: both spheres
// carry alike offsets, which cancel, so it is within 0.15 % over 20 frames on every POV-Ray film
// once the radius is near. A_r = length / diameter gives the centre distance (A_r - 1) d, hence
// m/px = (A_r - 1) d / (median centre distance in px).
//
// The template method's rows rest on the radius in pixels (centre = plate contact - R) and its
// learning is sized by it, so the radius must be known before the film is tracked: the first
// kLengthScaleFrames frames are tracked with the radius measured as before, then again with the
// radius their length implies, until that moves by less than kLengthScaleTolPx; the film is then
// tracked once with it, and its own median length sets the scale written.
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "tracking/diagnostics.h"
#include "tracking/track_sequence.h"
#include "tracking/frame_follower.h"

namespace dimer::tracking {

// Frames the calibration passes track (the film's first ones; the learning's frames lie there).
inline constexpr size_t kLengthScaleFrames = 200;
// Passes stop once the radius moves by less than this, px: a row bias a fifth of the 0.1 px
// target (a pass moves the length by ~0.1 px on one-sided light, the radius by 0.02).
inline constexpr double kLengthScaleTolPx = 0.02;
// At most this many passes (the first with the radius measured).
inline constexpr int kLengthScaleMaxPasses = 4;
// With --m-per-px and --ar both given, a tracked length implying an A_r - 1 off by more than this
// fraction is warned about (the length is within 0.15 %, a caliper's A_r - 1 within ~0.5 %).
inline constexpr double kLengthCheckTolerance = 0.01;
// Aspect ratios accepted by --ar: two spheres touching (2) and longer. The paper's range is
// 2.0-6.1.
inline constexpr double kMinAspectRatio = 2.0;

// Frames with both spheres a length needs.
inline constexpr size_t kLengthScaleMinFrames = 10;

// The median distance between the two centres over the frames showing both, px (offsets
// applied: the left and right templates' offsets differ by tenths of a pixel); NaN with fewer
// than kLengthScaleMinFrames. `used`: how many frames it rests on.
double MedianDimerLength(const std::vector<FrameTrack>& frames, size_t* used = nullptr);

// The sphere radius in px that a median centre distance `length_px` implies for aspect ratio
// `ar`: length / (2 (ar - 1)).
double RadiusFromDimerLength(double length_px, double ar);
// m/px from a centre distance in px: (ar - 1) diameter / length.
double ScaleFromDimerLength(double length_px, double ar, double diameter_m);

struct LengthScalePass {
  double radius_px_used = std::numeric_limits<double>::quiet_NaN();  // NaN: measured by the pass
  double length_px = std::numeric_limits<double>::quiet_NaN();       // its median centre distance
};

struct LengthScale {
  bool ok = false;
  double radius_px = std::numeric_limits<double>::quiet_NaN();  // what the film is tracked with
  bool converged = false;  // the last two passes' radii within kLengthScaleTolPx
  std::vector<LengthScalePass> passes;  // every pass, guesses included
  std::string failure;  // why not ok (no length measured)
  // The radius the first pass measured from the spheres' outline, or from clean silhouettes
  // where those methods were chosen: a check on --ar. NaN where the silhouette methods' radius
  // stood beside a template (20-65 % short there) or nothing was found.
  double outline_radius_px = std::numeric_limits<double>::quiet_NaN();
};

// That radius (outline_radius_px) is within 4.1 % of the one --ar settles on for every POV-Ray
// film where it is measured (see povray.dimer_length.CASE); a radius
// from --ar further from it than this fraction is warned about (A_r - 1, the centre distance
// over the diameter, given for A_r puts it 53 % off at A_r 3.9).
inline constexpr double kOutlineRadiusCheck = 0.10;

// Where the radius measured as without a scale loses the spheres (a silhouette radius of 8 px on
// the under-exposed POV-Ray film, whose spheres are 23.75 px; none through a camera turned 8
// degrees), radii are guessed: geometric from kGuessMinRadiusPx by kGuessRatio, while the dimer,
// 2 A_r R long, fits in the frame's `width`. A guess within ~20 % of the radius finds both
// spheres there (the two films: from 18 to 28 px, and from 14 to 23.75), and the passes after
// it correct it.
inline constexpr double kGuessMinRadiusPx = 6.0;
inline constexpr double kGuessRatio = 1.25;
std::vector<double> DimerLengthRadiusGuesses(int width, double ar);

// The fixed point: `length_of(radius_px)` tracks the calibration frames with that radius (NaN:
// measured as without a scale) and returns their median centre distance (NaN where too few
// frames show both spheres). From the radius measured, then from each of `guesses()` (may be
// empty) in turn: passes with the radius the last length implies, until it settles
// (kLengthScaleTolPx) or kLengthScaleMaxPasses have run from that start. A start whose pass
// shows no length, or whose later pass loses the spheres, gives way to the next.
LengthScale IterateDimerLengthScale(const std::function<double(double radius_px)>& length_of,
                                    double ar,
                                    const std::function<std::vector<double>()>& guesses = {});

// The film whose first frames the calibration passes track: what `track` was given of it.
struct LengthScaleFilm {
  std::string input;   // folder of frames, TIFF stack, .cine or video
  std::string frames;  // --frames A:B (frame_range.h); empty: all
  double ar = std::numeric_limits<double>::quiet_NaN();        // --ar
  double diameter = std::numeric_limits<double>::quiet_NaN();  // sphere diameter, m
  // --plate-m-per-px, m/px; NaN: the dimer plane's.
  std::optional<double> plate_m_per_px;
};

// The calibration passes of `track --ar` over the first kLengthScaleFrames frames of
// film.frames (`seq` as the film will be tracked, its contact radius replaced by each pass's),
// each pass a note in `diag`: decoder messages are left to the film's own pass, which meets the
// same frames. Throws Interrupted on Ctrl-C.
LengthScale TrackedDimerLengthScale(const LengthScaleFilm& film, const SequenceOptions& seq,
                                    Diagnostics* diag);

}  // namespace dimer::tracking
