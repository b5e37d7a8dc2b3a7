#include "tracking/plate_slope.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "tracking/sphere/detector.h"
#include "common/median.h"
#include "tracking/plate/plate_edge.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// Columns left out about each detected sphere, in its detected radius: the detection's radius
// of a front-lit steel sphere can be short by half (its highlights), and its centre 10 px off.
constexpr double kSlopeExcludeR = 1.6;

}  // namespace

PlateSlope EstimatePlateSlope(const std::vector<cv::Mat>& frames, int polarity) {
  PlateSlope out;
  if (frames.empty()) {
    out.reason = "no frames";
    return out;
  }
  const size_t n = std::min(frames.size(), kSlopeFrames);
  std::vector<double> slopes, errs;
  const int width = frames[0].cols;
  for (size_t j = 0; j < n; ++j) {
    const cv::Mat& f = frames[j * frames.size() / n];
    const Detection det = DetectSpheres(f, polarity);
    std::vector<std::pair<double, double>> excluded;
    for (size_t k = 0; k < det.centres.size(); ++k) {
      const double r = kSlopeExcludeR * det.radii_px[k] + kPlateSphereClearPx;
      excluded.emplace_back(det.centres[k].x() - r, det.centres[k].x() + r);
    }
    double err = 0;
    const double s = PlateEdgeSlope(f, excluded, &err);
    if (!std::isfinite(s) || !std::isfinite(err)) continue;
    slopes.push_back(s);
    errs.push_back(err);
  }
  out.frames = slopes.size();
  if (slopes.empty()) {
    out.reason = "no plate edge to measure it on";
    return out;
  }
  out.measured = MedianOf(slopes);
  // The median's uncertainty: from the frames' scatter when there are several (the plate's row
  // noise and what each frame's blocks miss), never below a single frame's own error / sqrt(n).
  std::vector<double> dev;
  for (double s : slopes) dev.push_back(std::abs(s - out.measured));
  const double scatter =
      slopes.size() > 2 ? 1.2533 * 1.4826 * MedianOf(dev) / std::sqrt(double(slopes.size())) : 0.0;
  out.err = std::max(scatter, MedianOf(errs) / std::sqrt(double(slopes.size())));
  const double effect = std::abs(out.measured) * (width - 1);
  char buf[200];
  if (effect < kMinSlopeEffectPx) {
    std::snprintf(buf, sizeof buf, "level: %.3f px across the frame, under %.2f", effect,
                  kMinSlopeEffectPx);
  } else if (std::abs(out.measured) < kMinSlopeSigmas * out.err) {
    std::snprintf(buf, sizeof buf,
                  "not taken: %.3g +- %.2g rows per column is within %.0f sigma of level",
                  out.measured, out.err, kMinSlopeSigmas);
  } else {  // (PlateEdgeSlope gives none steeper than kPlateMaxSlope)
    out.applied = true;
    out.value = out.measured;
    std::snprintf(buf, sizeof buf, "the edge falls %.2f px across the frame (%.3f deg)", effect,
                  std::atan(out.measured) * 180.0 / std::numbers::pi);
  }
  out.reason = buf;
  return out;
}

}  // namespace dimer::tracking
