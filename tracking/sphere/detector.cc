#include "tracking/sphere/detector.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "tracking/io/full_scale.h"
#include "tracking/plate/plate_edge.h"
#include "tracking/plate/plate_under_dimer.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// Pixel stride of the polarity sample: 1/16 of the pixels is plenty for three quantiles.
constexpr int kPolarityStride = 4;
// Smallest sphere radius the detector accepts, px (smaller blobs are noise or debris).
constexpr double kMinRadiusPx = 3.0;
// Silhouette threshold above the background: noise sigmas (4: ~3e-5 of the background pixels
// pass, isolated specks with no distance-transform peak) and a floor, fraction of full scale.
constexpr double kSilhouetteNoiseSigmas = 4.0;
constexpr double kSilhouetteMinStepFraction = 0.02;

// Silhouette threshold: the background (median) plus kSilhouetteNoiseSigmas noise sigmas
// (from the median absolute deviation), at least kSilhouetteMinStepFraction of full scale.
// Not Otsu: a mirror sphere's rim is only ~12 grey levels above the background while its
// lower half reflects the bright plate, and Otsu's split between those leaves the dim upper
// part out, which moves the distance-transform peak by several pixels.
double SilhouetteThreshold(const cv::Mat& region, double full) {
  std::vector<float> v;
  for (int r = 0; r < region.rows; r += kPolarityStride) {
    const float* p = region.ptr<float>(r);
    for (int c = 0; c < region.cols; c += kPolarityStride) v.push_back(p[c]);
  }
  auto median = [](std::vector<float>& x) {
    std::nth_element(x.begin(), x.begin() + x.size() / 2, x.end());
    return double(x[x.size() / 2]);
  };
  const double m = median(v);
  for (float& x : v) x = std::abs(x - float(m));
  const double sigma = 1.4826 * median(v);
  return m + std::max(kSilhouetteNoiseSigmas * sigma, kSilhouetteMinStepFraction * full);
}

}  // namespace

int DetectPolarity(const cv::Mat& frame) {
  std::vector<double> v;
  for (int r = 0; r < frame.rows; r += kPolarityStride) {
    for (int c = 0; c < frame.cols; c += kPolarityStride) {
      v.push_back(frame.depth() == CV_8U ? frame.at<uint8_t>(r, c) : frame.at<uint16_t>(r, c));
    }
  }
  auto quantile = [&](double q) {
    auto it = v.begin() + std::ptrdiff_t(q * double(v.size() - 1));
    std::nth_element(v.begin(), it, v.end());
    return *it;
  };
  const double lo = quantile(0.01), med = quantile(0.5), hi = quantile(0.99);
  return (hi - med) >= (med - lo) ? 1 : -1;
}

