// Rough centres from the highlights (tracking/sphere/highlight_seed.h): the blobs' masses, the two
// splits into the spheres' groups, the film's choice between them, and the highlight floor. The
// blob layouts are those measured on the POV-Ray films (bench_tracking_footage --seeds).
#include "tracking/sphere/highlight_seed.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <initializer_list>
#include <random>

namespace dimer::tracking {
namespace {

constexpr double kRadius = 23.75;

HighlightBlob At(double col, double row, double mass) { return {{col, row}, mass}; }

// A ring light on steel: one heavy highlight per sphere at its centre, and the rod's
// reflections, a row of light dots nearer the right sphere. Splitting at the widest gap between
// columns put the dots with the right sphere, 41 px off.
TEST(SplitHighlights, TheRodsGlintsDoNotJoinASphere) {
  const std::vector<HighlightBlob> blobs = {
      At(387.0, 223.5, 179), At(249.5, 225.0, 177), At(315.5, 224, 3),  At(326.5, 224, 10),
      At(338.5, 224.0, 6),   At(346.5, 224.0, 5),   At(350.5, 224, 4), At(357.0, 224, 6.5)};
  std::array<Eigen::Vector2d, 2> c;
  ASSERT_TRUE(SplitHighlights(blobs, kRadius, &c));
  EXPECT_NEAR(c[0].x(), 249.5, 1e-9);
  EXPECT_NEAR(c[1].x(), 387.0, 1e-9);
  EXPECT_NEAR(c[0].y(), 225.0, 1e-9);
}

// Touching spheres (A_r 2.0): each sphere's two lamps' highlights 10 px apart, the spheres a
// diameter apart; a run a diameter long can take the left sphere's pair and the right sphere's
// near highlight with all the mass in two runs either way. The runs farthest apart are kept.
TEST(SplitHighlights, TouchingSpheresAreSplitBetweenThem) {
  const std::vector<HighlightBlob> blobs = {At(337.7, 215.3, 47.5), At(347.7, 216.7, 41.5),
                                            At(290.5, 219.0, 57.0), At(300.5, 221.0, 36.0)};
  std::array<Eigen::Vector2d, 2> c;
  ASSERT_TRUE(SplitHighlights(blobs, kRadius, &c));
  EXPECT_NEAR(c[0].x(), 295.5, 1e-9);
  EXPECT_NEAR(c[1].x(), 342.7, 1e-9);
}

// A cluttered backdrop reflected at both limbs of each sphere, 21.7 px either side of its
// centre: each group spans nearly a diameter. A faint speck (mass 0.3) is left out.
TEST(SplitHighlights, LimbReflectionsEitherSideOfEachSphere) {
  const std::vector<HighlightBlob> blobs = {At(228.0, 216.0, 0.3), At(271.0, 219.5, 60.1),
                                            At(365.3, 218.5, 81.1), At(408.6, 219.0, 112.4),
                                            At(228.3, 222.0, 54.0)};
  std::array<Eigen::Vector2d, 2> c;
  ASSERT_TRUE(SplitHighlights(blobs, kRadius, &c));
  EXPECT_NEAR(c[0].x(), 0.5 * (271.0 + 228.3), 1e-9);
  EXPECT_NEAR(c[1].x(), 0.5 * (365.3 + 408.6), 1e-9);
}

TEST(SplitHighlights, OneSpheresHighlightsOrTooFewBlobsAreRefused) {
  std::array<Eigen::Vector2d, 2> c;
  EXPECT_FALSE(SplitHighlights({}, kRadius, &c));
  EXPECT_FALSE(SplitHighlights({At(100, 50, 10)}, kRadius, &c));
  // Two highlights on one sphere, 10 px apart: no gap of a radius between two runs.
  EXPECT_FALSE(SplitHighlights({At(100, 50, 10), At(110, 52, 9)}, kRadius, &c));
  // A heavy blob and specks only: the specks are dropped, one blob is left.
  EXPECT_FALSE(SplitHighlights({At(100, 50, 100), At(200, 50, 2), At(260, 50, 3)}, kRadius, &c));
}

// The old split, kept for the films it suits: at the widest gap between columns, every blob on
// its side averaged (the rod's dots then join the right sphere).
TEST(SplitAtWidestGap, EveryBlobOnEachSideOfTheWidestGap) {
  const std::vector<HighlightBlob> blobs = {At(387.0, 223.5, 179), At(249.5, 225.0, 177),
                                            At(315.5, 224, 3), At(357.0, 224, 6.5)};
  std::array<Eigen::Vector2d, 2> c;
  ASSERT_TRUE(SplitAtWidestGap(blobs, kRadius, &c));
  EXPECT_NEAR(c[0].x(), 249.5, 1e-9);
  EXPECT_NEAR(c[1].x(), (387.0 + 315.5 + 357.0) / 3, 1e-9);
  EXPECT_FALSE(SplitAtWidestGap({At(100, 50, 10), At(110, 52, 9)}, kRadius, &c));
}

// A film's seeds by the split whose two seeds stand a dimer's length apart in the most frames.
// Ring light: the weighed split keeps the separation, the widest gap does not. Cluttered
// backdrop whose left sphere's right limb fades after frame 4: the weighed split puts that
// sphere's seed at its left limb (21.7 px off) from then on, the widest gap keeps the specks
// there and stays within a few px.
TEST(SeedFilm, TheSplitWhoseSeedsStandADimersLengthApartIsTheFilms) {
  std::vector<std::vector<HighlightBlob>> ring, clutter;
  for (int i = 0; i < 12; ++i) {
    const double x = 250 + 0.3 * i;
    ring.push_back({At(x, 225, 177), At(x + 137.5, 223.5, 179), At(x + 66 + i % 3, 224, 10),
                    At(x + 97, 224, 6), At(x + 107.5 - i % 4, 224, 5)});
    const double faint = i < 5 ? 60 : 4;  // the left sphere's right limb
    clutter.push_back({At(x - 21.7, 222, 55), At(x + 21.7, 219, faint), At(x + 3 - i % 5, 219, 3),
                       At(x + 137.5 - 21.7, 218, 81), At(x + 137.5 + 21.7, 219, 112)});
  }
  const HighlightSeeds r = SeedFilm(ring, kRadius, 8, 3);
  EXPECT_TRUE(r.by_mass);
  EXPECT_EQ(r.agreeing, 12u);
  for (size_t i = 0; i < ring.size(); ++i) {
    ASSERT_TRUE(r.seeded[i]);
    EXPECT_NEAR(r.seeds[i][1].x() - r.seeds[i][0].x(), 137.5, 1e-9) << "frame " << i;
  }
  const HighlightSeeds c = SeedFilm(clutter, kRadius, 8, 3);
  EXPECT_FALSE(c.by_mass);
  EXPECT_GT(c.agreeing, c.other_agreeing);
  for (size_t i = 0; i < clutter.size(); ++i) {
    ASSERT_TRUE(c.seeded[i]);
    EXPECT_TRUE(c.agrees[i]) << "frame " << i;
    EXPECT_NEAR(c.seeds[i][0].x(), 250 + 0.3 * double(i), 8.0) << "frame " << i;
  }
}

// A frame whose seeds are not a dimer's length apart (one sphere's highlight lost, a speck taken
// for it) is marked, and left out of the learning by its caller.
TEST(SeedFilm, FramesWhoseSeedsAreNotADimersLengthApartAreMarked) {
  std::vector<std::vector<HighlightBlob>> film;
  for (int i = 0; i < 10; ++i) {
    const double x = 250 + 0.3 * i;
    film.push_back({At(x, 225, 177), At(x + 137.5, 223.5, 179)});
  }
  film[4] = {At(250 + 1.2 + 40, 225, 177), At(250 + 1.2 + 137.5, 223.5, 179)};  // 40 px off
  film[7] = {At(250, 225, 177)};                                                 // one blob
  const HighlightSeeds s = SeedFilm(film, kRadius, 8, 3);
  EXPECT_EQ(s.agreeing, 8u);
  for (size_t i = 0; i < film.size(); ++i) {
    EXPECT_EQ(s.seeded[i], i != 7) << "frame " << i;
    EXPECT_EQ(s.agrees[i], i != 4 && i != 7) << "frame " << i;
  }
}

// Gaussian spots (sigma 1.2 px, `peak` levels high) added to a float frame: the spheres'
// highlights.
void AddHighlights(cv::Mat* f, std::initializer_list<cv::Point2d> at, double peak) {
  for (int r = 0; r < f->rows; ++r) {
    for (int c = 0; c < f->cols; ++c) {
      for (const cv::Point2d& p : at) {
        const double d2 = (c - p.x) * (c - p.x) + (r - p.y) * (r - p.y);
        f->at<float>(r, c) += float(peak * std::exp(-d2 / (2 * 1.2 * 1.2)));
      }
    }
  }
}

// Through FindHighlightBlobs on a frame: two bright spots (the spheres' highlights) and a row of
// dim dots between them, above a bright plate, with noise. The dots pass the highlight level
// but weigh little; the seeds are the spots'.
TEST(FindHighlightBlobs, MassesSetTheRodsGlintsApartFromTheSpheresHighlights) {
  cv::Mat frame(240, 480, CV_8U, cv::Scalar(6));
  cv::Mat f;
  frame.convertTo(f, CV_32F);
  cv::Mat n32(frame.size(), CV_32F);
  cv::RNG rng(7);
  rng.fill(n32, cv::RNG::NORMAL, 0, 1.5);  // a noisy dark backdrop
  f += n32;
  const cv::Point2d left(150.3, 150.6), right(289.7, 149.2);
  AddHighlights(&f, {left, right}, 120);
  for (int col : {215, 226, 238, 246, 250, 257}) f.at<float>(150, col) += 70;  // the rod's dots
  f.rowRange(200, 240).setTo(200);                                              // the plate
  f.convertTo(frame, CV_8U);
  const std::vector<HighlightBlob> blobs = FindHighlightBlobs(frame, 200, kRadius);
  ASSERT_GE(blobs.size(), 8u);  // both spots and the six dots
  std::array<Eigen::Vector2d, 2> c;
  ASSERT_TRUE(SplitHighlights(blobs, kRadius, &c));
  EXPECT_NEAR(c[0].x(), left.x, 0.3);
  EXPECT_NEAR(c[1].x(), right.x, 0.3);
  EXPECT_NEAR(c[0].y(), left.y, 0.3);
}

// A backdrop of broad bands two levels apart (a cluttered lab: shelves, a poster), noise of one
// level, and two spheres' highlights 30 levels above it, as the cluttered backdrop at half the
// gain (bench_tracking_footage --seeds). The highlight floor is set by the noise, read
// from neighbouring pixels; read from the levels' spread about their median (the bands) it stood
// at 44 levels above the median, over the highlights.
TEST(FindHighlightBlobs, TheFloorFollowsTheNoiseNotTheBackdropsShading) {
  cv::Mat f(240, 480, CV_32F);
  for (int c = 0; c < f.cols; ++c) f.col(c).setTo((c / 40) % 2 == 0 ? 20.0 : 26.0);
  cv::Mat n32(f.size(), CV_32F);
  cv::RNG rng(11);
  rng.fill(n32, cv::RNG::NORMAL, 0, 1.0);
  f += n32;
  const cv::Point2d left(150.3, 150.6), right(289.7, 149.2);
  AddHighlights(&f, {left, right}, 30);
  f.rowRange(200, 240).setTo(200);  // the plate
  cv::Mat frame;
  f.convertTo(frame, CV_8U);
  const std::vector<HighlightBlob> blobs = FindHighlightBlobs(frame, 200, kRadius);
  std::array<Eigen::Vector2d, 2> c;
  ASSERT_TRUE(SplitHighlights(blobs, kRadius, &c)) << blobs.size() << " blobs";
  EXPECT_NEAR(c[0].x(), left.x, 0.5);
  EXPECT_NEAR(c[1].x(), right.x, 0.5);
  EXPECT_EQ(blobs.size(), 2u);  // nothing of the bands or the noise
}

}  // namespace
}  // namespace dimer::tracking
