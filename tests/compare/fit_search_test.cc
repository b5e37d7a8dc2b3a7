// The fit's last stage (compare/fit_search.h) on chi2 functions whose minima are known: a
// failing fit moves to the lower point its profiles find, an acceptable one stays where it is,
// and a fit with no acceptable point says so with no range.
#include "compare/fit_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace dimer::compare {
namespace {

// Two wells of chi2 over the five coefficients (eps, mu_hat, mu_hat_s, mu, mu_s), apart only in
// eps: a narrow one (sigma 0.01 in eps) whose floor is `floor_a` at eps = 0.85 and another whose
// floor is `floor_b` at eps = 0.60; chi2 is the lower of the two. Between them chi2 rises to
// hundreds, so a local search started in one stays there; the profile of eps, which steps
// across the whole range of eps, meets the other.
class TwoWells : public Chi2Objective {
 public:
  TwoWells(double floor_a, double floor_b) : floor_a_(floor_a), floor_b_(floor_b) {}
  double Chi2(const std::vector<double>& x, std::vector<double>* simulated) override {
    ++evaluations;
    if (simulated) simulated->assign(kObservables, 0.0);
    double rest = 0;
    for (size_t k = 1; k < x.size(); ++k) rest += std::pow((x[k] - kCentre[k]) / kSigma, 2);
    const double a = floor_a_ + std::pow((x[0] - kEpsA) / kSigmaEps, 2);
    const double b = floor_b_ + std::pow((x[0] - kEpsB) / kSigmaEps, 2);
    return std::min(a, b) + rest;
  }
  void AddScatter(const std::vector<double>&, bool) override {}
  double ScaleFloors(const std::vector<double>&, double, double) override { return 1; }
  int usable() const override { return kObservables; }

  static constexpr double kEpsA = 0.85, kEpsB = 0.60, kSigmaEps = 0.01, kSigma = 0.05;
  static constexpr std::array<double, 5> kCentre = {0, 0.2, 0.4, 0.5, 1.0};
  static constexpr int kObservables = 40;  // 35 degrees of freedom
  int evaluations = 0;

