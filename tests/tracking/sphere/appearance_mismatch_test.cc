// AppearanceMismatch (tracking/sphere/appearance_mismatch.h): two spheres learnt from the same noisy
// frames, drawn alike or with one sphere's highlights moved as a lamp to one side moves them.
// Alike, the registered appearances differ by their noise (mismatch near 1); unlike, by more,
// and then the row carried over by registration is off, which is why the test matters.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "tracking/sphere/appearance_mismatch.h"
#include "tracking/sphere/appearance_model.h"
#include "common/disc_coverage.h"
#include "render/seeded_noise.h"

namespace dimer::tracking {
namespace appearance_mismatch_test {
namespace {

constexpr double kRadius = 20.0;
constexpr int kWidth = 280, kHeight = 120;
constexpr double kRestRow = 60.0;
constexpr double kColumns[2] = {80.0, 200.0};
constexpr int kFrames = 24;

// How one sphere looks: its highlight's place relative to its centre, px.
struct Look {
  double spot_col = -6, spot_row = -7;
};

// A frame with both spheres at `centre`: a faint disc (8 over a backdrop of 3), a bright
// plate reflection below its middle (50) and one highlight; lens blur, noise 2 levels, 8 bit.
cv::Mat DrawFrame(const std::array<Eigen::Vector2d, 2>& centre, const std::array<Look, 2>& look,
                  Gaussian* noise) {
  cv::Mat img(kHeight, kWidth, CV_32F, cv::Scalar(3.0));
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d& c = centre[k];
    for (int y = int(c.y() - kRadius) - 2; y <= int(c.y() + kRadius) + 2; ++y) {
      for (int x = int(c.x() - kRadius) - 2; x <= int(c.x() + kRadius) + 2; ++x) {
        const double dx = x - c.x(), dy = y - c.y();
        const double sx = dx - look[k].spot_col, sy = dy - look[k].spot_row;
        // The reflection's horizon 3 px below the centre, antialiased like the outline (the
        // part of the pixel below it): drawn whole pixels at a time it would move against the
        // sphere with the sphere's sub-pixel row, and the two spheres be unlike.
        const double below = std::clamp(dy - 3.0 + 0.5, 0.0, 1.0);
        const double level = 8.0 + 42.0 * below + 180.0 * std::exp(-(sx * sx + sy * sy) / 3.0);
        img.at<float>(y, x) += float(DiscPixelArea(x, y, c, kRadius) * level);
      }
    }
  }
  cv::GaussianBlur(img, img, cv::Size(0, 0), 0.6);
  cv::Mat out(kHeight, kWidth, CV_8U);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      out.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(img.at<float>(y, x) + 2.0 * noise->Next());
    }
  }
  return out;
}

struct Learnt {
  std::array<LearntSphere, 2> spheres;
  // Each sphere's true offset (reference -> centre), from the truth of the frames it learnt.
  std::array<Eigen::Vector2d, 2> offset;
};

// kFrames frames: the left sphere resting, the right one lifted by up to 6 px (it bounces),
// both at sub-pixel columns that vary from frame to frame; rough centres a few px off.
Learnt Learn(const std::array<Look, 2>& look, uint64_t seed) {
  Gaussian noise(FrameSeed(seed, 0));
  std::vector<LearningSample> samples;
  std::vector<std::array<Eigen::Vector2d, 2>> truth;
  for (int i = 0; i < kFrames; ++i) {
    const double u = std::fmod(0.37 * i, 1.0), lift = 6.0 * std::pow(std::sin(0.4 * i), 2);
    const std::array<Eigen::Vector2d, 2> c{Eigen::Vector2d(kColumns[0] + u, kRestRow),
                                           Eigen::Vector2d(kColumns[1] + 1 - u, kRestRow - lift)};
    LearningSample s;
    s.image = DrawFrame(c, look, &noise);
    s.plate_row = kRestRow + kRadius;
    s.plate_col = 0.5 * (kColumns[0] + kColumns[1]);
    s.found = {true, true};
    s.centre = {c[0] + Eigen::Vector2d(1.0, 2.5), c[1] + Eigen::Vector2d(-0.7, 1.5)};
    samples.push_back(s);
    truth.push_back(c);
  }
  Learnt out;
  out.spheres = LearnAppearances(samples, kRadius, true);
  for (int k = 0; k < 2; ++k) {
    const LearntSphere& s = out.spheres[k];
    Eigen::Vector2d sum(0, 0);
    for (size_t i = 0; i < s.samples.size(); ++i) sum += truth[s.samples[i]][k] - s.registered[i];
    out.offset[k] = s.samples.empty() ? sum : Eigen::Vector2d(sum / double(s.samples.size()));
  }
  return out;
}

