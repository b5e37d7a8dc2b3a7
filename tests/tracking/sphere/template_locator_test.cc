#include "tracking/sphere/template_locator.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "tests/tracking/sphere/sphere_pattern.h"
#include "tracking/sphere/appearance_mismatch.h"
#include "tracking/sphere/appearance_model.h"
#include "tracking/sphere/impact_vertex.h"

namespace dimer::tracking {
namespace {

constexpr double kR = testing::kPatternRadius;

cv::Mat Render(int w, int h, double cx, double cy, double noise, uint64_t seed,
               double plate_row = NAN) {
  return testing::RenderPattern(w, h, cx, cy, 1.0, 0.0, noise, seed, plate_row);
}

// The exact appearance, reference point at the pattern's centre.
Appearance Exact() { return testing::ExactPattern(); }

TEST(LocateAppearance, RecoversSubPixelShiftsToAFewHundredthsOfAPixel) {
  const Appearance a = Exact();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  double worst = 0, sx = 0, sy = 0, ss = 0;
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    const double cx = 80 + u(rng), cy = 60 + u(rng);
    const cv::Mat img = Render(160, 120, cx, cy, 0.0, i);
    // From a guess 1.4 px off: the whole-pixel search and ECC must bring it back.
    const Located l = LocateAppearance(img, a, {cx + 1.4, cy - 0.9}, 3, MaskContext{});
    ASSERT_TRUE(l.ok);
    EXPECT_GT(l.score, 0.95);  // the whole-pixel peak of a pattern up to half a pixel off
    worst = std::max(worst, (l.position - Eigen::Vector2d(cx, cy)).norm());
    ss += (l.position - Eigen::Vector2d(cx, cy)).squaredNorm();
    sx += l.position.x() - cx;
    sy += l.position.y() - cy;
  }
  // Noise free (8-bit quantisation only): what is left is OpenCV's ECC, whose iterations settle
  // within ~0.03 px of the optimum (measured: RMS 0.015 px, worst 0.036 px on this pattern).
  EXPECT_LT(std::sqrt(ss / n), 0.02);
  EXPECT_LT(worst, 0.04);
  EXPECT_LT(std::abs(sx / n), 0.005);
  EXPECT_LT(std::abs(sy / n), 0.005);
}

TEST(LocateAppearance, NoiseAndTheMaskedPlateAndRodDoNotBiasIt) {
  const Appearance a = Exact();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  double sx = 0, sy = 0, sxx = 0, syy = 0;
  const int n = 60;
  for (int i = 0; i < n; ++i) {
    const double cx = 80 + u(rng), cy = 60 + u(rng);
    // A bright plate 3 px below the sphere and a bright bar (a rod) leaving it to the right.
    const double plate = cy + kR + 3;
    cv::Mat img = Render(160, 120, cx, cy, 2.0, 100 + i, plate);
    cv::rectangle(img, cv::Point(int(cx + kR - 1), int(cy - 3)), cv::Point(159, int(cy + 3)),
                  cv::Scalar(230), cv::FILLED);
    MaskContext ctx;
    ctx.plate_row = plate;
    ctx.rod_dir = {1, 0};
    const Located l = LocateAppearance(img, a, {cx + 0.6, cy + 0.4}, 2, ctx);
    ASSERT_TRUE(l.ok);
    const double ex = l.position.x() - cx, ey = l.position.y() - cy;
    sx += ex, sy += ey, sxx += ex * ex, syy += ey * ey;
  }
  const double mx = sx / n, my = sy / n;
  EXPECT_LT(std::abs(mx), 0.01);
  EXPECT_LT(std::abs(my), 0.01);
  EXPECT_LT(std::sqrt(sxx / n - mx * mx), 0.02);  // sigma = 2 grey levels
  EXPECT_LT(std::sqrt(syy / n - my * my), 0.02);
}

TEST(LocateAppearance, OutsideTheFrameIsClippedAndAnEmptyWindowIsNotFound) {
  const Appearance a = Exact();
  const cv::Mat img = Render(160, 120, 80.3, 60.7, 2.0, 1);
  EXPECT_TRUE(LocateAppearance(img, a, {10, 60}, 2, {}).clipped);
  const cv::Mat empty(120, 160, CV_8U, cv::Scalar(10));
  const Located l = LocateAppearance(empty, a, {80, 60}, 2, {});
  EXPECT_LT(l.score, 0.5);
}

// A frame flat over more than a template (a background clipped at black with no noise left, or
// a lossy video's smoothed background): OpenCV's normalised correlation is 0/0 or x/0 there, NaN
// or inf, and an inf outscored the spheres (H.264 and MJPEG films: no sphere found in any frame).
TEST(FindAppearance, AFlatRegionOfTheFrameIsNoMatch) {
  Appearance a = Exact();
  a.image *= 0.7310585;  // levels of a mean over frames, not whole numbers (scale-free match)
  cv::Mat img = Render(240, 120, 170.8, 55.6, 2.0, 9);
  img(cv::Rect(0, 0, 110, 120)).setTo(1);
  const std::vector<Located> f = FindAppearance(img, a, NAN, 1.5 * kR, 0.5);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_LT((f[0].position - Eigen::Vector2d(170.8, 55.6)).norm(), 0.5);
  EXPECT_LE(f[0].score, 1.001);
  // Following into the flat part finds nothing there either.
  const Located l = LocateAppearance(img, a, {60, 60}, 3, {});
  EXPECT_LT(l.score, 0.5);
}

TEST(FindAppearance, FindsBothSpheresOfAFrameBestFirst) {
  const Appearance a = Exact();
  cv::Mat img = Render(240, 120, 60.4, 60.2, 2.0, 7);
  const cv::Mat right = Render(240, 120, 170.8, 55.6, 0.0, 8);
  // Two spheres: the right half of the frame from the second rendering.
  right(cv::Rect(120, 0, 120, 120)).copyTo(img(cv::Rect(120, 0, 120, 120)));
  const std::vector<Located> f = FindAppearance(img, a, NAN, 1.5 * kR, 0.5);
  ASSERT_EQ(f.size(), 2u);
  const Eigen::Vector2d p0 = f[0].position, p1 = f[1].position;
  const bool left_first = p0.x() < p1.x();
  EXPECT_LT(((left_first ? p0 : p1) - Eigen::Vector2d(60.4, 60.2)).norm(), 0.5);
  EXPECT_LT(((left_first ? p1 : p0) - Eigen::Vector2d(170.8, 55.6)).norm(), 0.5);
}

// The whole-frame search at half resolution first (kCoarseCandidates) finds what the search at
// every whole pixel finds: the same spheres, best first, at the same places, on frames with
// two spheres anywhere (touching ones too), one, or none.
TEST(FindAppearance, TheCoarseSearchFindsWhatTheFullOneFinds) {
  const Appearance a = Exact();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> col(kR, 320 - kR), row(kR, 120 - kR);
  int found = 0;
  for (int i = 0; i < 40; ++i) {
    const int spheres = i % 4 == 3 ? 0 : i % 4 == 2 ? 1 : 2;
    const Eigen::Vector2d first(col(rng), row(rng));
    cv::Mat img = Render(320, 120, spheres ? first.x() : -3 * kR, first.y(), 2.0, 200 + i);
    if (spheres == 2) {  // the second a diameter or more away, its half of the frame pasted in
      Eigen::Vector2d second;
      do {
        second = {col(rng), row(rng)};
      } while ((second - first).norm() < 2 * kR);
      const cv::Mat other = Render(320, 120, second.x(), second.y(), 2.0, 300 + i);
      const int cut = int(std::lround(0.5 * (first.x() + second.x())));
      const cv::Rect side = second.x() > first.x() ? cv::Rect(cut, 0, 320 - cut, 120)
                                                   : cv::Rect(0, 0, cut, 120);
      if (std::abs(second.x() - first.x()) > 2 * kR) other(side).copyTo(img(side));
      else cv::max(img, other, img);  // one above the other: both drawn
    }
    const std::vector<Located> full = FindAppearance(img, a, NAN, 1.5 * kR, 0.5, 0);
    const std::vector<Located> coarse = FindAppearance(img, a, NAN, 1.5 * kR, 0.5);
    ASSERT_EQ(coarse.size(), full.size()) << "frame " << i;
    for (size_t k = 0; k < full.size(); ++k) {
      EXPECT_LT((coarse[k].position - full[k].position).norm(), 1e-3) << "frame " << i;
      EXPECT_NEAR(coarse[k].score, full[k].score, 1e-4) << "frame " << i;
    }
    found += int(full.size());
  }
  EXPECT_GE(found, 40);  // the frames hold 50 spheres
}

// Reference rows of a sphere whose bottom is lift(i) px above a plate swinging by 0.5 px, with an
// offset of 3.2 px above its centre (centre = row + offset) and noise 0.02 px.
constexpr double kContactR = 23.75, kContactOffset = 3.2;
struct ContactSeries {
  std::vector<double> rows, plate;
};
ContactSeries RowsAbovePlate(int frames, uint64_t seed, const std::function<double(int)>& lift) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 0.02);
  ContactSeries c;
  for (int i = 0; i < frames; ++i) {
    const double p = 200 + 0.5 * std::sin(i * 0.1);
    c.plate.push_back(p);
    c.rows.push_back(p - kContactR - lift(i) - kContactOffset + n(rng));
  }
  return c;
}