 private:
  double floor_a_, floor_b_;
};

std::vector<double> InWell(double eps) {
  std::vector<double> x(TwoWells::kCentre.begin(), TwoWells::kCentre.end());
  x[0] = eps;
  return x;
}

// Started in the well whose floor (chi2 200 for 35 dof, p ~ 1e-24) fails the goodness test, the
// fit moves to the other (floor 30: p 0.71) and states eps's range there.
TEST(FitSearch, AFailingFitMovesToTheLowerPointItsProfileFinds) {
  TwoWells chi2(200, 30);
  const FitSearchResult s = JudgeAndMove(&chi2, InWell(TwoWells::kEpsA), FitOptions{});
  EXPECT_EQ(s.moves, 1);
  ASSERT_TRUE(s.result.acceptable) << "chi2 " << s.result.chi2;
  EXPECT_NEAR(s.result.chi2, 30, 0.1);
  const FitParameter& eps = s.result.params[0];
  ASSERT_EQ(eps.status, "constrained");
  // chi2 rises by 1 at eps +- sigma: the range is [0.59, 0.61], to the search's tolerance.
  EXPECT_LE(eps.range_lo, TwoWells::kEpsB);
  EXPECT_GE(eps.range_hi, TwoWells::kEpsB);
  EXPECT_NEAR(eps.err, TwoWells::kSigmaEps, 0.2 * TwoWells::kSigmaEps);
}

// Both wells acceptable (floors 30 and 20): the fit started in the higher one stays there, as
// an acceptable fit is not moved; its range is that well's.
TEST(FitSearch, AnAcceptableFitStaysWhereItIs) {
  TwoWells chi2(30, 20);
  const FitSearchResult s = JudgeAndMove(&chi2, InWell(TwoWells::kEpsA), FitOptions{});
  EXPECT_EQ(s.moves, 0);
  ASSERT_TRUE(s.result.acceptable);
  EXPECT_NEAR(s.result.chi2, 30, 0.1);
  EXPECT_LE(s.result.params[0].range_lo, TwoWells::kEpsA);
  EXPECT_GE(s.result.params[0].range_hi, TwoWells::kEpsA);
}

// Neither well acceptable (floors 200 and 150 for 35 dof): the fit moves to the lower one, fails
// there too, and gives no range for any coefficient, only the best point.
TEST(FitSearch, NoAcceptablePointGivesNoRange) {
  TwoWells chi2(200, 150);
  const FitSearchResult s = JudgeAndMove(&chi2, InWell(TwoWells::kEpsA), FitOptions{});
  EXPECT_FALSE(s.result.acceptable);
  EXPECT_EQ(s.moves, 1);
  EXPECT_NEAR(s.x[0], TwoWells::kEpsB, 0.005);
  for (const FitParameter& p : s.result.params) {
    EXPECT_EQ(p.status, "no_acceptable_fit") << p.name;
    EXPECT_TRUE(std::isnan(p.range_lo) && std::isnan(p.range_hi) && std::isnan(p.err)) << p.name;
  }
}

// A chaotic drift's chi2 changes realisation between coefficients that differ by 1e-9 (fit.h):
// here the smooth well of floor 30 plus a term of up to 20 that changes at every such step. A
// rise smaller than that roughness is not resolved, so the range's threshold is the roughness
// (a smooth chi2's is 1: AFailingFitMovesToTheLowerPointItsProfileFinds) and eps's range is
// wider than the smooth well's +- sigma.
class RoughWell : public TwoWells {
 public:
  RoughWell() : TwoWells(30, 1000) {}
  double Chi2(const std::vector<double>& x, std::vector<double>* simulated) override {
    double phase = 0;
    for (size_t k = 0; k < x.size(); ++k) phase += (k + 1) * x[k];
    return TwoWells::Chi2(x, simulated) + kRoughness * (1 + std::sin(1e9 * phase));
  }
  static constexpr double kRoughness = 10;
};

TEST(FitSearch, ARoughChi2sRangeSpansItsRoughness) {
  RoughWell chi2;
  const FitSearchResult s = JudgeAndMove(&chi2, InWell(TwoWells::kEpsA), FitOptions{});
  ASSERT_TRUE(s.result.acceptable) << "chi2 " << s.result.chi2;
  EXPECT_GT(s.result.threshold, 0.3 * RoughWell::kRoughness);
  EXPECT_LT(s.result.threshold, 2 * RoughWell::kRoughness);
  const FitParameter& eps = s.result.params[0];
  ASSERT_EQ(eps.status, "constrained");
  EXPECT_LE(eps.range_lo, TwoWells::kEpsA);
  EXPECT_GE(eps.range_hi, TwoWells::kEpsA);
  EXPECT_GT(eps.err, 1.5 * TwoWells::kSigmaEps);
}

// Floors that overstate the scatter (fit.h, kMinFloorScale): 40 observables, linear in the five
// coefficients (orthogonal cosine columns, so each profile is a slice), each stated with error 1
// and a floor of 4, about which the data scatter by `scatter`. With the floor as set chi2/dof is
// then (scatter^2 / 17), and the scale s that brings it to 1 solves 1 + 16 s^2 = 17 chi2/dof.
class Floored : public Chi2Objective {
 public:
  explicit Floored(double scatter) : scatter_(scatter) {}
  double Chi2(const std::vector<double>& x, std::vector<double>* simulated) override {
    if (simulated) simulated->assign(kObservables, 0.0);
    const double var = 1 + std::pow(kFloor * scale_, 2);
    double chi2 = 0;
    for (int k = 0; k < kObservables; ++k) {
      double model = 0;
      for (int j = 0; j < 5; ++j) model += kGain * std::cos(M_PI * j * (k + 0.5) / kObservables) * (x[j] - kTruth[j]);
      const double data = scatter_ * std::sqrt(2.0) * std::sin(2.1 * k + 0.3);
      chi2 += (model - data) * (model - data) / var;
    }
    return chi2;
  }
  void AddScatter(const std::vector<double>&, bool) override {}
  double ScaleFloors(const std::vector<double>& x, double target, double min_scale) override {
    scale_ = 1;
    const double at_floors = Chi2(x, nullptr);
    if (at_floors >= target) return scale_;
    const double s2 = (at_floors * (1 + kFloor * kFloor) / target - 1) / (kFloor * kFloor);
    scale_ = std::max(min_scale, std::sqrt(std::max(0.0, s2)));
    return scale_;
  }
  int usable() const override { return kObservables; }

  static constexpr int kObservables = 40;
  static constexpr double kFloor = 4, kGain = 60;
  static constexpr std::array<double, 5> kTruth = {0.6, 0.2, 0.4, 0.5, 1.0};

