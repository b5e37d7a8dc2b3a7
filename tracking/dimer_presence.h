#pragma once
// Stage "a dimer is here": a film is refused unless two spheres stand a constant distance apart
// in most of its readable frames. Every film of the experiment shows that, whatever its
// lighting; a film of something else (one sphere, a blob, a scene with no dimer) does not, and
// tracking it would write a track of whatever the locators latched onto. Held by
// RunTrack.AFilmWithoutADimerIsRefusedAndNothingIsWritten.
#include <string>

#include "tracking/track_sequence.h"

namespace dimer::tracking {

// The fraction of readable frames that must show the dimer (both spheres, a constant distance
// apart); a film where the dimer is out of view longer is tracked over the frames that show it
// (--frames).
inline constexpr double kMinDimerFraction = 0.5;
// Two centres are the dimer's length apart within this many px, or this fraction of it.
inline constexpr double kDimerLengthTolerancePx = 1.0;
inline constexpr double kDimerLengthToleranceFraction = 0.01;

struct DimerPresence {
  size_t frames = 0;      // readable frames
  size_t dimer = 0;       // both spheres found, the dimer's length apart
  size_t both = 0;        // both found at any distance
  size_t one = 0;         // one found
  double length_px = 0;   // the median distance of the pairs
  bool seen() const { return frames > 0 && double(dimer) >= kMinDimerFraction * double(frames); }
};

DimerPresence MeasureDimerPresence(const SequenceResult& r);

// The one-line reason a film is refused ("no dimer ..."), naming what was found instead.
std::string NoDimerMessage(const DimerPresence& p);

}  // namespace dimer::tracking