TEST(AppearanceOffset, ASphereThatNeverRestsTouchesWhereItsImpactsArmsMeet) {
  // The jump mode: the sphere bounces once every 80 frames, leaving the plate at 0.6 px a frame
  // and landing at 0.9 px a frame (a V in plate - R - row), the impact at a different fraction
  // of a frame each time.
  const auto bounce_lift = [](int i) {
    const int bounce = i / 80;
    const double impact = 80.0 * bounce + 40.0 + 0.37 * bounce - std::floor(0.37 * bounce);
    const double dt = i - impact;  // frames from the impact
    return std::min(12.0, dt < 0 ? -0.9 * dt : 0.6 * dt);
  };
  const ContactSeries c = RowsAbovePlate(800, 3, bounce_lift);
  const OffsetEstimate e = ContactRowOffset(c.rows, c.plate, kContactR);
  // The frames next to the impacts sit up to 0.3 px above the plate, and their mean leaned off
  // it (+0.09 to +0.18 px on POV-Ray films of the jump mode); the V's vertices do not.
  EXPECT_EQ(e.source, "plate_contact_impacts");
  EXPECT_NEAR(e.value, kContactOffset, 3 * e.err) << e.value << " +- " << e.err;
  EXPECT_LT(e.err, 0.02);
  EXPECT_EQ(e.n, 10u * 2 * kImpactArmFrames);
  // Where a frame of every rebound is lost, no V is whole: the frames next to the impacts are
  // all there is, and their spread is stated.
  ContactSeries lost = c;
  for (int b = 0; b < 10; ++b) lost.rows[size_t(80 * b + 42)] = NAN;
  const OffsetEstimate m = ContactRowOffset(lost.rows, lost.plate, kContactR);
  EXPECT_EQ(m.source, "plate_contact_bounces");
  EXPECT_GT(m.value - kContactOffset, 0.03) << "the mean of the frames next to the impacts";
  EXPECT_GE(m.err, 0.05);
  EXPECT_LE(std::abs(m.value - kContactOffset), 2 * m.err) << m.value << " +- " << m.err;
  // The same sphere resting 5 frames in a row at each landing rests.
  const ContactSeries rest = RowsAbovePlate(800, 3, [](int i) {
    const int k = i % 80;
    return k > 40 && k <= 45 ? 0.0 : std::min(12.0, k <= 40 ? 0.9 * (40.5 - k) : 0.6 * (k - 45.5));
  });
  EXPECT_EQ(ContactRowOffset(rest.rows, rest.plate, kContactR).source, "plate_contact");
}

