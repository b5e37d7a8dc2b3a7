#include "tracking/sphere/clipped_highlights.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "common/parallel_for.h"
#include "tracking/io/full_scale.h"
#include "tracking/sphere/fast_follow.h"

namespace dimer::tracking {
namespace {

// One sample registered both ways: the difference of the positions and of the variances.
struct Pair {
  bool ok = false;
  Eigen::Vector2d d{0, 0};
  bool has_delta = false;  // the variances stated (every kClipSigmaEvery-th sample)
  double delta = 0;
};

}  // namespace

Appearance ShiftContent(const Appearance& a, const Eigen::Vector2d& by) {
  // Lanczos, as the quick step shifts the appearance; the edge repeated as there.
  Appearance out = a;
  out.image = cv::Mat();  // a new image: `a`'s, shared by the copy, is left as it is
  const cv::Matx23d shift(1, 0, by.x(), 0, 1, by.y());
  cv::warpAffine(a.image, out.image, shift, a.image.size(), cv::INTER_LANCZOS4,
                 cv::BORDER_REPLICATE);
  return out;
}

cv::Mat ClippedZone(const LearntSphere& s, const std::vector<LearningSample>& samples) {
  const Appearance& a = s.appearance;
  const int size = 2 * a.half + 1;
  cv::Mat zone = cv::Mat::zeros(size, size, CV_8U);
  for (size_t i = 0; i < s.samples.size() && i < s.registered.size(); ++i) {
    const cv::Mat& frame = samples[s.samples[i]].image;
    const double level = kClipLevelFraction * FullScale(frame);
    // Appearance pixel u shows frame point u + origin: a clipped frame pixel x falls between
    // appearance pixels floor(x - origin) and the one after.
    const Eigen::Vector2d origin = s.registered[i] - Eigen::Vector2d(a.half, a.half);
    const int x0 = std::max(0, int(std::floor(origin.x())));
    const int y0 = std::max(0, int(std::floor(origin.y())));
    const int x1 = std::min(frame.cols - 1, int(std::ceil(origin.x())) + size - 1);
    const int y1 = std::min(frame.rows - 1, int(std::ceil(origin.y())) + size - 1);
    if (x1 < x0 || y1 < y0) continue;
    cv::Mat clipped;  // 255 where the frame is at the clip
    cv::compare(frame(cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1)), level, clipped, cv::CMP_GE);
    for (int y = y0; y <= y1; ++y) {
      const uint8_t* c = clipped.ptr<uint8_t>(y - y0);
      for (int x = x0; x <= x1; ++x) {
        if (!c[x - x0]) continue;
        const int u = int(std::floor(x - origin.x())), v = int(std::floor(y - origin.y()));
        for (int dv = 0; dv <= 1; ++dv) {
          for (int du = 0; du <= 1; ++du) {
            if (u + du >= 0 && u + du < size && v + dv >= 0 && v + dv < size) {
              zone.at<uint8_t>(v + dv, u + du) = 1;
            }
          }
        }
      }
    }
  }
  zone &= a.mask;
  const double reach = a.radius_px + kClipZoneMarginPx;
  for (int v = 0; v < size; ++v) {
    for (int u = 0; u < size; ++u) {
      if (std::hypot(u - a.half, v - a.half) > reach) zone.at<uint8_t>(v, u) = 0;
    }
  }
  return zone;
}

ClipDecision DecideClippedHighlights(const LearntSphere& s,
                                     const std::vector<LearningSample>& samples, int k,
                                     int threads) {
  ClipDecision out;
  out.appearance = s.appearance;
  const cv::Mat zone = ClippedZone(s, samples);
  out.zone_px = cv::countNonZero(zone);
  const char* side = k == 0 ? "left" : "right";
  if (out.zone_px == 0) {
    out.reason = std::string(side) + " sphere: no clipped highlight";
    return out;
  }
  Appearance cut = s.appearance;
  cut.mask = s.appearance.mask.clone();
  cut.mask.setTo(0, zone);
  const FollowModel whole = PrepareFollow(s.appearance), part = PrepareFollow(cut);
  std::vector<Pair> pairs(s.registered.size());
  ParallelFor(pairs.size(), threads, [&](size_t i) {
    const LearningSample& sample = samples[s.samples[i]];
    const MaskContext ctx = LearningContext(sample, k);
    const bool sigma = i % kClipSigmaEvery == 0;
    const std::optional<Located> in = FollowOnlyQuickly(
        sample.image, s.appearance, whole, s.registered[i], ctx, FollowStop{}, 0, sigma);
    const std::optional<Located> left_out =
        FollowOnlyQuickly(sample.image, cut, part, s.registered[i], ctx, FollowStop{}, 0, sigma);
    if (!in || !left_out) return;
    pairs[i].ok = true;
    pairs[i].d = left_out->position - in->position;
    if (sigma && in->sigma.allFinite() && left_out->sigma.allFinite()) {
      pairs[i].has_delta = true;
      pairs[i].delta = left_out->sigma.squaredNorm() - in->sigma.squaredNorm();
    }
  });
  size_t with_delta = 0;
  for (const Pair& p : pairs) {
    if (!p.ok) continue;
    ++out.n;
    out.mean_d2 += p.d.squaredNorm();
    out.mean_d += p.d;
    if (p.has_delta) ++with_delta, out.mean_delta += p.delta;
  }
  char numbers[256];
  if (out.n < kClipMinSamples || with_delta == 0) {  // nothing to weigh d by: kept
    std::snprintf(numbers, sizeof numbers,
                  " sphere: %d px shaped by clipping kept (%zu samples registered both ways, "
                  "%zu with variances)",
                  out.zone_px, out.n, with_delta);
    out.reason = side + std::string(numbers);
    return out;
  }
  out.mean_d2 /= double(out.n);
  out.mean_delta /= double(with_delta);
  out.mean_d /= double(out.n);
  // Delta <= 0: the clipped pixels add more mismatch than information (the residual's variance
  // in RegistrationSigma holds both), so leaving them out costs nothing.
  out.leave_out = out.mean_d2 > kClipLeaveOutRatio * std::max(0.0, out.mean_delta);
  std::snprintf(numbers, sizeof numbers,
                " sphere: %d px shaped by clipping %s (mean |d|^2 %.3g px^2 against %.3g from "
                "noise, mean d %+.4f, %+.4f px, %zu samples)",
                out.zone_px, out.leave_out ? "left out" : "kept", out.mean_d2, out.mean_delta,
                out.mean_d.x(), out.mean_d.y(), out.n);
  out.reason = side + std::string(numbers);
  if (out.leave_out) out.appearance = ShiftContent(cut, out.mean_d);
  return out;
}

}  // namespace dimer::tracking
