// The ruler's POV-Ray film rendered to 100 frames (the right sphere hopping up to 16.5 px, the
// camera centred on the longer path, 5 px further right than on the 20-frame case): what its
// first 20 frames hid. With the scale given, auto follows both spheres on the plate: before
// each sphere's own appearance looked for it (FrameFollower.FindsASphereUnlikeItsPartner) it
// found the hopping one in none of its trial frames and ran the centroid, 10 px off; before the
// learning frames kept one plate (plate_consensus.h) the resting sphere's rows, held by the
// ruler, scattered 0.53 px about the truth. Without the scale the learning is made again at the
// outline's radius. CTest `povray.long_ruler`; its own film.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "tests/footage/povray_footage.h"
#include "tests/footage/track_accuracy.h"
#include "tracking/io/frame_range.h"
#include "tracking/io/frame_source.h"
#include "tracking/track_sequence.h"

namespace dimer::footage {
namespace {

constexpr size_t kLongRulerFrames = 100;

struct LongRuler {
  std::string dir;
  std::vector<TruthRow> truth;
  double radius_px = 0;
  double gravity_per_radius_px = 0;
};

const LongRuler& Film() {
  static const LongRuler film = [] {
    LongRuler f;
    FootageOptions o = FootageOptions::For(Lighting::kRulerAbovePlate);
    o.subframes = 2;
    o.reuse = true;
    o.quiet = true;
    f.dir = std::string(DIMERLAB_POVRAY_CACHE) + "/ruler_above_plate_100_frames";
    std::filesystem::create_directories(DIMERLAB_POVRAY_CACHE);
    WriteFootage(HopMotion(o.shape, kLongRulerFrames, o.fps), o, f.dir);
    f.truth = ReadTruthCsv(f.dir + "/truth.csv", &f.radius_px);
    // As `dimerlab track` sets it: gravity in px per frame^2 per px of radius.
    f.gravity_per_radius_px = 2.0 * 9.81 / (o.shape.diameter * o.fps * o.fps);
    return f;
  }();
  return film;
}

tracking::SequenceResult Track(const LongRuler& f, bool scale_given,
                               const std::string& frames = "") {
  tracking::SequenceOptions o;
  o.threads = 2;
  o.follower.method = tracking::Method::kAuto;
  o.gravity_per_radius_px = f.gravity_per_radius_px;
  if (scale_given) o.contact_radius_px = f.radius_px;
  auto source = tracking::SelectFrames(tracking::OpenFrameSource(f.dir),
                                       tracking::ParseFrameRange(frames), f.dir);
  return tracking::TrackSequence(*source, o);
}

// Sphere k's error against the truth over the film: every frame found under its own name
// (nearer its own truth than the other's by far) with the plate within its target.
struct RulerError {
  bool whole = false;  // found in every frame, under its own name
  Eigen::Vector2d bias{0, 0}, sd{0, 0};
};

RulerError RulerSphereError(const tracking::SequenceResult& r, const LongRuler& f, int k) {
  RulerError a;
  Eigen::Vector2d sum(0, 0), sum2(0, 0);
  for (size_t i = 0; i < f.truth.size(); ++i) {
    const tracking::FrameTrack& t = r.frames[i];
    if (!t.found[k] || !((t.centre[k] - f.truth[i].centre[k]).norm() < 2.0)) {
      ADD_FAILURE() << "frame " << i << " sphere " << k << " not found under its own name";
      return a;
    }
    EXPECT_LE(std::abs(t.plate_row - f.truth[i].plate_row), 0.3) << "frame " << i;
    const Eigen::Vector2d e = t.centre[k] - f.truth[i].centre[k];
    sum += e, sum2 += e.cwiseProduct(e);
  }
  const double n = double(f.truth.size());
  a.whole = true;
  a.bias = sum / n;
  a.sd = (sum2 / n - a.bias.cwiseProduct(a.bias)).cwiseSqrt();
  return a;
}

TEST(PovrayLongRuler, WithTheScaleBothSpheresAreFollowedOnThePlate) {
  const LongRuler& f = Film();
  const tracking::SequenceResult r = Track(f, true);
  ASSERT_EQ(r.frames.size(), f.truth.size());
  for (int k = 0; k < 2; ++k) {
    const RulerError a = RulerSphereError(r, f, k);
    ASSERT_TRUE(a.whole);
    std::printf("[ stats    ] long ruler, %s sphere: bias %.3f / %.3f px, scatter %.3f / %.3f px "
                "(col / row)\n",
                k == 0 ? "left" : "right", a.bias.x(), a.bias.y(), a.sd.x(), a.sd.y());
    EXPECT_LE(a.bias.norm(), 0.1) << "sphere " << k;
    // Both meet the scatter target; the resting one's rows scattered 0.084 px with the flat
    // side of the ruler's still edge kept beside the cut (kStillBackgroundMarginPx).
    EXPECT_LE(a.sd.x(), 0.05) << "sphere " << k;
    EXPECT_LE(a.sd.y(), 0.05) << "sphere " << k;
    EXPECT_EQ(r.held_rows[k].held, 0u) << "sphere " << k;
  }
}

// The hopping right sphere's row offset comes from its own impacts, beside the resting left
// one: they put its rows 0.062 px high, stating 0.027 px (2.3 sigma; 0.026-0.077 px at up to
// 7 sigma over the POV-Ray films of 100 frames, bench_tracking_footage 100), while the contact
// carried over from the resting sphere lay 0.024 px from the truth. The stated uncertainty
// reaches the carried contact (EstimateOffsets, tracking/learn_method.cc), and covers the bias.
TEST(PovrayLongRuler, TheImpactsRowUncertaintyReachesTheRestingSpheresContact) {
  const LongRuler& f = Film();
  const tracking::SequenceResult r = Track(f, true);
  ASSERT_EQ(r.frames.size(), f.truth.size());
  const tracking::OffsetEstimate& row = r.offsets.row[1];
  ASSERT_EQ(row.source, "plate_contact_impacts");
  ASSERT_EQ(r.offsets.row[0].source, "plate_contact");
  const RulerError a = RulerSphereError(r, f, 1);
  ASSERT_TRUE(a.whole);
  std::printf("[ stats    ] long ruler, right sphere's row: bias %+.3f px, stated +-%.3f px\n",
              a.bias.y(), row.err);
  EXPECT_LE(std::abs(a.bias.y()), 2.0 * row.err);
  EXPECT_LE(row.err, 0.3);
}

TEST(PovrayLongRuler, WithoutTheScaleTheOutlinesRadiusFramesTheLearning) {
  const LongRuler& f = Film();
  const tracking::SequenceResult r = Track(f, false);
  ASSERT_EQ(r.frames.size(), f.truth.size());
  ASSERT_EQ(r.radius_source, "outline");
  const double radius = r.appearance[0].radius_px;
  // Learnt at the first frame's radius (26.0 px) both spheres' rows were held 7-12 px off, the
  // plate 13 px off on 2 frames; learnt again at the outline's (kRelearnRadiusFraction,
  // track_sequence.cc) they are on the truth, lowered by the outline's radius error as every
  // track without the scale is.
  EXPECT_NE(r.method_reason.find("learnt again at the outline's radius"), std::string::npos);
  for (int k = 0; k < 2; ++k) {
    const RulerError a = RulerSphereError(r, f, k);
    ASSERT_TRUE(a.whole);
    std::printf("[ stats    ] long ruler without the scale (radius %.2f px, truth %.2f), %s "
                "sphere: bias %.3f / %.3f px, scatter %.3f / %.3f px (col / row)\n",
                radius, f.radius_px, k == 0 ? "left" : "right", a.bias.x(), a.bias.y(),
                a.sd.x(), a.sd.y());
    EXPECT_LE(std::abs(a.bias.x()), 0.1) << "sphere " << k;
    EXPECT_LE(std::abs(a.bias.y() - (f.radius_px - radius)), 0.1) << "sphere " << k;
    EXPECT_LE(a.sd.x(), 0.05) << "sphere " << k;
    EXPECT_LE(a.sd.y(), 0.05) << "sphere " << k;
    EXPECT_EQ(r.held_rows[k].held, 0u) << "sphere " << k;
  }
}

// The worst distance of a found centre from its truth over `r`'s frames, which start at film
// frame `first`.
double WorstCentreError(const tracking::SequenceResult& r, const LongRuler& f, size_t first) {
  double worst = 0;
  for (size_t i = 0; i < r.frames.size(); ++i) {
    for (int k = 0; k < 2; ++k) {
      if (!r.frames[i].found[k]) continue;
      worst = std::max(worst, (r.frames[i].centre[k] - f.truth[first + i].centre[k]).norm());
    }
  }
  return worst;
}

// Frames 0-40 and 20-100 with the scale: learnt as the detections' and the plate's referees
// passed it, the hopping right sphere's appearance kept the ruler's band in its lower half, and
// followed, its rows stood still, then stepped, up to 12-13 px off. The dimer's length over the
// trial frames departed by up to 2.7-2.8 px against a noise of 0.05-0.10 px, and the sphere
// learnt again without what stands still behind it keeps it (length_relearn.h).
TEST(PovrayLongRuler, WhereTheLengthDepartsTheHeldSphereIsLearntAgain) {
  const LongRuler& f = Film();
  for (const auto& [frames, first, end] :
       {std::tuple<std::string, size_t, size_t>{"0:40", 0, 40}, {"20:100", 20, 100}}) {
    const tracking::SequenceResult r = Track(f, true, frames);
    ASSERT_EQ(r.frames.size(), end - first) << frames;
    const double worst = WorstCentreError(r, f, first);
    std::printf("[ stats    ] long ruler, frames %s: worst centre %.2f px off; the length %.2f "
                "px, noise %.3f px, departing in %zu of %zu frames\n",
                frames.c_str(), worst, r.length.median_px, r.length.noise_px,
                r.length.departing, r.length.frames);
    EXPECT_NE(r.method_reason.find("the right sphere learnt again from the highlights"),
              std::string::npos)
        << frames << ": " << r.method_reason;
    EXPECT_TRUE(r.relearnt_by_length[1]) << frames;
    EXPECT_FALSE(r.relearnt_by_length[0]) << frames;
    EXPECT_LE(worst, 0.3) << frames;
    EXPECT_EQ(r.length.departing, 0u) << frames;
  }
}

// Frames 10-70: the hopping right sphere, learnt again without the ruler's still edges over
// frames where it flew higher, lands 2 px lower on the window's last frames. Its appearance's
// corners beside the disc then met the ruler's upper edge, which held it: lost on frame 64,
// found again 1.2-1.8 px high on frames 65-69, and nothing warned (the error lies across the
// rod). The still background known in the frame's coordinates is cut wherever the sphere goes
// (still_background.h): every frame within 0.3 px with the scale (0.14 px measured).
TEST(PovrayLongRuler, TheStillBackgroundKeepsALandingSphereOffTheRulersEdge) {
  const LongRuler& f = Film();
  const tracking::SequenceResult r = Track(f, true, "10:70");
  ASSERT_EQ(r.frames.size(), 60u);
  for (int k = 0; k < 2; ++k) {
    EXPECT_TRUE(r.appearance[k].still) << "sphere " << k << " learnt without the ruler";
  }
  size_t found = 0;
  for (const tracking::FrameTrack& t : r.frames) found += t.found[0] && t.found[1];
  const double worst = WorstCentreError(r, f, 10);
  std::printf("[ stats    ] long ruler, frames 10-70: both spheres in %zu of 60 frames, worst "
              "centre %.2f px off\n",
              found, worst);
  EXPECT_EQ(found, 60u);
  EXPECT_LE(worst, 0.3);
}

// Frames 20-80 without the scale: the left sphere's columns 2 px off in some frames, and no
// referee but the length saw it (length_constancy.h): where a sphere is more than a pixel off in
// a frame, the track must say that the dimer's length departs. It passes either way once the
// window is followed.
TEST(PovrayLongRuler, WithoutTheScaleOverFrames20To80TheLengthSaysWhereASphereIsOff) {
  const LongRuler& f = Film();
  const tracking::SequenceResult r = Track(f, false, "20:80");
  ASSERT_EQ(r.frames.size(), 60u);
  const double worst = WorstCentreError(r, f, 20);
  const tracking::LengthConstancy& c = r.length;
  std::printf("[ stats    ] long ruler without the scale, frames 20-80: worst centre %.2f px "
              "off; the length %.2f px, noise %.3f px, departing by up to %.2f px in %zu of %zu "
              "frames\n",
              worst, c.median_px, c.noise_px, c.worst_px, c.departing, c.frames);
  if (worst > 1.0) {
    EXPECT_GT(c.departing, 0u) << "a sphere " << worst << " px off, and the length said nothing";
  }
}

}  // namespace
}  // namespace dimer::footage