TEST(AppearanceOffset, ANoisyRestIsFoundAtItsLevelNotInItsTail) {
  // A resting sphere whose rows scatter by 0.24 px (POV-Ray's one-sided light at 0.4 mm/px: a
  // dim sphere of 11.9 px), 2000 frames, hopping 4 px every 400 frames. Its lowest values lie
  // 0.8 px below its level: one window of 0.3 px about them settled below it (0.35 px here;
  // on the film the resting sphere lost the contact to the bouncing one, whose rows were then
  // 0.26 px off with +-0.03 stated).
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0, 0.24);
  ContactSeries c = RowsAbovePlate(2000, 4, [](int i) {
    const int k = i % 400;
    return k < 20 ? 4.0 * std::sin(k * M_PI / 20) : 0.0;
  });
  for (double& r : c.rows) r += noise(rng);
  const OffsetEstimate e = ContactRowOffset(c.rows, c.plate, kContactR);
  EXPECT_EQ(e.source, "plate_contact");
  EXPECT_GT(e.n, 1700u);
  EXPECT_NEAR(e.value, kContactOffset, 3 * e.err) << e.value << " +- " << e.err;
  EXPECT_LT(e.err, 0.04);
}

TEST(AppearanceOffset, PlateContactIsTheRestingCluster) {
  // The sphere rests for 200 frames and flies for 300 (up to 15 px above the plate).
  const ContactSeries c = RowsAbovePlate(
      500, 2, [](int i) { return i < 200 ? 0.0 : 15.0 * std::sin((i - 200) * M_PI / 300); });
  const OffsetEstimate e = ContactRowOffset(c.rows, c.plate, kContactR);
  EXPECT_EQ(e.source, "plate_contact");
  EXPECT_NEAR(e.value, kContactOffset, 0.01);
  EXPECT_GT(e.n, 150u);
  EXPECT_TRUE(std::isfinite(e.err));
  EXPECT_LT(e.err, 0.05);
  // No plate: nothing to estimate, said so.
  const OffsetEstimate none = ContactRowOffset(c.rows, std::vector<double>(500, NAN), kContactR);
  EXPECT_EQ(none.source, "none");
  EXPECT_TRUE(std::isnan(none.err));
}