namespace {

// The top of the silhouette's blob over `at`: the boundary above the first row up the column
// that is background. Unlike the distance-transform circle, it does not move where an edge
// across the frame cuts the sphere's lower part off or joins a band to it.
double TopRow(const cv::Mat& silhouette, const cv::Point& at) {
  int row = at.y;
  while (row > 0 && silhouette.at<uint8_t>(row - 1, at.x) != 0) --row;
  return row - 0.5;
}

// The spheres above out->plate_row (the band under it left out), into out->centres and radii_px.
void FindSpheresAbove(const cv::Mat& frame, int polarity, double slope, Detection* det) {
  Detection& out = *det;
  // The plate and a guard band above it are left out of the silhouette: under the plate's
  // line, which slopes across the frame by `slope` rows per column.
  const double centre = 0.5 * (frame.cols - 1), half_drop = std::abs(slope) * centre;
  int rows = frame.rows, clear_rows = frame.rows;  // above the plate's lowest / highest point
  if (std::isfinite(out.plate_row)) {
    rows = std::clamp(int(out.plate_row + half_drop - kPlateGuardPx), 0, frame.rows);
    clear_rows = std::clamp(int(out.plate_row - half_drop - kPlateGuardPx), 0, frame.rows);
  }
  if (rows < 2 * kMinRadiusPx) return;
  cv::Mat region;
  frame.rowRange(0, rows).convertTo(region, CV_32F, polarity);
  // The threshold from the rows clear of the plate in every column (when there are enough).
  const cv::Mat clear = clear_rows >= 2 * kMinRadiusPx ? region.rowRange(0, clear_rows) : region;
  cv::Mat silhouette;
  cv::threshold(region, silhouette, SilhouetteThreshold(clear, FullScale(frame)), 255,
                cv::THRESH_BINARY);
  silhouette.convertTo(silhouette, CV_8U);
  if (slope != 0 && std::isfinite(out.plate_row)) {
    for (int c = 0; c < silhouette.cols; ++c) {
      const int first = std::max(0, int(out.plate_row + slope * (c - centre) - kPlateGuardPx));
      for (int r = first; r < silhouette.rows; ++r) silhouette.at<uint8_t>(r, c) = 0;
    }
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(silhouette, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  silhouette.setTo(0);
  cv::drawContours(silhouette, contours, -1, cv::Scalar(255), cv::FILLED);
  cv::Mat dist;
  cv::distanceTransform(silhouette, dist, cv::DIST_L2, cv::DIST_MASK_5);  // coarse is enough
  double first_peak = 0;
  for (int k = 0; k < 2; ++k) {
    double peak = 0;
    cv::Point at;
    cv::minMaxLoc(dist, nullptr, &peak, nullptr, &at);
    if (peak < kMinRadiusPx || (k == 1 && peak < kSecondPeakFraction * first_peak)) break;
    if (k == 0) first_peak = peak;
    out.centres.emplace_back(at.x, at.y);
    out.radii_px.push_back(peak);
    out.top_rows.push_back(TopRow(silhouette, at));
    // Suppress this sphere (and the rod near it) before looking for the other one.
    cv::circle(dist, at, int(std::ceil(1.5 * peak)), cv::Scalar(0), cv::FILLED);
  }
}

// The lowest sphere's lowest point (the top of its blob plus a diameter), moved along the slope
// to the frame's centre column; NaN with no sphere.
double LowestPointRow(const Detection& det, double slope, int cols, double radius_px) {
  // Without the radius, the smallest distance-transform one (a band joined to a sphere only
  // makes its circle larger).
  double r = radius_px;
  if (!std::isfinite(r)) {
    r = std::numeric_limits<double>::infinity();
    for (double dt : det.radii_px) r = std::min(r, dt);
  }
  const double centre = 0.5 * (cols - 1);
  double lowest = std::numeric_limits<double>::quiet_NaN();
  for (size_t k = 0; k < det.centres.size(); ++k) {
    const double row = det.top_rows[k] + 2 * r - slope * (det.centres[k].x() - centre);
    if (!(row <= lowest)) lowest = row;
  }
  return lowest;
}

double LargestRadius(const Detection& det) {
  double r = 0;
  for (double dt : det.radii_px) r = std::max(r, dt);
  return r;
}

// The spheres found above the image's choice (`out`) do not stand on it (`lowest`: their lowest
// point, NaN where none was found), or one is missing (an edge that runs across the spheres
// leaves too little of them above it). The candidate their lowest point meets is the plate;
// where none does, each other candidate in turn, the strongest first, with the spheres found
// above it, until one is met by as many spheres as the image's choice had. False when none is:
// the image's choice stands.
bool DimerStandsOnAnother(const cv::Mat& frame, int polarity, double slope, double radius_px,
                          const std::vector<PlateCandidate>& candidates, double lowest,
                          Detection* out) {
  const size_t found = out->centres.size();
  const double largest = LargestRadius(*out);
  std::vector<size_t> order;
  const int meets = CandidateTheDimerStandsOn(candidates, lowest);
  if (meets >= 0) order.push_back(size_t(meets));
  std::vector<size_t> rest;
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (!candidates[i].from_image && int(i) != meets) rest.push_back(i);
  }
  std::stable_sort(rest.begin(), rest.end(), [&](size_t a, size_t b) {
    return candidates[a].step > candidates[b].step;
  });
  order.insert(order.end(), rest.begin(), rest.end());
  for (size_t i : order) {
    if (candidates[i].from_image) continue;
    out->plate_row = candidates[i].row;
    out->centres.clear();
    out->radii_px.clear();
    out->top_rows.clear();
    FindSpheresAbove(frame, polarity, slope, out);
    const double low = LowestPointRow(*out, slope, frame.cols, radius_px);
    // Without the radius, a lowest point is only as good as the smallest blob's radius, and
    // above an edge that cuts the spheres only their highlights may be left, whose lowest
    // points meet that edge: the spheres above the edge taken must be no smaller than above the
    // image's choice (lowering the line the spheres are found above only adds to them).
    const bool no_smaller = std::isfinite(radius_px) || LargestRadius(*out) >= largest;
    if (out->centres.size() >= found && no_smaller &&
        CandidateTheDimerStandsOn({candidates[i]}, low) == 0) {
      out->plate_by_dimer = true;
      return true;
    }
  }
  return false;
}

}  // namespace

Detection DetectSpheres(const cv::Mat& frame, int polarity, double slope, double radius_px) {
  Detection out;
  const std::vector<PlateCandidate> candidates = PlateCandidates(frame, slope);
  out.plate_row = std::numeric_limits<double>::quiet_NaN();
  double strongest = out.plate_row;
  for (const PlateCandidate& c : candidates) {
    if (c.from_image) out.plate_row = c.row;
    if (c.strongest) strongest = c.row;
  }
  FindSpheresAbove(frame, polarity, slope, &out);
  const double lowest = LowestPointRow(out, slope, frame.cols, radius_px);
  // Kept where both spheres are found and the lowest one stands on the edge or in the band
  // below it where a plate whose top is in view has its contact line (plate_contact.h).
  const double below = lowest - out.plate_row;
  if (out.centres.size() < 2 || !(below >= -kPlateMeetPx && below <= kPlateBandHalfPx)) {
    const Detection image_choice = out;
    if (!DimerStandsOnAnother(frame, polarity, slope, radius_px, candidates, lowest, &out)) {
      out = image_choice;
    }
  }
  if (strongest != out.plate_row) out.strongest_edge_row = strongest;
  return out;
}

}  // namespace dimer::tracking
