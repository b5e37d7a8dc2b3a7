// The learnt appearance refereed by the sphere's detections (tracking/detection_agreement.h):
// learning frames whose rough and learnt positions are made up, the truth known.
#include "tracking/detection_agreement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace dimer::tracking {
namespace {

// A sphere hopping `hop` px up and down over `n` learning frames, drifting 1 px along the
// columns: the rough centres follow its rows `rough_gain` times over with noise `rough_noise`,
// the learnt positions follow `learnt_gain` times over with noise 0.02 px (a registration's).
LearntSphere Hopping(int n, double hop, double rough_gain, double rough_noise, double learnt_gain,
                     unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 1);
  LearntSphere s;
  for (int i = 0; i < n; ++i) {
    const double col = 100 + double(i) / n;
    const double row = 50 - hop * std::sin(M_PI * i / (n - 1));
    s.rough.emplace_back(col + 3 + rough_noise * noise(rng),
                         50 + rough_gain * (row - 50) + 4 + rough_noise * noise(rng));
    s.registered.emplace_back(col + 0.02 * noise(rng), 50 + learnt_gain * (row - 50) + 0.02 * noise(rng));
  }
  return s;
}

TEST(DetectionAgreement, ASphereBothFollowAgreesWhateverTheOffset) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    EXPECT_TRUE(AgreementWithDetections(Hopping(20, 9, 1.0, 0.3, 1.0, seed)).agrees) << seed;
  }
}

// Highlight seeds and silhouettes of front-lit steel follow a hop up to 1.6 times over
// (POV-Ray front_point, mains_flicker): still the same sphere.
TEST(DetectionAgreement, RoughCentresThatOvershootTheMotionStillAgree) {
  for (double gain : {0.5, 1.6, 2.0}) {
    EXPECT_TRUE(AgreementWithDetections(Hopping(20, 9, gain, 0.2, 1.0)).agrees) << gain;
  }
}

// The learnt positions held nearly still (a tenth of the hop) while the rough ones rise and
// fall with the sphere: the appearance followed something else.
TEST(DetectionAgreement, LearntPositionsHeldStillDisagree) {
  const DetectionAgreement a = AgreementWithDetections(Hopping(20, 9, 0.8, 0.3, 0.1));
  EXPECT_FALSE(a.agrees);
  EXPECT_EQ(a.axis, 1);
  EXPECT_GT(a.slope, kDetectionSlopeBand);
  EXPECT_GT(a.rough_sd, 5 * a.learnt_sd);
}

// Where they disagree the axis's stated uncertainty grows by how far the two parted, their
// constant offset aside: for learnt rows held at a tenth of a 9-px hop that the rough centres
// follow 0.8 times over, (0.8 - 0.1) of the hop's spread; where they agree it stays as it was.
TEST(DetectionAgreement, ADisagreementWidensTheStatedUncertaintyByHowFarTheyPart) {
  const DetectionAgreement held = AgreementWithDetections(Hopping(20, 9, 0.8, 0.3, 0.1));
  ASSERT_FALSE(held.agrees);
  std::vector<double> hop;
  for (int i = 0; i < 20; ++i) hop.push_back(9 * std::sin(M_PI * i / 19));
  double mean = 0, var = 0;
  for (double h : hop) mean += h / 20;
  for (double h : hop) var += (h - mean) * (h - mean) / 19;
  const double parted = 0.7 * std::sqrt(var);
  EXPECT_NEAR(held.residual_sd, parted, 0.1);  // the rough centres' noise 0.3 px aside
  EXPECT_NEAR(WidenForDisagreement(held, 0.5), std::hypot(0.5, held.residual_sd), 1e-12);
  EXPECT_GT(WidenForDisagreement(held, 0.5), parted);
  const DetectionAgreement both = AgreementWithDetections(Hopping(20, 9, 1.0, 0.3, 1.0));
  ASSERT_TRUE(both.agrees);
  EXPECT_EQ(WidenForDisagreement(both, 0.5), 0.5);
}

// A resting sphere (no hop) gives the slope no lever: nothing is decided, whatever the noise
// of the rough centres; nor with fewer than three frames.
TEST(DetectionAgreement, NoMotionOrTooFewFramesDecideNothing) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    EXPECT_TRUE(AgreementWithDetections(Hopping(20, 0, 1.0, 1.0, 1.0, seed)).agrees) << seed;
  }
  EXPECT_TRUE(AgreementWithDetections(Hopping(2, 9, 1.0, 0.3, 0.1)).agrees);
  EXPECT_TRUE(AgreementWithDetections(LearntSphere{}).agrees);
}

}  // namespace
}  // namespace dimer::tracking
