#include "tracking/sphere/highlight_seed.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/median.h"

namespace dimer::tracking {
namespace {

// A pixel is a highlight when it stands this many robust sigmas above the median of the region
// above the plate, and above the midpoint between that median and the brightest pixel.
constexpr double kHighlightSigmas = 10.0;

// The sensor's noise in `region`, from the differences of horizontal neighbours (sigma sqrt 2
// each, whatever the scene's shading), their median read through the level step (median.h,
// QuantisedMedian). The spread of the levels about their median measured the scene instead: a
// cluttered backdrop's shading, and in whole levels, so that at half the gain the floor stood at
// 30 levels over the median where the noise was 1 and the spheres' highlights 31
// (see FindHighlightBlobs.TheFloorFollowsTheNoiseNotTheBackdropsShading). At least half the
// data's level step: a backdrop whose noise the quantisation hides must not make every level
// above its median a highlight. The step is the frame's own (the greatest common divisor of
// its levels): 16-bit frames of coarser data (8-bit levels x 257, a 10-bit camera's x 64) with
// a floor of half a 16-bit level made every noisy pixel a highlight, and the learning followed
// noise (a warm-lit POV-Ray film 30 px off); a floor of half an 8-bit level was too high for
// x 64 data.
double NoiseSigma(const cv::Mat& region, double step) {
  std::vector<double> d;
  d.reserve(size_t(region.rows) * size_t(std::max(region.cols - 1, 0)));
  for (int r = 0; r < region.rows; ++r) {
    const float* a = region.ptr<float>(r);
    for (int c = 1; c < region.cols; ++c) d.push_back(double(a[c]) - double(a[c - 1]));
  }
  const double m = QuantisedMedian(d, step);
  return std::max(std::isfinite(m) ? 1.4826 * m / std::sqrt(2.0) : 0.0, 0.5 * step);
}

}  // namespace

double LevelStep(const cv::Mat& image) {
  unsigned step = 0;
  for (int r = 0; r < image.rows && step != 1; ++r) {
    for (int c = 0; c < image.cols && step != 1; ++c) {
      const unsigned v =
          image.depth() == CV_8U ? image.at<uint8_t>(r, c) : image.at<uint16_t>(r, c);
      step = std::gcd(step, v);
    }
  }
  return step == 0 ? 1.0 : double(step);
}

std::vector<HighlightBlob> FindHighlightBlobs(const cv::Mat& image, double plate_row,
                                              double radius_px) {
  const int rows = std::isfinite(plate_row) ? std::clamp(int(plate_row) - 2, 1, image.rows)
                                            : image.rows;
  cv::Mat above;
  image(cv::Rect(0, 0, image.cols, rows)).convertTo(above, CV_32F);
  std::vector<float> v(above.begin<float>(), above.end<float>());
  auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double median = *mid;
  const double sigma = NoiseSigma(above, LevelStep(image));
  const double floor_level = median + kHighlightSigmas * sigma;
  double top = 0;
  cv::minMaxLoc(above, nullptr, &top);
  cv::Mat labels, stats, centroids;
  // A highlight lies on a sphere: a bright blob wider or taller than a sphere is something else
  // in the scene (a white ruler or a lamp behind the dimer). When the brightest pixel is in one,
  // the level it sets is above the highlights: the brightest pixel is then taken outside what
  // is connected to those blobs at the floor level (the whole ruler), and the level set again.
  auto larger = [&](int i) {
    return radius_px > 0 && (stats.at<int>(i, cv::CC_STAT_WIDTH) > 2 * radius_px ||
                             stats.at<int>(i, cv::CC_STAT_HEIGHT) > 2 * radius_px);
  };
  double level = std::max(floor_level, 0.5 * (median + top));
  int n = cv::connectedComponentsWithStats(above > level, labels, stats, centroids, 8, CV_32S);
  cv::Mat large = cv::Mat::zeros(above.size(), CV_8U);
  for (int i = 1; i < n; ++i) {
    if (larger(i)) large.setTo(255, labels == i);
  }
  if (cv::countNonZero(large) > 0) {
    cv::Mat floor_labels;
    const int m = cv::connectedComponents(above > floor_level, floor_labels, 8, CV_32S);
    std::vector<uint8_t> excluded(size_t(m), 0);
    for (int r = 0; r < large.rows; ++r) {
      for (int c = 0; c < large.cols; ++c) {
        if (large.at<uint8_t>(r, c)) excluded[size_t(floor_labels.at<int>(r, c))] = 1;
      }
    }
    cv::Mat rest = above > floor_level;
    for (int r = 0; r < rest.rows; ++r) {
      for (int c = 0; c < rest.cols; ++c) {
        if (excluded[size_t(floor_labels.at<int>(r, c))]) rest.at<uint8_t>(r, c) = 0;
      }
    }
    top = 0;
    if (cv::countNonZero(rest) > 0) cv::minMaxLoc(above, nullptr, &top, nullptr, nullptr, rest);
    level = std::max(floor_level, 0.5 * (median + top));
    n = cv::connectedComponentsWithStats((above > level) & rest, labels, stats, centroids, 8,
                                         CV_32S);
  }
  // Each blob's mass: how much light stands above the level, not how many pixels do. A steel
  // rod's reflections of a ring light are a row of dots a few levels above it; the spheres'
  // highlights carry tens of times more (see
  // FindHighlightBlobs.MassesSetTheRodsGlintsApartFromTheSpheresHighlights).
  std::vector<double> mass(size_t(std::max(n, 1)), 0.0);
  for (int r = 0; r < labels.rows; ++r) {
    const int* l = labels.ptr<int>(r);
    const float* a = above.ptr<float>(r);
    for (int c = 0; c < labels.cols; ++c) {
      if (l[c] > 0) mass[size_t(l[c])] += a[c] - level;
    }
  }
  std::vector<HighlightBlob> blobs;
  for (int i = 1; i < n; ++i) {
    if (!larger(i)) {
      blobs.push_back({{centroids.at<double>(i, 0), centroids.at<double>(i, 1)}, mass[size_t(i)]});
    }
  }
  return blobs;
}

bool SplitHighlights(std::vector<HighlightBlob> blobs, double radius_px,
                     std::array<Eigen::Vector2d, 2>* centres) {
  double heaviest = 0;
  for (const HighlightBlob& b : blobs) heaviest = std::max(heaviest, b.mass);
  std::erase_if(blobs, [&](const HighlightBlob& b) { return b.mass * kMinMassDivisor < heaviest; });
  if (blobs.size() < 2) return false;
  std::sort(blobs.begin(), blobs.end(), [](const HighlightBlob& a, const HighlightBlob& b) {
    return a.centre.x() < b.centre.x() ||
           (a.centre.x() == b.centre.x() && a.centre.y() < b.centre.y());
  });
  // A sphere's highlights lie within its radius of its centre: a run of blobs spanning at most a
  // diameter. The runs worth trying are those as long as they can be from one blob rightward, and
  // from one blob leftward; the two spheres' groups are two of them that share no blob.
  struct Run {
    size_t first, last;
    double mass;
  };
  const double span = 2 * radius_px;
  const size_t n = blobs.size();
  std::vector<Run> runs;
  for (size_t i = 0; i < n; ++i) {
    Run r{i, i, 0};
    for (size_t j = i; j < n && blobs[j].centre.x() - blobs[i].centre.x() <= span; ++j) {
      r.last = j;
      r.mass += blobs[j].mass;
    }
    runs.push_back(r);
    Run l{i, i, 0};
    for (size_t j = i + 1; j-- > 0 && blobs[i].centre.x() - blobs[j].centre.x() <= span;) {
      l.first = j;
      l.mass += blobs[j].mass;
    }
    runs.push_back(l);
  }
  double best = 0;
  for (const Run& a : runs) {
    for (const Run& b : runs) {
      if (a.last < b.first) best = std::max(best, a.mass + b.mass);
    }
  }
  if (best <= 0) return false;
  // Touching spheres: a run may take the near highlights of the other sphere with the same mass
  // in all; of the pairs (nearly) as heavy as the heaviest, the one whose runs stand farthest
  // apart is the two spheres.
  double gap = -1;
  const Run* left = nullptr;
  const Run* right = nullptr;
  for (const Run& a : runs) {
    for (const Run& b : runs) {
      if (a.last >= b.first ||
          (a.mass + b.mass) * kMassTieDivisor < best * (kMassTieDivisor - 1)) {
        continue;
      }
      const double g = blobs[b.first].centre.x() - blobs[a.last].centre.x();
      if (g > gap) {
        gap = g;
        left = &a;
        right = &b;
      }
    }
  }
  if (gap < radius_px) return false;
  auto mean = [&](const Run& r) {
    Eigen::Vector2d s(0, 0);
    for (size_t i = r.first; i <= r.last; ++i) s += blobs[i].centre;
    return Eigen::Vector2d(s / double(r.last - r.first + 1));
  };
  *centres = {mean(*left), mean(*right)};
  return true;
}

bool SplitAtWidestGap(std::vector<HighlightBlob> blobs, double radius_px,
                      std::array<Eigen::Vector2d, 2>* centres) {
  if (blobs.size() < 2) return false;
  std::stable_sort(blobs.begin(), blobs.end(), [](const HighlightBlob& a, const HighlightBlob& b) {
    return a.centre.x() < b.centre.x();
  });
  size_t cut = 1;
  for (size_t i = 1; i < blobs.size(); ++i) {
    if (blobs[i].centre.x() - blobs[i - 1].centre.x() >
        blobs[cut].centre.x() - blobs[cut - 1].centre.x()) {
      cut = i;
    }
  }
  if (blobs[cut].centre.x() - blobs[cut - 1].centre.x() < radius_px) return false;
  Eigen::Vector2d left(0, 0), right(0, 0);
  for (size_t i = 0; i < blobs.size(); ++i) (i < cut ? left : right) += blobs[i].centre;
  *centres = {left / double(cut), right / double(blobs.size() - cut)};
  return true;
}

namespace {

// How consistent a split's seeds are over the film: the frames whose two seeds stand within
// `tolerance_px` of the median frame's separation, and the mean absolute deviation from it
// (infinity with fewer than `min_frames` seeded).
struct Consistency {
  size_t agreeing = 0;
  double spread = std::numeric_limits<double>::infinity();
  std::vector<bool> agrees;  // per frame
};
Consistency SeparationConsistency(const std::vector<std::array<Eigen::Vector2d, 2>>& seeds,
                                  const std::vector<bool>& seeded, double tolerance_px,
                                  size_t min_frames) {
  std::vector<double> apart;
  for (size_t i = 0; i < seeds.size(); ++i) {
    if (seeded[i]) apart.push_back((seeds[i][1] - seeds[i][0]).norm());
  }
  Consistency c;
  c.agrees.assign(seeds.size(), false);
  if (apart.empty() || apart.size() < min_frames) return c;
  std::vector<double> sorted = apart;
  auto mid = sorted.begin() + std::ptrdiff_t(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  double sum = 0;
  for (size_t i = 0; i < seeds.size(); ++i) {
    if (!seeded[i]) continue;
    const double off = std::abs((seeds[i][1] - seeds[i][0]).norm() - *mid);
    sum += off;
    c.agrees[i] = off <= tolerance_px;
    c.agreeing += c.agrees[i];
  }
  c.spread = sum / double(apart.size());
  return c;
}

}  // namespace

HighlightSeeds SeedFilm(const std::vector<std::vector<HighlightBlob>>& blobs, double radius_px,
                        double tolerance_px, size_t min_frames) {
  std::array<HighlightSeeds, 2> by;  // 0: weighed, 1: widest gap
  std::array<Consistency, 2> c;
  for (int k = 0; k < 2; ++k) {
    by[k].by_mass = k == 0;
    by[k].seeds.resize(blobs.size());
    by[k].seeded.resize(blobs.size());
    for (size_t i = 0; i < blobs.size(); ++i) {
      by[k].seeded[i] = k == 0 ? SplitHighlights(blobs[i], radius_px, &by[k].seeds[i])
                               : SplitAtWidestGap(blobs[i], radius_px, &by[k].seeds[i]);
    }
    c[k] = SeparationConsistency(by[k].seeds, by[k].seeded, tolerance_px, min_frames);
  }
  for (int k = 0; k < 2; ++k) {
    by[k].agreeing = c[k].agreeing;
    by[k].agrees = c[k].agrees;
    by[k].spread_px = c[k].spread;
    by[k].other_agreeing = c[1 - k].agreeing;
    by[k].other_spread_px = c[1 - k].spread;
  }
  const bool gap = c[1].agreeing > c[0].agreeing ||
                   (c[1].agreeing == c[0].agreeing && c[1].spread < c[0].spread);
  return by[gap ? 1 : 0];
}

}  // namespace dimer::tracking