TEST(AppearanceOffset, SeparatePosesAreMotionNotNoiseWithTheLengthsNoiseGiven) {
  // A still-plate calibration film: 16 poses, the sphere lifted by 0 to 7 px (one pose at rest,
  // one 0.5 px up); each frame is its own pose, so the gap's second differences are the poses'
  // changes. A band of three of them held every pose, and the mean of all was the offset.
  const ContactSeries c = RowsAbovePlate(16, 5, [](int i) { return 7.0 * ((i * 7) % 16) / 15; });
  const OffsetEstimate blind = ContactRowOffset(c.rows, c.plate, kContactR);
  EXPECT_GT(blind.value - kContactOffset, 1.0) << "every pose in the band";
  // The dimer's length from frame to frame shows the tracker's noise (0.02 px here): the band is
  // the least one, and holds the resting pose alone. One pose rests: not a resting sphere
  // (kMinRestingFrames), said so, and the film's other sphere will give the row.
  const OffsetEstimate e = ContactRowOffset(c.rows, c.plate, kContactR, NAN, 0.02);
  EXPECT_EQ(e.n, 1u);
  EXPECT_EQ(e.source, "plate_contact_bounces");
  EXPECT_NEAR(e.value, kContactOffset, 0.1);
  // A cap above the gap's own noise changes nothing.
  const OffsetEstimate same = ContactRowOffset(c.rows, c.plate, kContactR, NAN, 1e3);
  EXPECT_EQ(same.value, blind.value);
  EXPECT_EQ(same.n, blind.n);
}

