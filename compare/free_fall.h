#pragma once
// The free-fall acceleration fitted from the track: a calibration check. While both spheres
// are in the air the centre of mass is a parabola z = z0 + v t - g t^2 / 2 in the lab frame,
// whatever the dimer's spin, so each such flight of >= kMinFreeFlightFrames frames gives g with
// a least-squares error; flights are combined by inverse variance. g_fit / g - 1 measures the
// m/px calibration error (the time base is the camera's). In the drift mode one end is always
// on or next to the plate, so there is no such flight and g_fit is NaN, with the reason.
#include <string>

#include "compare/contacts.h"
#include "compare/sampled_run.h"

namespace dimer::compare {

inline constexpr int kMinFreeFlightFrames = 10;
inline constexpr int kFreeFlightTrimFrames = 1;  // frames dropped at each end (impacts, blur)
// Frames count only while both spheres are this far (fraction of d) above the plate: next to
// the plate a tracker's error depends on the height (the plate edge, its reflection), which
// bends short flights; measured: the drift mode's sub-millimetre hops gave g_fit/g 0.97-0.99 on
// rendered footage whose calibration was exact.
// The centre of mass's acceleration along x is fitted alike. In the plate's frame (a tilted
// plate's track or simulation) a flight falls at g (-sin alpha, -cos alpha), so the two give the
// plate's tilt alpha against gravity, and g_fit is the length of that vector. It tells a plate
// tilted on purpose from a camera that is not level (whose track, turned to the plate, is level).
inline constexpr double kFreeFlightMinGapRel = 0.05;

struct FreeFall {
  double g_fit = kNaN, g_fit_err = kNaN;  // m/s^2
  double tilt_deg = kNaN, tilt_deg_err = kNaN;  // plate tilt against gravity, > 0 rising toward +x
  int flights = 0, frames = 0;
  std::string note;  // why it is NaN, when it is
};

FreeFall FitFreeFall(const SampledRun& run, const Contacts& contacts);

}  // namespace dimer::compare
