#pragma once
// The brightest level a frame's pixels can hold: 255 for 8-bit frames, 65535 for 16-bit ones
// (the only depths frames come in as, frame_source.h). Thresholds that are fractions of the
// range scale by it.
#include <opencv2/core.hpp>

namespace dimer::tracking {

inline double FullScale(const cv::Mat& frame) { return frame.depth() == CV_8U ? 255.0 : 65535.0; }

}  // namespace dimer::tracking
