#include "tracking/method_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// Median and robust spread (1.4826 MAD) of a sample.
std::pair<double, double> MedianSpread(std::vector<double> v) {
  if (v.empty()) return {0, 0};
  auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double med = *mid;
  for (double& x : v) x = std::abs(x - med);
  std::nth_element(v.begin(), mid, v.end());
  return {med, 1.4826 * *mid};
}

}  // namespace

bool CleanSilhouette(const cv::Mat& frame, const Eigen::Vector2d& centre, double radius_px,
                     const Eigen::Vector2d& other, double plate_row) {
  std::vector<double> in, out;
  const Eigen::Vector2d dir =
      (other - centre).norm() > 0 ? Eigen::Vector2d((other - centre).normalized()) : Eigen::Vector2d(0, 0);
  const double reach = radius_px + kRingInnerPx + kRingWidthPx;
  const double rod_half = kRodCorridorHalfWidthR * radius_px;
  for (int y = int(std::floor(centre.y() - reach)); y <= int(std::ceil(centre.y() + reach)); ++y) {
    if (y < 0 || y >= frame.rows) continue;
    if (std::isfinite(plate_row) && y > plate_row - kPlateGuardPx) continue;
    for (int x = int(std::floor(centre.x() - reach)); x <= int(std::ceil(centre.x() + reach)); ++x) {
      if (x < 0 || x >= frame.cols) continue;
      const Eigen::Vector2d d(x - centre.x(), y - centre.y());
      if (d.dot(dir) > 0 && std::abs(d.x() * dir.y() - d.y() * dir.x()) < rod_half) continue;
      const double r = d.norm() - radius_px;
      const double v = frame.depth() == CV_8U ? frame.at<uint8_t>(y, x) : frame.at<uint16_t>(y, x);
      const double rr = d.norm() / radius_px;
      if (rr >= kBodyInnerR && rr <= kBodyOuterR) in.push_back(v);
      if (r >= kRingInnerPx && r < kRingInnerPx + kRingWidthPx) out.push_back(v);
    }
  }
  if (in.size() < 16 || out.size() < 16) return false;
  const auto [in_level, in_spread] = MedianSpread(in);
  const auto [out_level, out_spread] = MedianSpread(out);
  const double floor = frame.depth() == CV_8U ? 1.0 : 256.0;  // quantisation: one 8-bit level
  return std::abs(in_level - out_level) >=
         kCleanContrastToSpread * std::max({in_spread, out_spread, floor});
}

MethodChoice ChooseMethod(const std::vector<FrameTrack>& probes,
                          const std::vector<std::array<bool, 2>>& clean, Method requested) {
  size_t total = 0, uniform = 0, mirror = 0;
  for (size_t i = 0; i < probes.size(); ++i) {
    const FrameTrack& f = probes[i];
    for (int k = 0; k < 2; ++k) {
      ++total;
      if (f.found[k] && !clean[i][k]) ++mirror;
      if (f.found[k] && clean[i][k]) ++uniform;
    }
  }
  MethodChoice c;
  c.silhouettes = total > 0 && double(uniform) >= kAutoUniformFraction * double(total);
  char evidence[200];
  std::snprintf(evidence, sizeof evidence,
                "%zu of %zu sphere measurements in %zu learning frames are clean silhouettes, "
                "%zu not, %zu not found",
                uniform, total, probes.size(), mirror, total - uniform - mirror);
  if (requested != Method::kAuto) {
    c.method = requested;
    c.reason = std::string("requested; ") + evidence;
  } else if (c.silhouettes) {
    c.method = Method::kCentroid;
    c.reason = std::string("clean silhouettes, the centroid is unbiased: ") + evidence;
  } else {
    c.method = Method::kTemplate;
    c.reason = std::string("not clean silhouettes (mirror-lit or hard to see), appearance learnt "
                           "from the footage: ") + evidence;
  }
  return c;
}

}  // namespace dimer::tracking
