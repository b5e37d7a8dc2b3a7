#include "tracking/calibration.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/median.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Found radii used for the diameter calibration (a median over this many is plenty).
constexpr size_t kCalibrationSamples = 2000;

}  // namespace

Calibration Calibrate(const TrackArgs& args, const SequenceResult& r, const LengthScale& passes) {
  Calibration cal;
  cal.m_per_px = args.m_per_px.value_or(std::numeric_limits<double>::quiet_NaN());
  cal.row0 = args.row0.value_or(std::numeric_limits<double>::quiet_NaN());
  cal.length_scale = passes;
  if (args.ar) cal.length_px = MedianDimerLength(r.frames, &cal.length_frames);
  if (std::isnan(cal.m_per_px) && args.ar) {
    if (!std::isfinite(cal.length_px)) {
      throw InputError(args.input + ": cannot take the scale from the dimer's length (--ar): " +
                       std::to_string(cal.length_frames) + " frames show both spheres (" +
                       std::to_string(kLengthScaleMinFrames) + " needed); pass --m-per-px");
    }
    cal.m_per_px = ScaleFromDimerLength(cal.length_px, *args.ar, args.diameter);
  } else if (std::isnan(cal.m_per_px)) {
    std::vector<double> radii;
    for (const auto& f : r.frames) {
      for (int k = 0; k < 2 && radii.size() < kCalibrationSamples; ++k) {
        if (f.found[k]) radii.push_back(f.radius_px[k]);
      }
    }
    const double radius = FiniteMedian(radii);
    if (!std::isfinite(radius)) {
      throw InputError(args.input +
                       ": no sphere found, cannot calibrate; pass --m-per-px, or --ar with the "
                       "dimer's aspect ratio");
    }
    cal.m_per_px = args.diameter / (2.0 * radius);
  }
  const double slope = r.plate_slope.value;
  if (slope != 0) {
    cal.col0 = 0.5 * (r.width - 1);
    const double a = std::atan(slope);
    cal.cos_a = std::cos(a);
    cal.sin_a = std::sin(a);
  }
  if (std::isnan(cal.row0)) {
    std::vector<double> rows;
    for (const auto& f : r.frames) rows.push_back(f.PlateRowAt(cal.col0));
    cal.row0 = FiniteMedian(rows);
    if (std::isnan(cal.row0)) cal.row0 = r.height - 0.5;  // no plate seen: bottom of the frame
  }
  return cal;
}

}  // namespace dimer::tracking