// A mirror sphere's appearance drawn `col` px right of the reference column: a soft disc, the
// plate reflected below, two lamps placed symmetrically about the centre; `light_from_right`
// makes its reflections brighter on the right and keeps only the right lamp.
Appearance MirrorSphereLike(double col, bool light_from_right) {
  Appearance a;
  a.radius_px = kR;
  a.half = int(std::ceil(kR + 4));
  const int size = 2 * a.half + 1;
  a.image = cv::Mat(size, size, CV_32F);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const double dx = x - a.half - col, dy = y - a.half;
      const double r = std::sqrt(dx * dx + dy * dy);
      const double disc = 1.0 / (1.0 + std::exp((r - kR) / 0.6));
      const double side = light_from_right ? 1.0 + 0.8 * std::clamp(dx / kR, -1.0, 1.0) : 1.0;
      const double lamp_x = light_from_right ? dx - 6 : std::abs(dx) - 6;
      a.image.at<float>(y, x) =
          float(10 + disc * side * (20 + 60 * std::max(0.0, dy / kR)) +
                120 * std::exp(-(lamp_x * lamp_x + (dy + 8) * (dy + 8)) / 3.0));
    }
  }
  a.mask = cv::Mat::ones(size, size, CV_8U);
  return a;
}

TEST(AppearanceOffset, SymmetryAxisOfAMirrorSymmetricAppearance) {
  // A left-right symmetric pattern drawn 0.3 px right of the reference column: offset +0.3.
  const OffsetEstimate e = SymmetryColumnOffset(MirrorSphereLike(0.3, false));
  EXPECT_EQ(e.source, "symmetry");
  EXPECT_NEAR(e.value, 0.3, 0.02);
  EXPECT_LT(e.err, 0.05);
}

// Where the upper outline gives no edge, the column rests on the symmetry axis; light from one
// side moves that axis. The whole outline (fitted in learning, given here as it was fitted:
// 0.05 px right of the truth) brackets it with the symmetry: their midpoint, and an uncertainty
// that covers the error (the symmetry alone claimed a few hundredths of a pixel).
TEST(AppearanceOffset, WithoutTheUpperOutlineTheSymmetryIsCheckedByTheWholeOutline) {
  LearntSphere s;
  s.appearance = MirrorSphereLike(0.3, true);
  const OffsetEstimate alone = ColumnWithoutTheUpperOutline(s);
  ASSERT_EQ(alone.source, "symmetry") << "no whole outline: the symmetry alone";
  const double symmetry_error = std::abs(alone.value - 0.3);
  ASSERT_GT(symmetry_error, 0.1) << "the lamp must move the axis for this test to mean anything";

  s.whole_outline_col = OffsetEstimate{0.35, 0.03, 60, "whole_outline"};
  const OffsetEstimate e = ColumnWithoutTheUpperOutline(s);
  EXPECT_EQ(e.source, "symmetry_and_whole_outline");
  EXPECT_NEAR(e.value, 0.5 * (alone.value + 0.35), 1e-12);
  EXPECT_LT(std::abs(e.value - 0.3), symmetry_error);
  EXPECT_LE(std::abs(e.value - 0.3), e.err) << "the stated uncertainty covers the error";
}

// The bouncing sphere's row carried over two ways: one alone is taken as it is; without the
// appearances' mismatch, two that disagree give their midpoint, with an uncertainty that covers
// either being the right one.
TEST(AppearanceOffset, RowTransfersAreCombinedWithTheirDisagreementInTheUncertainty) {
  const OffsetEstimate none{0, NAN, 0, "none"};
  const OffsetEstimate reg{1.20, 0.03, 40, "plate_contact_of_other"};
  const OffsetEstimate out{0.90, 0.06, 40, "plate_contact_of_other_outline"};
  EXPECT_EQ(CombineRowTransfers(reg, none, NAN).source, "plate_contact_of_other");
  EXPECT_EQ(CombineRowTransfers(none, out, NAN).source, "plate_contact_of_other_outline");
  EXPECT_EQ(CombineRowTransfers(none, none, NAN).source, "none");
  const OffsetEstimate both = CombineRowTransfers(reg, out, NAN);
  EXPECT_EQ(both.source, "plate_contact_of_other_both");
  EXPECT_NEAR(both.value, 1.05, 1e-12);
  EXPECT_NEAR(both.err, std::hypot(0.06, 0.15), 1e-12);
  EXPECT_GE(both.err, std::abs(both.value - reg.value));
  EXPECT_EQ(both.n, 40u);
}

