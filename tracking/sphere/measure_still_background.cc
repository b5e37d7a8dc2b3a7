#include "tracking/sphere/measure_still_background.h"

#include <cmath>
#include <limits>

#include "common/median.h"
#include "tracking/sphere/precision_bound.h"

namespace dimer::tracking {

std::shared_ptr<const StillBackground> MeasureStillBackground(
    const std::vector<LearningSample>& samples, double radius_px) {
  if (samples.size() < size_t(kStillMinFrames) || samples[0].image.empty() ||
      !(radius_px > 0)) {
    return nullptr;
  }
  const double noise = FrameNoiseSigma(samples[0].image);
  if (!(noise > 0)) return nullptr;
  const cv::Size size = samples[0].image.size();
  std::vector<cv::Mat> frames;
  for (const LearningSample& s : samples) {
    if (s.image.size() != size) return nullptr;
    cv::Mat f;
    s.image.convertTo(f, CV_32F);
    frames.push_back(f);
  }
  const double cover = kStillCoverRadii * radius_px;
  const double cover2 = cover * cover;
  auto out = std::make_shared<StillBackground>();
  out->spread = kStillBackgroundSpread * noise;
  out->level = cv::Mat(size, CV_32F, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  int told = 0;
  std::vector<double> v, dev;
  for (int r = 0; r < size.height; ++r) {
    float* level = out->level.ptr<float>(r);
    for (int c = 0; c < size.width; ++c) {
      v.clear();
      for (size_t i = 0; i < samples.size(); ++i) {
        bool shown = true;
        for (int k = 0; k < 2 && shown; ++k) {
          if (!samples[i].found[k]) continue;
          const double dx = c - samples[i].centre[k].x(), dy = r - samples[i].centre[k].y();
          shown = dx * dx + dy * dy > cover2;
        }
        if (shown) v.push_back(frames[i].at<float>(r, c));
      }
      if (v.size() < size_t(kStillMinFrames)) continue;
      const double median = MedianOf(v);
      dev.clear();
      for (double x : v) dev.push_back(std::abs(x - median));
      if (1.4826 * MedianOf(dev) > kStillPixelNoise * noise) continue;
      level[c] = float(median);
      ++told;
    }
  }
  if (told == 0) return nullptr;
  return out;
}

}  // namespace dimer::tracking
