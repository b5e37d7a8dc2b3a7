#pragma once
// A square window of a frame, copied to float with the polarity applied (the sphere brighter
// than the background), shared by the refiners (centroid, disc fit) and the rim fit.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

namespace dimer::tracking {

struct PixelWindow {
  int col0 = 0, row0 = 0, size = 0;  // top-left pixel and side, px
  std::vector<float> v;              // row-major, size x size
  float at(int x, int y) const { return v[size_t(y) * size + x]; }
};

// A sphere near the frame's edge is measured when its disc and this many px around it are in
// the frame: the window's part beyond the edge repeats the frame's edge pixels, which are
// then background (Tracker.ASphereAtTheFramesEdgeIsMeasured).
inline constexpr double kEdgeGuardPx = 2.0;

// Copies the square of half-size `half` (side 2 half + 1) around the pixel nearest `centre`
// (col, row), 8- or 16-bit, times `polarity` (+1 or -1). False, leaving `w` unfilled, when the
// square of half-size `inside` (<= half) about that pixel leaves the frame (a clipped sphere);
// the rest of the window beyond the frame repeats its nearest edge pixel. `inside` < 0: the
// whole window must be inside. Reuses w's buffer.
bool ExtractWindow(const cv::Mat& frame, const Eigen::Vector2d& centre, int half, int polarity,
                   PixelWindow* w, int inside = -1);

// The half-size that must be inside the frame for a sphere of `radius` px (its disc and
// kEdgeGuardPx), at most `half`.
inline int InsideHalf(double radius, int half) {
  return std::min(half, int(std::ceil(radius + kEdgeGuardPx)));
}

// Visits the pixels of `w` whose centres lie between the circles of radii `inner` and `outer`
// about `c` (frame coordinates): per row, only the columns between the two circles on each
// side, so a thin band costs its own area and not the window's. Rows where row_ok(dy) is false
// are skipped whole. Calls f(x, y, dx, dy) with window indices and the offset from `c`; the
// callers apply their own exact band test (pixels on the circles' rows may be slightly out).
template <typename RowOk, typename F>
void ForEachAnnulusPixel(const PixelWindow& w, const Eigen::Vector2d& c, double inner,
                         double outer, RowOk&& row_ok, F&& f) {
  const double outer2 = outer * outer, inner2 = inner * inner;
  const int y0 = std::max(0, int(std::ceil(c.y() - outer)) - w.row0);
  const int y1 = std::min(w.size - 1, int(std::floor(c.y() + outer)) - w.row0);
  for (int y = y0; y <= y1; ++y) {
    const double dy = (w.row0 + y) - c.y();
    if (!row_ok(dy)) continue;
    const double half_outer = std::sqrt(std::max(0.0, outer2 - dy * dy));
    const double half_inner = dy * dy < inner2 ? std::sqrt(inner2 - dy * dy) : -1.0;
    const int x0 = std::max(0, int(std::ceil(c.x() - half_outer)) - w.col0);
    const int x1 = std::min(w.size - 1, int(std::floor(c.x() + half_outer)) - w.col0);
    for (int x = x0; x <= x1; ++x) {
      const double dx = (w.col0 + x) - c.x();
      if (std::abs(dx) < half_inner) {  // inside the inner circle: jump to its far side
        x = std::max(x, int(std::floor(c.x() + half_inner)) - w.col0);
        continue;
      }
      f(x, y, dx, dy);
    }
  }
}

}  // namespace dimer::tracking