// The right sphere's row offset carried over from the left's true one by registration, less the
// right's true one.
double RegisteredRowError(const Learnt& l) {
  const OffsetEstimate from{l.offset[0].y(), 0.03, 1, "plate_contact"};
  const OffsetEstimate e =
      TransferOffset(l.spheres[0].appearance, l.spheres[1].appearance, from, 1);
  EXPECT_EQ(e.source, "plate_contact_of_other");
  return e.value - l.offset[1].y();
}

TEST(AppearanceMismatch, AlikeSpheresDifferByTheirNoise) {
  for (uint64_t seed : {1, 2}) {
    const Learnt l = Learn({Look{}, Look{}}, seed);
    ASSERT_TRUE(l.spheres[0].appearance.valid() && l.spheres[1].appearance.valid());
    const double mismatch = AppearanceMismatch(l.spheres[0], l.spheres[1]);
    const double err = RegisteredRowError(l);
    std::printf("[ alike    ] seed %d: mismatch %.2f, registered row error %+.3f px\n",
                int(seed), mismatch, err);
    // The noise measured by the jackknife, not assumed: a mismatch near 1.
    EXPECT_GT(mismatch, 0.5);
    EXPECT_LE(mismatch, 1.5);
    EXPECT_LE(std::abs(err), 0.03);
  }
}

TEST(AppearanceMismatch, HighlightsMovedByALampToOneSideAreUnlike) {
  // The right sphere sees the lamp from lower and further right: its highlight moved by up to a
  // pixel (0.4 px: a lamp 2 degrees further round). The mismatch grows with the move, and the
  // registered row's error, which follows the highlight, stays within the model error the
  // mismatch gives it.
  double last = 1.0;
  for (double move : {0.2, 0.4, 0.7, 1.0}) {
    Look moved;
    moved.spot_col += 0.64 * move;
    moved.spot_row += 0.77 * move;
    const Learnt l = Learn({Look{}, moved}, 1);
    ASSERT_TRUE(l.spheres[0].appearance.valid() && l.spheres[1].appearance.valid());
    const double mismatch = AppearanceMismatch(l.spheres[0], l.spheres[1]);
    const double err = RegisteredRowError(l);
    std::printf("[ unlike   ] highlight moved %.1f px: mismatch %.2f, registered row error %+.3f "
                "px, its model error %.3f px\n",
                move, mismatch, err, RegisteredTransferModelErr(mismatch));
    EXPECT_GT(mismatch, last) << move;
    EXPECT_LE(std::abs(err), RegisteredTransferModelErr(mismatch)) << move;
    if (move >= 0.4) {
      EXPECT_GT(std::abs(err), 0.05) << "the registration follows the highlight";
    }
    last = mismatch;
  }
}

// The outline transfer's noise from the jackknife (appearance_model.h, TransferRowByOutline):
// the same row as from the appearances alone, an uncertainty at least the circle fits', and the
// row within twice of it.
TEST(OutlineTransfer, TheJackknifeStatesItsNoise) {
  for (uint64_t seed : {1, 2}) {
    const Learnt l = Learn({Look{}, Look{}}, seed);
    const OffsetEstimate from{l.offset[0].y(), 0.03, 1, "plate_contact"};
    const OffsetEstimate fits =
        TransferRowByOutline(l.spheres[0].appearance, l.spheres[1].appearance, from);
    const OffsetEstimate e = TransferRowByOutline(l.spheres[0], l.spheres[1], from);
    ASSERT_EQ(e.source, "plate_contact_of_other_outline");
    std::printf("[ outline  ] seed %d: row error %+.3f px, stated %.3f (the fits alone %.3f)\n",
                int(seed), e.value - l.offset[1].y(), e.err, fits.err);
    EXPECT_EQ(e.value, fits.value);
    EXPECT_GE(e.err, fits.err);
    EXPECT_LE(std::abs(e.value - l.offset[1].y()), 2 * e.err);
  }
}

TEST(AppearanceMismatch, UnmeasuredWithoutTheJackknife) {
  Learnt l = Learn({Look{}, Look{}}, 1);
  // Groups too small to learn from (a film of 3 learning frames: groups of 2) have no
  // appearance; fewer than 3 that do, and nothing is measured.
  std::vector<Appearance> kept = l.spheres[1].jackknife;
  l.spheres[1].jackknife.assign(3, Appearance{});
  l.spheres[1].jackknife[0] = kept[0];
  EXPECT_TRUE(std::isnan(AppearanceMismatch(l.spheres[0], l.spheres[1])));
  l.spheres[1].jackknife.clear();
  EXPECT_TRUE(std::isnan(AppearanceMismatch(l.spheres[0], l.spheres[1])));
  EXPECT_TRUE(std::isnan(AppearanceMismatch(LearntSphere{}, l.spheres[0])));
}

}  // namespace
}  // namespace appearance_mismatch_test
}  // namespace dimer::tracking
