#include "tracking/io/defect_pixels.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "tracking/io/full_scale.h"

namespace dimer::tracking {
namespace {

// Noise sigma of a frame: the median absolute difference of horizontal neighbours (every
// second row), / sqrt(2); at least the quantisation's.
double FrameNoise(const cv::Mat& f) {
  std::vector<float> d;
  d.reserve(size_t(f.rows / 2 + 1) * size_t(f.cols));
  for (int r = 0; r < f.rows; r += 2) {
    const float* p = f.ptr<float>(r);
    for (int c = 0; c + 1 < f.cols; ++c) d.push_back(std::abs(p[c + 1] - p[c]));
  }
  if (d.empty()) return 1.0;
  std::nth_element(d.begin(), d.begin() + std::ptrdiff_t(d.size() / 2), d.end());
  return std::max(1.4826 * d[d.size() / 2] / std::sqrt(2.0), 1.0 / std::sqrt(12.0));
}

}  // namespace

namespace {

// One round: the pixels standing out from all 8 neighbours, one way, in `need` frames or more.
std::vector<cv::Point> StandingOut(const std::vector<cv::Mat>& frames, double need) {
  // The 8 neighbours, not the pixel: their largest and smallest by one dilation and erosion
  // (a frame's edge reflected about its outer pixels, which are not their own neighbours).
  cv::Mat ring = cv::Mat::ones(3, 3, CV_8U);
  ring.at<uint8_t>(1, 1) = 0;
  cv::Mat count = cv::Mat::zeros(frames[0].size(), CV_16U);
  for (const cv::Mat& frame : frames) {
    cv::Mat f, hi, lo;
    frame.convertTo(f, CV_32F);
    const double limit = std::max(kDefectSigmas * FrameNoise(f),
                                  kDefectMinLevels * FullScale(frame) / 255.0);
    cv::dilate(f, hi, ring, {-1, -1}, 1, cv::BORDER_REFLECT_101);
    cv::erode(f, lo, ring, {-1, -1}, 1, cv::BORDER_REFLECT_101);
    const cv::Mat stuck = (f - hi > limit) | (lo - f > limit);
    cv::add(count, 1, count, stuck);
  }
  std::vector<cv::Point> at;
  for (int r = 0; r < count.rows; ++r) {
    const uint16_t* c = count.ptr<uint16_t>(r);
    for (int col = 0; col < count.cols; ++col) {
      if (c[col] >= need) at.emplace_back(col, r);
    }
  }
  return at;
}

// Rounds: a stuck pixel next to a brighter stuck one stands out only once that one is repaired.
constexpr int kDefectRounds = 3;

}  // namespace

DefectPixels FindDefectPixels(const std::vector<cv::Mat>& frames) {
  DefectPixels out;
  out.frames = frames.size();
  if (frames.size() < kMinDefectFrames) return out;
  const cv::Size size = frames[0].size();
  const double need = std::ceil(kDefectFrameFraction * double(frames.size()));
  const double most = kMaxDefectFraction * double(size.area());
  std::vector<cv::Mat> repaired = frames;
  DefectPixels found;
  found.mask = cv::Mat::zeros(size, CV_8U);
  for (int round = 0; round < kDefectRounds; ++round) {
    const std::vector<cv::Point> more = StandingOut(repaired, need);
    if (more.empty()) break;
    for (const cv::Point& p : more) {
      if (!found.mask.at<uint8_t>(p)) found.at.push_back(p), found.mask.at<uint8_t>(p) = 1;
    }
    if (double(found.at.size()) > most) {
      out.reason = std::to_string(found.at.size()) + " pixels or more stand out from all their " +
                   "neighbours in nearly every frame, more than a sensor's defects: taken for " +
                   "the scene, kept";
      return out;
    }
    for (size_t i = 0; i < repaired.size(); ++i) repaired[i] = RepairDefectPixels(frames[i], found);
  }
  if (found.at.empty()) return out;
  std::sort(found.at.begin(), found.at.end(), [](const cv::Point& a, const cv::Point& b) {
    return a.y != b.y ? a.y < b.y : a.x < b.x;
  });
  found.frames = out.frames;
  return found;
}

namespace {

// A stuck pixel's value: the mean of its sound opposite neighbours, pair by pair (left and
// right, above and below; the diagonals only where neither of those pairs is whole), a linear
// interpolation across it, exact where the image is locally a plane; the mean of whatever
// neighbours are sound where no pair is. A median of the 8 was tried first: on a highlight's
// flank it is off by tens of levels, and the templates registered around the repaired pixels
// moved tracks by up to 0.1 px (tests/tracking/io/defect_pixels_test.cc).
template <typename T>
void Repair(cv::Mat& img, const DefectPixels& d) {
  const cv::Mat& stuck = d.mask;
  auto sound = [&](int r, int c) {
    return r >= 0 && c >= 0 && r < img.rows && c < img.cols && !stuck.at<uint8_t>(r, c);
  };
  // (row, col) of one neighbour of each pair, the other opposite it: the direct pairs first.
  constexpr int kPairs[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
  for (const cv::Point& p : d.at) {
    double sum = 0;
    int n = 0;
    for (int k = 0; k < 4 && !(k == 2 && n > 0); ++k) {  // diagonals only without a direct pair
      const int dr = kPairs[k][0], dc = kPairs[k][1];
      if (sound(p.y + dr, p.x + dc) && sound(p.y - dr, p.x - dc)) {
        sum += double(img.at<T>(p.y + dr, p.x + dc)) + double(img.at<T>(p.y - dr, p.x - dc));
        n += 2;
      }
    }
    if (n == 0) {  // no whole pair: whatever neighbours are sound
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if ((dr || dc) && sound(p.y + dr, p.x + dc)) sum += img.at<T>(p.y + dr, p.x + dc), ++n;
        }
      }
    }
    if (n == 0) continue;  // a block of stuck pixels: nothing sound to take
    img.at<T>(p) = cv::saturate_cast<T>(sum / n);
  }
}

}  // namespace

cv::Mat RepairDefectPixels(const cv::Mat& frame, const DefectPixels& defects) {
  if (defects.at.empty() || frame.size() != defects.mask.size()) return frame;
  cv::Mat out = frame.clone();
  // Only stuck pixels are written, and they are never read as neighbours: the result does not
  // depend on the order of repair.
  if (frame.depth() == CV_8U) {
    Repair<uint8_t>(out, defects);
  } else {
    Repair<uint16_t>(out, defects);
  }
  return out;
}

}  // namespace dimer::tracking
