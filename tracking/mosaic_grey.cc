#include "tracking/mosaic_grey.h"

#include <opencv2/imgproc.hpp>

#include <stdexcept>

namespace dimer::tracking {

cv::Mat MosaicToGrey(const cv::Mat& raw) {
  if (raw.type() != CV_8UC1 && raw.type() != CV_16UC1) {
    throw std::invalid_argument("MosaicToGrey: expected an 8- or 16-bit single-channel mosaic");
  }
  const cv::Mat k = (cv::Mat_<float>(1, 3) << 0.25f, 0.5f, 0.25f);
  cv::Mat sum;
  cv::sepFilter2D(raw, sum, CV_32F, k, k, cv::Point(-1, -1), 0, cv::BORDER_REFLECT_101);
  cv::Mat grey;
  sum.convertTo(grey, raw.type());  // rounded to the nearest level, saturated
  return grey;
}

}  // namespace dimer::tracking
