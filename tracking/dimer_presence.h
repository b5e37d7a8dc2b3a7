#pragma once
// Stage "a dimer is here": a film is refused unless two spheres stand a constant distance apart
// in most of the frames that show anything (two objects or one) and in kMinDimerFrames frames
// at least. Every film of the experiment shows that, whatever its lighting; a film of something
// else (one sphere, a blob, a scene with no dimer) does not, and tracking it would write a track
// of whatever the locators latched onto. A long drift run's dimer leaves the field of view, one
// sphere after the other, often for good: frames with nothing in view do not count against it,
// and a frame with one sphere counts for it where the other's place (a dimer's length along the
// row, the furthest a tilt can put it) is within a sphere's radius of the frame's side edge or
// beyond; such a film is tracked where the dimer is in view (found = 0 elsewhere). Held by
// RunTrack.AFilmWithoutADimerIsRefusedAndNothingIsWritten and
// RunTrack.ADimerThatLeavesTheViewIsTrackedWhereItIsInView.
#include <algorithm>
#include <string>

#include "tracking/track_sequence.h"

namespace dimer::tracking {

// The fraction of the frames that show anything (both spheres or one found) that must show the
// dimer (both spheres a constant distance apart, or one with the other's place out of view), and
// the fewest frames that must show both (2.5 ms at 2000 frames/s; half of a shorter film's).
inline constexpr double kMinDimerFraction = 0.5;
inline constexpr size_t kMinDimerFrames = 5;
// Two centres are the dimer's length apart within this many px, or this fraction of it.
inline constexpr double kDimerLengthTolerancePx = 1.0;
inline constexpr double kDimerLengthToleranceFraction = 0.01;
struct DimerPresence {
  size_t frames = 0;      // readable frames
  size_t dimer = 0;       // both spheres found, the dimer's length apart
  size_t both = 0;        // both found at any distance
  size_t one = 0;         // one found
  size_t leaving = 0;     // one found, the other's place cut or out by the frame's side edge
  double length_px = 0;   // the median distance of the pairs
  size_t shown() const { return both + one; }  // frames that show anything
  size_t needed() const { return std::min(kMinDimerFrames, (frames + 1) / 2); }
  bool seen() const {
    return dimer > 0 && dimer >= needed() &&
           double(dimer + leaving) >= kMinDimerFraction * double(shown());
  }
};

DimerPresence MeasureDimerPresence(const SequenceResult& r);

// The one-line reason a film is refused ("no dimer ..."), naming what was found instead.
// Without the scale (`scale_given` false) the spheres were looked for at the size of the first
// frame's silhouettes, which on dim or front-lit steel finds none: POV-Ray underexposed and a
// camera rolled 8 degrees are refused so and tracked with the scale; the line says so.
std::string NoDimerMessage(const DimerPresence& p, bool scale_given);

// The note for a film whose dimer is in view in fewer than half of its frames ("" otherwise).
std::string DimerOutOfViewNote(const DimerPresence& p);

}  // namespace dimer::tracking
