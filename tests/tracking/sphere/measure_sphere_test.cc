#include "tracking/sphere/measure_sphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <tuple>

#include "tests/tracking/synthetic.h"

namespace dimer::tracking {
namespace {

constexpr double kRadiusPx = 23.75;     // 9.5 mm at 2e-4 m/px: the paper's ~47 px spheres at the default scale
constexpr double kRodHalfWidthPx = 3.75;

struct ErrorStats {
  Eigen::Vector2d bias{0, 0};  // mean error, px
  double scatter = 0;          // RMS distance from the bias, px
  double rms = 0;              // RMS error, px
  int missed = 0;
};

// Measures both spheres of `n` tilted dimers at random sub-pixel positions, tilts and plate
// rows, starting from guesses up to 1.5 px off (a tracker's prediction error).
ErrorStats Measure(Method method, Lighting lighting, double noise, int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RenderOptions o;
  o.lighting = lighting;
  o.noise = noise;
  o.gradient = 0.0;
  std::vector<Eigen::Vector2d> errors;
  ErrorStats st;
  for (int i = 0; i < n; ++i) {
    const SceneGeometry s = testing::TiltedDimer(120 + 40 * u(rng), 190 + 10 * u(rng), kRadiusPx,
                                                 0.3 * u(rng), kRodHalfWidthPx);
    const cv::Mat img = RenderFrame({s}, o, uint64_t(i));
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d truth = k == 0 ? s.left : s.right, other = k == 0 ? s.right : s.left;
      RefineContext ctx;
      ctx.polarity = lighting == Lighting::kBacklit ? -1 : 1;
      ctx.plate_row = s.plate_row;
      ctx.rod_dir = (other - truth).normalized();
      const Eigen::Vector2d guess = truth + Eigen::Vector2d(3 * u(rng) - 1.5, 3 * u(rng) - 1.5);
      const SphereMeasurement m = MeasureSphere(img, guess, kRadiusPx, ctx, method);
      if (!m.found()) {
        ++st.missed;
        continue;
      }
      errors.push_back(m.centre - truth);
    }
  }
  for (const auto& e : errors) st.bias += e / double(errors.size());
  for (const auto& e : errors) {
    st.rms += e.squaredNorm() / double(errors.size());
    st.scatter += (e - st.bias).squaredNorm() / double(errors.size());
  }
  st.rms = std::sqrt(st.rms);
  st.scatter = std::sqrt(st.scatter);
  return st;
}

// Bounds, px, per (lighting, noise). Justification:
//  - sigma = 0 on uniform discs: the only error is the sampling ("pixel locking") of the edge
//    and of the masks; for a sphere resting on the plate the centroid's locking is < 0.004 px
//    peak to peak (PixelLocking.SphereRestingOnThePlate; it was 0.023, hence the bound, kept at
//    0.008 px RMS, measured 0.002).
//  - sigma > 0: the Cramér-Rao bound for a 47 px disc with contrast 173 levels is ~0.002 px per
//    axis at sigma = 2 and scales with sigma; the centroid's clamped weights are close to it.
//    Bounds are 0.01 px at sigma = 2 and 0.02 px at sigma = 5 (the project's target, docs/BENCHMARKS.md bench_tracking, is 0.02 px at
//    sigma = 2).
//  - reflect: a mirror sphere is located by its rim (rim_fit.h), at a constant offset from the
//    centre (the bias, ~0.1 px, from the unresolved backdrop sliver at the rim; below 0.2 px).
//    The target is scatter about the bias <= 0.05 px at the benchmark's sigma = 2. Noise free,
//    the scatter is the rim model's error over tilts and plate contacts (measured 0.009 px):
//    bound 0.02 px. Noise-limited scatter scales with sigma, so at sigma = 5 the target scales
//    to 0.05 * 5 / 2 = 0.125 px (the rim is only ~12-19 grey levels above the background over
//    the fitted arc, so this is close to its Cramer-Rao limit, not a loosened target).
double ScatterBound(Lighting l, double noise) {
  if (l == Lighting::kReflect) return noise == 0 ? 0.02 : 0.05 * std::max(1.0, noise / 2.0);
  if (noise == 0) return 0.008;
  return noise <= 2 ? 0.01 : 0.02;
}

using Case = std::tuple<Method, Lighting, double>;
class RefinerAccuracy : public ::testing::TestWithParam<Case> {};

TEST_P(RefinerAccuracy, ErrorAgainstExactTruth) {
  const auto [method, lighting, noise] = GetParam();
  const int n = std::max(4, int(30 * testing::TestScale()));
  const ErrorStats st = Measure(method, lighting, noise, n, 11);
  std::printf("[ stats    ] %s %s sigma=%.0f: bias (%.4f, %.4f) scatter %.4f rms %.4f px\n",
              ToString(method).c_str(), ToString(lighting).c_str(), noise, st.bias.x(),
              st.bias.y(), st.scatter, st.rms);
  EXPECT_EQ(st.missed, 0);
  EXPECT_LE(st.scatter, ScatterBound(lighting, noise));
  if (lighting == Lighting::kReflect) {
    EXPECT_LT(st.bias.norm(), 0.2);
  } else {
    EXPECT_LE(st.rms, ScatterBound(lighting, noise) * 1.5);  // bias negligible on true discs
  }
}

std::string CaseName(const ::testing::TestParamInfo<Case>& p) {
  return ToString(std::get<0>(p.param)) + "_" + ToString(std::get<1>(p.param)) + "_sigma" +
         std::to_string(int(std::get<2>(p.param)));
}

INSTANTIATE_TEST_SUITE_P(
    UniformSpheres, RefinerAccuracy,
    ::testing::Combine(::testing::Values(Method::kCentroid, Method::kDiscFit),
                       ::testing::Values(Lighting::kDisc, Lighting::kBacklit),
                       ::testing::Values(0.0, 2.0, 5.0)),
    CaseName);

// Mirror spheres: random tilts, spheres resting on the plate, guesses 1.5 px off (rim fit).
INSTANTIATE_TEST_SUITE_P(
    MirrorSpheres, RefinerAccuracy,
    ::testing::Combine(::testing::Values(Method::kCentroid, Method::kDiscFit),
                       ::testing::Values(Lighting::kReflect), ::testing::Values(0.0, 2.0, 5.0)),
    CaseName);

// Peak-to-peak error of a disc swept across one pixel in x and y (20 steps), noise free: a
// method that locks to pixel centres shows an error that oscillates with the fractional
// position. `lift_px` raises the sphere off the plate (0: resting on it, plate mask active).
double LockingPeakToPeak(Method method, double lift_px) {
  RenderOptions o;
  o.lighting = Lighting::kDisc;
  o.noise = 0;
  o.gradient = 0;
  double lo = 1e9, hi = -1e9;
  for (int k = 0; k < 20; ++k) {
    SceneGeometry s = testing::TiltedDimer(200 + k / 20.0, 150 + k / 20.0, kRadiusPx, 0, 0);
    s.left.y() -= lift_px;
    s.right.y() -= lift_px;
    const cv::Mat img = RenderFrame({s}, o, 0);
    RefineContext ctx;
    ctx.plate_row = s.plate_row;
    ctx.rod_dir = {1, 0};
    const SphereMeasurement m = MeasureSphere(img, s.left, kRadiusPx, ctx, method);
    EXPECT_TRUE(m.found());
    for (double e : {m.centre.x() - s.left.x(), m.centre.y() - s.left.y()}) {
      lo = std::min(lo, e);
      hi = std::max(hi, e);
    }
  }
  std::printf("[ stats    ] %s pixel locking, lift %.1f px: %.5f px peak to peak\n",
              ToString(method).c_str(), lift_px, hi - lo);
  return hi - lo;
}

class PixelLocking : public ::testing::TestWithParam<Method> {};

TEST_P(PixelLocking, FreeSphereMeetsTheTarget) {
  // The project's target (docs/BENCHMARKS.md, bench_tracking): <= 0.01 px peak to peak (rod mask active, plate out of the window).
  EXPECT_LE(LockingPeakToPeak(GetParam(), 10.0), 0.01);
}

TEST_P(PixelLocking, SphereRestingOnThePlate) {
  // The project's target (docs/BENCHMARKS.md, bench_tracking), 0.01 px peak to peak, for a sphere in contact and just above the plate
  // (the plate cut active at every lift here). The centroid's plate cut is a double wedge whose
  // ramps run along the disc's edge, not across it (measure_sphere.cc, CentroidMask): measured
  // 0.0028-0.0038 px (it was 0.014 with a horizontal 8 px ramp); discfit 0.0006-0.001 px.
  for (double lift_px : {0.0, 0.5, 1.0, 2.0, 3.0}) {
    EXPECT_LE(LockingPeakToPeak(GetParam(), lift_px), 0.01) << "lift " << lift_px << " px";
  }
}

INSTANTIATE_TEST_SUITE_P(AllMethods, PixelLocking,
                         ::testing::Values(Method::kCentroid, Method::kDiscFit),
                         [](const auto& p) { return ToString(p.param); });

TEST(Refiner, ClippedAndMissingSpheresAreReportedNotThrown) {
  RenderOptions o;
  o.lighting = Lighting::kDisc;
  SceneGeometry s = testing::TiltedDimer(10, 150, kRadiusPx, 0, 0);  // left sphere cut by x = 0
  const cv::Mat img = RenderFrame({s}, o, 0);
  RefineContext ctx;
  ctx.plate_row = s.plate_row;
  EXPECT_EQ(MeasureSphere(img, s.left, kRadiusPx, ctx, Method::kCentroid).status,
            SphereMeasurement::Status::kClipped);
  // Nothing at (300, 60): background only.
  EXPECT_EQ(MeasureSphere(img, {300, 60}, kRadiusPx, ctx, Method::kCentroid).status,
            SphereMeasurement::Status::kMissing);
}

}  // namespace
}  // namespace dimer::tracking
