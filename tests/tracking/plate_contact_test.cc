// The contact line on a plate whose top is in view (tracking/plate_contact.h): frames made here
// with exact pixel coverage. The plate's far edge (dark backdrop above, the lit top below) is
// what the plate finder sees; the spheres rest a few pixels below it, on the top surface.
#include "tracking/plate_contact.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/disc_coverage.h"

namespace dimer::tracking {
namespace {

constexpr double kRadius = 23.75;
constexpr int kFarEdgeRow = 40;    // first row of the plate's top (edge at 39.5)
constexpr int kFrontEdgeRow = 48;  // first row of its front face
constexpr double kCols[2] = {200.3, 338.9};

struct Scene {
  double contact = 43.37;   // contact line row
  bool mirror = true;       // the top shows the spheres' images
  double noise = 2.0;       // grey levels
  uint64_t seed = 1;
};

// Backdrop 2, the plate's top 12 (its own dull diffuse light plus the mirrored black backdrop),
// front face 25; a sphere 7 (dark steel) over all of it, its mirror image 12 + 0.6 x 7 on the
// top only.
cv::Mat MakeFrame(const Scene& s) {
  cv::Mat img(96, 540, CV_8U);
  cv::RNG rng(s.seed);
  for (int r = 0; r < img.rows; ++r) {
    const double back = r < kFarEdgeRow ? 2.0 : r < kFrontEdgeRow ? 12.0 : 25.0;
    for (int c = 0; c < img.cols; ++c) {
      double v = back;
      for (double col : kCols) {
        if (s.mirror && r >= kFarEdgeRow && r < kFrontEdgeRow) {
          const double image = DiscPixelArea(c, r, {col, s.contact + kRadius}, kRadius);
          v = image * (12.0 + 0.6 * 7.0) + (1 - image) * v;
        }
        const double sphere = DiscPixelArea(c, r, {col, s.contact - kRadius}, kRadius);
        v = sphere * 7.0 + (1 - sphere) * v;
      }
      v += rng.gaussian(s.noise);
      img.at<uint8_t>(r, c) = cv::saturate_cast<uint8_t>(v);
    }
  }
  return img;
}

std::vector<LearningSample> Samples(const Scene& base, double found_edge, int n) {
  std::vector<LearningSample> out;
  for (int i = 0; i < n; ++i) {
    Scene s = base;
    s.seed = base.seed + uint64_t(i);
    LearningSample l;
    l.image = MakeFrame(s);
    l.plate_row = found_edge;
    l.found = {true, true};
    // Rough centres a pixel or so off, as from highlights.
    l.centre = {Eigen::Vector2d(kCols[0] + 1.2, s.contact - kRadius - 3),
                Eigen::Vector2d(kCols[1] - 0.8, s.contact - kRadius + 2)};
    out.push_back(l);
  }
  return out;
}

// Noise-free: the model is the picture but for its five sub-rows down a pixel and the frame's
// 8-bit rounding of a 5-level contrast; measured within 0.029 px.
TEST(MirroredContact, FindsTheLineWhereASphereMeetsItsImage) {
  for (double contact : {42.5, 43.37, 44.81, 46.05}) {
    Scene s;
    s.contact = contact;
    s.noise = 0;
    const cv::Mat frame = MakeFrame(s);
    for (double col : kCols) {
      const MirroredContact c = FitMirroredContact(frame, col + 1.0, kRadius, kFarEdgeRow - 0.5);
      ASSERT_TRUE(c.ok) << "contact " << contact;
      EXPECT_NEAR(c.row, contact, 0.03) << "column " << col;
      EXPECT_NEAR(c.col, col, 0.1);
      EXPECT_GE(c.reflection_chi2, kMinReflectionChi2);
    }
  }
}

// With noise of 2 grey levels against a contrast of 4-5 one fit scatters by ~0.1 px; the
// sequence's median over 20 sphere-frames is within its stated uncertainty.
TEST(MirroredContact, OneFitUnderNoiseIsWithinAFewTenths) {
  Scene s;
  const cv::Mat frame = MakeFrame(s);
  for (double col : kCols) {
    const MirroredContact c = FitMirroredContact(frame, col + 1.0, kRadius, kFarEdgeRow - 0.5);
    ASSERT_TRUE(c.ok);
    EXPECT_NEAR(c.row, s.contact, 0.3);
    EXPECT_GE(c.reflection_chi2, kMinReflectionChi2);
  }
}

TEST(MirroredContact, AMattePlateShowsNoImage) {
  // The spheres rest on a plate with no mirror image: nothing below the line to fit.
  Scene s;
  s.mirror = false;
  const cv::Mat frame = MakeFrame(s);
  for (double col : kCols) {
    const MirroredContact c = FitMirroredContact(frame, col, kRadius, kFarEdgeRow - 0.5);
    EXPECT_FALSE(c.ok && c.reflection_chi2 >= kMinReflectionChi2) << "chi2 " << c.reflection_chi2;
  }
}

TEST(PlateShift, MovesTheFarEdgeToTheContactLine) {
  Scene s;
  s.contact = 43.37;
  const PlateShift shift = EstimatePlateShift(Samples(s, kFarEdgeRow - 0.5, 10), kRadius);
  ASSERT_TRUE(shift.applied) << shift.reason;
  EXPECT_LT(shift.err, 0.05);
  EXPECT_NEAR(shift.value, s.contact - (kFarEdgeRow - 0.5), 3 * shift.err);
  EXPECT_EQ(shift.fits, 20u);
}

TEST(PlateShift, KeepsAnEdgeThatIsTheContactLine) {
  // The plate finder already on the contact line (the top not in view): the mirror images fit,
  // and put the line where the edge is.
  Scene s;
  s.contact = 43.37;
  const PlateShift shift = EstimatePlateShift(Samples(s, s.contact, 24), kRadius);
  EXPECT_FALSE(shift.applied) << shift.reason;
  // Only the probe was fitted (every third of the 24 samples, two spheres each).
  EXPECT_LE(shift.fits, 2 * kProbeSamples);
  EXPECT_NE(shift.reason.find("probe"), std::string::npos) << shift.reason;
  // And on a matte plate there is nothing to go by.
  s.mirror = false;
  const PlateShift matte = EstimatePlateShift(Samples(s, kFarEdgeRow - 0.5, 6), kRadius);
  EXPECT_FALSE(matte.applied) << matte.reason;
}

// The far edge moves 7/8 as much as the contact line (800 against 700 mm from the camera): the
// left sphere rests and follows the contact line, the right one hops.
TEST(PlateMotionScale, ARestingSphereGivesTheContactLinesMotionPerPxOfEdge) {
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.03);  // the tracker's scatter
  std::vector<double> edge;
  std::array<std::vector<double>, 2> rows;
  for (int i = 0; i < 80; ++i) {
    const double contact = 248.8 + 1.25 * std::sin(2 * 3.14159265 * i / 80.0);
    edge.push_back(245.9 + (contact - 248.8) / 1.14 + noise(rng));
    rows[0].push_back(contact - kRadius + noise(rng));
    const double lift = std::max(0.0, 12.0 * std::sin(2 * 3.14159265 * i / 40.0));
    rows[1].push_back(contact - kRadius - lift + noise(rng));
  }
  const PlateMotionScale m = FitPlateMotionScale(edge, rows, PlateShift{});
  ASSERT_TRUE(m.fitted);
  EXPECT_EQ(m.sphere, 0);
  EXPECT_NEAR(m.scale, 1.14, 3 * m.err);
  EXPECT_LT(m.err, 0.02);
  // A plate that hardly moves over the frames says nothing about the scale.
  for (double& e : edge) e = 245.9 + 0.05 * (e - 245.9);
  EXPECT_FALSE(FitPlateMotionScale(edge, rows, PlateShift{}).fitted);
}

// Given (`--plate-m-per-px`), the scale moves each edge row about the edge's median, or, on a
// polished plate whose shift was measured, about the row it was measured at; gaps in the edge
// (NaN: no plate found) neither count nor move.
TEST(PlateMotionScale, AGivenScaleMovesTheEdgeAboutItsMedianRow) {
  const std::vector<double> edge = {250.0, 251.0, std::nan(""), 249.0, 250.5, 248.0};
  const PlateMotionScale m = GivenPlateMotionScale(0.9, edge, PlateShift{});
  EXPECT_TRUE(m.given);
  EXPECT_FALSE(m.fitted);
  EXPECT_EQ(m.scale, 0.9);
  EXPECT_EQ(m.err, 0.0);
  EXPECT_EQ(m.edge_ref, 250.0);  // median of the five found rows
  EXPECT_NEAR(ContactRow(PlateShift{}, m, 251.0), 250.9, 1e-12);
  EXPECT_NEAR(ContactRow(PlateShift{}, m, 248.0), 248.2, 1e-12);
  EXPECT_EQ(ContactRow(PlateShift{}, m, 250.0), 250.0);
  // A shift measured but not applied moves nothing; applied, it adds, and sets the centre.
  PlateShift shift;
  shift.value = 3.0;
  shift.edge_ref = 249.0;
  EXPECT_EQ(ContactRow(shift, m, 250.0), 250.0);
  shift.applied = true;
  const PlateMotionScale on_shift = GivenPlateMotionScale(0.9, edge, shift);
  EXPECT_EQ(on_shift.edge_ref, 249.0);
  EXPECT_NEAR(ContactRow(shift, on_shift, 251.0), 251.0 + 3.0 - 0.1 * 2.0, 1e-12);
}

}  // namespace
}  // namespace dimer::tracking
