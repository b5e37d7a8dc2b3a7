#pragma once
// The free-fall acceleration fitted from the track: a calibration check. While both spheres
// are in the air the centre of mass is a parabola z = z0 + v t - g t^2 / 2 in the lab frame,
// whatever the dimer's spin, so each such flight of >= kMinFreeFlightFrames frames gives g with
// a least-squares error; flights are combined by inverse variance. g_fit / g - 1 measures the
// m/px calibration error (the time base is the camera's). In the drift mode one end is always
// on the plate, so there is no free flight and g_fit is NaN, with the reason.
#include <string>

#include "compare/contacts.h"
#include "compare/sampled_run.h"

namespace dimer::compare {

inline constexpr int kMinFreeFlightFrames = 10;
inline constexpr int kFreeFlightTrimFrames = 1;  // frames dropped at each end (impacts, blur)

struct FreeFall {
  double g_fit = kNaN, g_fit_err = kNaN;  // m/s^2
  int flights = 0, frames = 0;
  std::string note;  // why it is NaN, when it is
};

FreeFall FitFreeFall(const SampledRun& run, const Contacts& contacts);

}  // namespace dimer::compare
