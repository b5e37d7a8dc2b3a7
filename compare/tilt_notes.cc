#include "compare/tilt_notes.h"

#include <cmath>
#include <numbers>

#include "compare/text.h"

namespace dimer::compare {

std::vector<std::string> TiltNotes(const Analysis& track, double sim_tilt_deg) {
  std::vector<std::string> notes;
  const SampledRun& r = track.run;
  if (r.kind == "track" && r.plate_slope != 0) {
    notes.push_back("the plate's edge slopes by " + Num(-std::atan(r.plate_slope) * 180 / std::numbers::pi) +
                    " deg in the frames (> 0 rising toward +x): x and z run along the plate and its normal. "
                    "A camera not level looks the same; if the plate itself was tilted, simulate it with "
                    "--tilt-deg (the flights' tilt, in the summary, tells the two apart)");
  }
  const FreeFall& f = track.free_fall;
  if (std::isfinite(sim_tilt_deg) && std::isfinite(f.tilt_deg)) {
    const double off = f.tilt_deg - sim_tilt_deg;
    if (std::abs(off) > kTiltNoteDeg && std::abs(off) > 3 * f.tilt_deg_err) {
      notes.push_back("the track's flights fall " + Num(f.tilt_deg) + " +- " + Num(f.tilt_deg_err) +
                      " deg from the plate's normal (the plate's tilt against gravity), the simulation's plate "
                      "is tilted " + Num(sim_tilt_deg) + " deg (--tilt-deg, or the sim file's)");
    }
  }
  return notes;
}

}  // namespace dimer::compare
