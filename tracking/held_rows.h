#pragma once
// The rows refereed by what a sphere can do: rest on the plate, moving with it, or fly, falling
// under gravity. Its rows cannot stand still while the plate under it moves. Something that
// stands still behind a sphere (a ruler's or a backdrop's edge) can hold a learnt appearance
// where the learning's referees could not tell (the plate's needs frames it recognises as
// resting, detection_agreement.h rough centres that move): on POV-Ray ruler_above_plate
// rendered to 100 frames and learnt at the first frame's radius, 26.0 px against 23.75 (without
// the scale; track_sequence.cc learns such a film again at its outline's radius), the resting
// left sphere's rows stayed within 0.39 px while the plate moved 2.47 px, 11.8 px above their
// truth, and the track said nothing of it (HeldRows.RowsThatNeitherRestNorFallAreHeld).
//
// The track is cut into windows long enough for a sphere in free flight to drop kHeldFallPx from
// its apex at the window's middle to either end. In a window where the plate under the sphere
// moves by kHeldMinPlateExcursionPx or more (between its kHeldPlateQuantile and 1 - that), rows
// whose range is under kHeldFraction of both the plate's excursion (a resting sphere's rows move
// with it, within ~15 % where the edge seen is nearer or further than the dimer:
// plate_contact.h) and that drop (a flight's rows move by at least it) are held.
#include <cstddef>
#include <limits>
#include <vector>

namespace dimer::tracking {

inline constexpr double kHeldFallPx = 5.0;
inline constexpr double kHeldMinPlateExcursionPx = 1.0;
inline constexpr double kHeldFraction = 0.25;
// The plate's excursion in a window is read between these quantiles of its rows.
inline constexpr double kHeldPlateQuantile = 0.1;

struct HeldRows {
  size_t window_frames = 0;  // frames a window; 0: none fits the track (or gravity unknown)
  size_t windows = 0;        // windows judged: the sphere found in all their frames, the plate
                             // moving by kHeldMinPlateExcursionPx or more
  size_t held = 0;           // of those, held
  // The held window whose rows moved least against the plate's excursion (NaN: none held).
  size_t first = 0;  // its first frame (index into the track)
  double row_range = std::numeric_limits<double>::quiet_NaN();    // px
  double plate_range = std::numeric_limits<double>::quiet_NaN();  // px
};

// `rows` one sphere's row per frame (NaN: not found), `plate` the plate's row under it, and
// `gravity_px` gravity in px per frame^2 (NaN or <= 0: not judged).
HeldRows FindHeldRows(const std::vector<double>& rows, const std::vector<double>& plate,
                      double gravity_px);

}  // namespace dimer::tracking