 private:
  double scatter_;
  double scale_ = 1;
};

FitSearchResult FitFloored(double scatter, double min_floor_scale) {
  Floored chi2(scatter);
  FitOptions o;
  o.min_floor_scale = min_floor_scale;
  return JudgeAndMove(&chi2, {0.62, 0.21, 0.38, 0.52, 0.97}, o);
}

// The rendered-and-tracked case: the data scatter twice their stated error, the floor four
// times it (chi2/dof ~0.2, as on fit_study_tracked.sh's drifts). The floors are scaled until
// chi2/dof is 1, and eps's range narrows by the errors' ratio, sqrt((1 + 16 s^2) / 17).
TEST(FitSearch, FloorsThatOverstateTheScatterAreScaledToIt) {
  const FitSearchResult set = FitFloored(2, 1), scaled = FitFloored(2, kMinFloorScale);
  ASSERT_TRUE(set.result.acceptable && scaled.result.acceptable);
  EXPECT_EQ(set.result.floor_scale, 1);
  const double at_floors = scaled.result.chi2_per_dof_at_floors;
  EXPECT_LT(at_floors, 0.5);
  const double s = std::sqrt((17 * at_floors - 1) / 16);
  ASSERT_GT(s, kMinFloorScale);
  EXPECT_NEAR(scaled.result.floor_scale, s, 1e-3);
  EXPECT_NEAR(scaled.result.chi2 / scaled.result.dof, 1, 0.01);
  const FitParameter &a = set.result.params[0], &b = scaled.result.params[0];
  ASSERT_EQ(a.status, "constrained");
  ASSERT_EQ(b.status, "constrained");
  EXPECT_NEAR(b.err / a.err, std::sqrt((1 + 16 * s * s) / 17), 0.05);
  EXPECT_LE(b.range_lo, Floored::kTruth[0] + 0.3 * a.err);
  EXPECT_GE(b.range_hi, Floored::kTruth[0] - 0.3 * a.err);
}

// A noise-free track (no scatter): chi2 stays below dof at any scale, and the floors shrink no
// further than kMinFloorScale.
TEST(FitSearch, ANoiseFreeTracksFloorsShrinkToTheLeastScale) {
  const FitSearchResult set = FitFloored(0, 1), scaled = FitFloored(0, kMinFloorScale);
  ASSERT_TRUE(scaled.result.acceptable);
  EXPECT_EQ(scaled.result.floor_scale, kMinFloorScale);
  const double ratio = std::sqrt((1 + 16 * kMinFloorScale * kMinFloorScale) / 17);
  EXPECT_NEAR(scaled.result.params[0].err / set.result.params[0].err, ratio, 0.05);
  EXPECT_LE(scaled.result.params[0].range_lo, Floored::kTruth[0]);
  EXPECT_GE(scaled.result.params[0].range_hi, Floored::kTruth[0]);
}

// Data that scatter more than their floors (chi2/dof above 1): nothing is scaled.
TEST(FitSearch, FloorsBelowTheScatterAreKept) {
  const FitSearchResult s = FitFloored(4.5, kMinFloorScale);
  ASSERT_TRUE(s.result.acceptable) << s.result.chi2;
  EXPECT_GT(s.result.chi2_per_dof_at_floors, 1);
  EXPECT_EQ(s.result.floor_scale, 1);
}

// One well of chi2 = 30 + ((eps - 0.6) / sigma)^2 + the others' (TwoWells' rest): eps's range is
// 0.6 +- sigma exactly. Its ends are bisected to their own scale (compare/fit.cc,
// kEdgeResolution): with sigma 2e-4, 0.7 % of the slice's step, 6 bisections alone locate each
// end only to within +-2.2e-4, about sigma (here the upper end 0.12 sigma off).
class OneWell : public Chi2Objective {
 public:
  explicit OneWell(double sigma_eps) : sigma_eps_(sigma_eps) {}
  double Chi2(const std::vector<double>& x, std::vector<double>* simulated) override {
    if (simulated) simulated->assign(TwoWells::kObservables, 0.0);
    double rest = 0;
    for (size_t k = 1; k < x.size(); ++k) {
      rest += std::pow((x[k] - TwoWells::kCentre[k]) / TwoWells::kSigma, 2);
    }
    return 30 + std::pow((x[0] - TwoWells::kEpsB) / sigma_eps_, 2) + rest;
  }
  void AddScatter(const std::vector<double>&, bool) override {}
  double ScaleFloors(const std::vector<double>&, double, double) override { return 1; }
  int usable() const override { return TwoWells::kObservables; }

 private:
  double sigma_eps_;
};

TEST(FitSearch, ARangesEndsAreLocatedToItsOwnWidth) {
  for (double sigma : {2e-4, 1e-2}) {
    OneWell chi2(sigma);
    const FitSearchResult s = JudgeAndMove(&chi2, InWell(TwoWells::kEpsB), FitOptions{});
    ASSERT_TRUE(s.result.acceptable);
    const FitParameter& eps = s.result.params[0];
    ASSERT_EQ(eps.status, "constrained") << sigma;
    EXPECT_NEAR(eps.range_lo, TwoWells::kEpsB - sigma, 0.03 * sigma) << sigma;
    EXPECT_NEAR(eps.range_hi, TwoWells::kEpsB + sigma, 0.03 * sigma) << sigma;
    EXPECT_NEAR(eps.err, sigma, 0.03 * sigma) << sigma;
  }
}

}  // namespace
}  // namespace dimer::compare
