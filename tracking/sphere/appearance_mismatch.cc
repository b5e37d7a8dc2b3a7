#include "tracking/sphere/appearance_mismatch.h"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <limits>

#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {
namespace {

// Pixels this close to a mask's edge are left out: the Lanczos kernel that shifts `to` reaches
// 4 px, and would mix in the mean level the unknown pixels hold.
constexpr int kInterpolationReachPx = 4;

// Per-pixel variance of the mean appearance from its jackknife (g - 1) / g * sum (a_j - mean)^2
// over the g left-out appearances that could be learnt, and where every one of them knows the
// pixel (CV_8U). False with fewer than 3.
bool JackknifeVariance(const LearntSphere& s, cv::Mat* variance, cv::Mat* known) {
  const cv::Size size = s.appearance.image.size();
  cv::Mat sum = cv::Mat::zeros(size, CV_64F), sum2 = cv::Mat::zeros(size, CV_64F);
  *known = s.appearance.mask > 0;
  cv::Mat a;
  int g = 0;
  for (const Appearance& j : s.jackknife) {
    // A group whose leaving-out left too few samples has no appearance.
    if (!j.valid() || j.image.size() != size) continue;
    j.image.convertTo(a, CV_64F);
    sum += a;
    sum2 += a.mul(a);
    *known &= j.mask > 0;
    ++g;
  }
  if (g < 3) return false;
  // sum (a_j - mean)^2 = sum2 - sum^2 / g.
  *variance = (sum2 - sum.mul(sum) / double(g)) * (double(g - 1) / double(g));
  return true;
}

}  // namespace

double AppearanceMismatch(const LearntSphere& from, const LearntSphere& to) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const Appearance& f = from.appearance;
  const Appearance& t = to.appearance;
  if (!f.valid() || !t.valid() || f.image.size() != t.image.size()) return kNaN;
  const cv::Mat both = f.mask & t.mask;
  Eigen::Vector2d shift(0, 0);
  if (!RegisterTranslation(f.image, t.image, both, &shift)) return kNaN;
  // to(x + shift) on from's grid.
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, shift.x(), 0, 1, shift.y());
  cv::Mat moved;
  cv::warpAffine(t.image, moved, m, t.image.size(), cv::INTER_LANCZOS4 | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
  cv::Mat var_f, var_t, known_f, known_t;
  if (!JackknifeVariance(from, &var_f, &known_f) || !JackknifeVariance(to, &var_t, &known_t)) {
    return kNaN;
  }
  // `to`'s own pixels move with the shift; its variance is read at the nearest of them.
  cv::Mat var_t_moved, known_t_moved;
  cv::warpAffine(var_t, var_t_moved, m, t.image.size(), cv::INTER_NEAREST | cv::WARP_INVERSE_MAP,
                 cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::warpAffine(known_t, known_t_moved, m, t.image.size(),
                 cv::INTER_NEAREST | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat used = both & known_f & known_t_moved;
  const int k = 2 * kInterpolationReachPx + 1;
  cv::erode(used, used, cv::Mat::ones(k, k, CV_8U), cv::Point(-1, -1), 1, cv::BORDER_CONSTANT,
            cv::Scalar(0));
  double squares = 0, noise = 0;
  for (int y = 0; y < used.rows; ++y) {
    for (int x = 0; x < used.cols; ++x) {
      if (!used.at<uint8_t>(y, x)) continue;
      const double r = double(moved.at<float>(y, x)) - double(f.image.at<float>(y, x));
      squares += r * r;
      noise += var_f.at<double>(y, x) + var_t_moved.at<double>(y, x);
    }
  }
  return noise > 0 ? squares / noise : kNaN;
}

}  // namespace dimer::tracking
