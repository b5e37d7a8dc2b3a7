#include "tracking/sphere/masked_correlation.h"

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

#include "common/check.h"

namespace dimer::tracking {
namespace {

// One template row over its mask's extent: the template less its masked mean, times the mask,
// and the mask, as floats (the dot products below are then plain and vectorised).
struct MaskedRow {
  int y = 0, x0 = 0;
  Eigen::VectorXf t, m;
};

}  // namespace

void MaskedCorrelation(const cv::Mat& image, const cv::Mat& templ, const cv::Mat& mask,
                       cv::Mat* res) {
  DIMER_CHECK(image.type() == CV_32F && templ.type() == CV_32F && mask.type() == CV_8U &&
                  mask.size() == templ.size() && image.rows >= templ.rows &&
                  image.cols >= templ.cols,
              "MaskedCorrelation: CV_32F image at least the CV_32F template's size, CV_8U mask");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  res->create(image.rows - templ.rows + 1, image.cols - templ.cols + 1, CV_32F);
  double n = 0, sum_t = 0;
  for (int y = 0; y < templ.rows; ++y) {
    for (int x = 0; x < templ.cols; ++x) {
      if (mask.at<uint8_t>(y, x)) n += 1, sum_t += templ.at<float>(y, x);
    }
  }
  if (n < 2) {
    res->setTo(nan);
    return;
  }
  const double mean_t = sum_t / n;
  std::vector<MaskedRow> rows;
  double stt = 0;
  for (int y = 0; y < templ.rows; ++y) {
    const uint8_t* mr = mask.ptr<uint8_t>(y);
    int x0 = 0, x1 = templ.cols;
    while (x0 < x1 && !mr[x0]) ++x0;
    while (x1 > x0 && !mr[x1 - 1]) --x1;
    if (x0 == x1) continue;
    MaskedRow r;
    r.y = y;
    r.x0 = x0;
    r.t.resize(x1 - x0);
    r.m.resize(x1 - x0);
    for (int x = x0; x < x1; ++x) {
      const double t = mr[x] ? templ.at<float>(y, x) - mean_t : 0.0;
      r.t(x - x0) = float(t);
      r.m(x - x0) = mr[x] ? 1.0f : 0.0f;
      stt += t * t;
    }
    rows.push_back(std::move(r));
  }
  // The image less its mean level (the coefficient does not depend on it): its squares' sums
  // then hold the contrast, not the level, in float (16-bit frames' levels reach 65,535).
  const float level = float(cv::mean(image)[0]);
  cv::Mat centred, squared;
  image.convertTo(centred, CV_32F, 1.0, -level);
  cv::multiply(centred, centred, squared);
  for (int py = 0; py < res->rows; ++py) {
    float* out = res->ptr<float>(py);
    for (int px = 0; px < res->cols; ++px) {
      double sti = 0, si = 0, sii = 0;
      for (const MaskedRow& r : rows) {
        const int len = int(r.t.size());
        const Eigen::Map<const Eigen::VectorXf> v(centred.ptr<float>(py + r.y) + px + r.x0, len);
        const Eigen::Map<const Eigen::VectorXf> v2(squared.ptr<float>(py + r.y) + px + r.x0, len);
        sti += r.t.dot(v);
        si += r.m.dot(v);
        sii += r.m.dot(v2);
      }
      const double var = sii - si * si / n;
      out[px] = var > 0 && stt > 0 ? float(sti / std::sqrt(stt * var)) : nan;
    }
  }
}

}  // namespace dimer::tracking
