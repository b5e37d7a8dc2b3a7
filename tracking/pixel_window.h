#pragma once
// A square window of a frame, copied to float with the polarity applied (the sphere brighter
// than the background), shared by the refiners (centroid, disc fit) and the rim fit.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace dimer::tracking {

struct PixelWindow {
  int col0 = 0, row0 = 0, size = 0;  // top-left pixel and side, px
  std::vector<float> v;              // row-major, size x size
  float at(int x, int y) const { return v[size_t(y) * size + x]; }
};

// Copies the square of half-size `half` (side 2 half + 1) around the pixel nearest `centre`
// (col, row), 8- or 16-bit, times `polarity` (+1 or -1). False, leaving `w` unfilled, when the
// square leaves the frame (a clipped sphere). Reuses w's buffer.
bool ExtractWindow(const cv::Mat& frame, const Eigen::Vector2d& centre, int half, int polarity,
                   PixelWindow* w);

}  // namespace dimer::tracking
