// A still-plate calibration film on our renderer: the dimer set down in separate poses, the
// left sphere on the plate, the right lifted by 0 to 8 px, a few frames per pose. Followed from
// one pose to the next, a sphere that jumped is far from its prediction; a match that neither
// the quick step nor ECC refines there is a whole-pixel peak beside it, and the frame is searched
// afresh (frame_follower.cc). Every sphere is found near its centre in every frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "render/scene_renderer.h"
#include "tests/tracking/synthetic.h"
#include "tracking/io/frame_source.h"
#include "tracking/track_sequence.h"

namespace dimer::tracking {
namespace pose_jumps_test {
namespace {

constexpr int kWidth = 400, kHeight = 170;
constexpr double kRadiusPx = 16.0, kPlateRow = 140.0;
constexpr int kPoses = 12, kFramesPerPose = 5;

TEST(PoseJumps, ASphereThatJumpsBetweenPosesIsFoundAtItsNewPose) {
  RenderOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.lighting = Lighting::kReflect;
  o.noise = 2.0;
  o.seed = 3;
  const double length = 2.0 * (testing::kAspectRatio - 1.0) * kRadiusPx;
  std::vector<SceneGeometry> poses;
  std::vector<cv::Mat> frames;
  for (int p = 0; p < kPoses; ++p) {
    // Lifts of 0 to 8 px in a scrambled order, the dimer moved by up to 6 px between poses.
    const double lift = 8.0 * ((p * 5) % kPoses) / (kPoses - 1);
    const double tilt = std::asin(lift / length);
    const double col = 80.0 + 2.0 * ((p * 7) % 4) + 0.37 * p;
    for (int i = 0; i < kFramesPerPose; ++i) {
      poses.push_back(testing::TiltedDimer(col, kPlateRow, kRadiusPx, tilt, 2.0));
      frames.push_back(RenderFrame({poses.back()}, o, frames.size()));
    }
  }
  MemorySource source(frames);
  SequenceOptions so;
  so.follower.method = Method::kTemplate;
  so.contact_radius_px = kRadiusPx;
  so.threads = 2;
  const SequenceResult r = TrackSequence(source, so);
  ASSERT_EQ(r.frames.size(), frames.size());
  double worst = 0;
  size_t found = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameTrack& f = r.frames[i];
    const Eigen::Vector2d truth[2] = {poses[i].left, poses[i].right};
    for (int k = 0; k < 2; ++k) {
      if (!f.found[k]) continue;
      ++found;
      const double e = (f.centre[k] - truth[k]).norm();
      worst = std::max(worst, e);
      EXPECT_LT(e, 0.5) << "frame " << i << " sphere " << k;
    }
  }
  std::printf("[ stats    ] %zu of %zu spheres found, worst error %.3f px\n", found,
              2 * frames.size(), worst);
  EXPECT_EQ(found, 2 * frames.size());
}

}  // namespace
}  // namespace pose_jumps_test
}  // namespace dimer::tracking