// With the mismatch measured, each transfer carries its model error (the registered one's grows
// with the mismatch, the outline one's is kOutlineTransferModelPx) and the two are weighed:
// alike appearances (mismatch 1) leave the registration's precision to the row, unlike ones
// (mismatch 10) hand it to the outline; where the two disagree beyond their uncertainties the
// stated one is scaled up to cover the disagreement.
TEST(AppearanceOffset, RowTransfersAreWeighedByHowAlikeTheAppearancesAre) {
  const OffsetEstimate none{0, NAN, 0, "none"};
  const OffsetEstimate reg{0.20, 0.03, 40, "plate_contact_of_other"};
  const OffsetEstimate out{-0.40, 0.27, 40, "plate_contact_of_other_outline"};
  // One alone carries its model error.
  const OffsetEstimate alone = CombineRowTransfers(reg, none, 10.0);
  EXPECT_EQ(alone.value, reg.value);
  EXPECT_NEAR(alone.err, std::hypot(0.03, RegisteredTransferModelErr(10.0)), 1e-12);
  EXPECT_NEAR(RegisteredTransferModelErr(10.0), 3 * kMismatchRowPx, 1e-12);
  EXPECT_EQ(RegisteredTransferModelErr(0.5), 0.0);
  EXPECT_NEAR(CombineRowTransfers(none, out, 1.0).err, std::hypot(0.27, kOutlineTransferModelPx),
              1e-12);
  // Alike: the weights 1 / 0.03^2 and 1 / (0.27^2 + 0.1^2).
  const OffsetEstimate alike = CombineRowTransfers(reg, out, 1.0);
  EXPECT_EQ(alike.source, "plate_contact_of_other_both");
  const double so = std::hypot(0.27, kOutlineTransferModelPx);
  const double wr = 1 / (0.03 * 0.03), wo = 1 / (so * so);
  EXPECT_NEAR(alike.value, (0.20 * wr - 0.40 * wo) / (wr + wo), 1e-12);
  EXPECT_LT(std::abs(alike.value - reg.value), 0.01);
  // 0.6 apart against sqrt(0.03^2 + so^2) = 0.29: the uncertainty scaled by 2.1.
  EXPECT_NEAR(alike.err, 0.6 / std::hypot(0.03, so) / std::sqrt(wr + wo), 1e-12);
  // Unlike: the registration's 0.03 becomes hypot(0.03, 0.3); the outline now weighs more.
  const OffsetEstimate unlike = CombineRowTransfers(reg, {-0.40, 0.05, 40, "x"}, 10.0);
  EXPECT_LT(unlike.value, 0.5 * (reg.value - 0.40));
  // Consistent estimates keep the weighted mean's own uncertainty, smaller than either's.
  const OffsetEstimate agree = CombineRowTransfers(reg, {0.22, 0.05, 40, "x"}, 1.0);
  EXPECT_LT(agree.err, 0.03);
}

TEST(AppearanceOffset, SilhouetteIsTheMedianDifference) {
  LearntSphere s;
  for (int i = 0; i < 21; ++i) {
    s.registered.push_back({100.0 + i, 50.0});
    s.rough.push_back({100.0 + i + 0.25 + 0.01 * (i % 3), 50.0 - 1.5});
  }
  s.rough[4].x() += 5;  // one bad rough centre does not move a median
  const OffsetEstimate c = SilhouetteOffset(s, 0), r = SilhouetteOffset(s, 1);
  EXPECT_NEAR(c.value, 0.26, 0.011);
  EXPECT_NEAR(r.value, -1.5, 1e-12);
  EXPECT_EQ(c.n, 21u);
  // The rows agree exactly: what is left of their uncertainty is the silhouette's own bias,
  // which the frames do not average away; the columns scatter and add to it.
  EXPECT_NEAR(r.err, kSilhouetteBiasPx, 1e-12);
  EXPECT_GT(c.err, kSilhouetteBiasPx);
}

}  // namespace
}  // namespace dimer::tracking
