// The tracker on footage it was not designed on: POV-Ray renders (tests/footage) of the dimer in
// every lighting of the issue, and touching spheres (A_r 2.0, 2.1, 2.3), judged against the
// issue's targets (tests/footage/track_accuracy.h): per sphere scatter <= 0.05 px after the
// constant offset, |bias| <= 0.1 px, >= 99 % found; no identity swap; plate row within 0.3 px.
//
// The tracker is told the scale (the sphere radius in pixels from truth.csv), as a user passes
// `--m-per-px` from the camera's calibration: the template method's plate-contact offset rests
// on it. The method is the one the tracker will use by default: the environment variable
// DIMERLAB_POVRAY_METHOD, else the compile-time DIMERLAB_POVRAY_TEST_METHOD (CMake cache
// variable of the same name, default `auto`, the tracker's default). The targets are the issue's
// and are never loosened here: a failing case is a finding about the tracker.
//
// Footage is rendered on first use into the build tree (DIMERLAB_POVRAY_CACHE) and reused while
// its scenes are unchanged (the folder's scene hash): 20 frames per case, 2 exposure slices.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <set>
#include <ostream>
#include <string>
#include <vector>

#include "common/error.h"
#include "common/h5_file.h"
#include "common/trajectory_io.h"
#include "tests/common/test_tmpdir.h"
#include "tests/common/warm_bayer.h"
#include "tests/footage/accuracy_cache.h"
#include "tests/footage/camera_variants.h"
#include "tests/footage/povray_footage.h"
#include "tests/footage/scaled_track.h"
#include "tests/footage/track_accuracy.h"
#include "tracking/io/cine_writer.h"
#include "tracking/dimer_length_scale.h"
#include "tracking/io/frame_source.h"
#include "tracking/io/mosaic_grey.h"
#include "tracking/run_track.h"
#include "tracking/track_sequence.h"

#ifndef DIMERLAB_POVRAY_TEST_METHOD
#define DIMERLAB_POVRAY_TEST_METHOD "centroid"
#endif
#ifndef DIMERLAB_POVRAY_CACHE
#define DIMERLAB_POVRAY_CACHE "povray_footage_cache"
#endif
#ifndef DIMERLAB_POVRAY_ACCURACY_CACHE
#define DIMERLAB_POVRAY_ACCURACY_CACHE "povray_accuracy_cache"
#endif

namespace dimer::footage {
namespace {

constexpr size_t kFrames = 20;
constexpr int kSlices = 2;

std::string TestMethod() {
  const char* env = std::getenv("DIMERLAB_POVRAY_METHOD");
  return env && *env ? env : DIMERLAB_POVRAY_TEST_METHOD;
}

struct Case {
  const char* name;
  Lighting lighting;
  double aspect_ratio;
  int camera = -1;  // index into CameraVariants() (front_point seen by another camera); -1: none
  uint64_t seed = 1;  // the frames' noise seed
};

// gtest prints the parameter by name (test names and messages), not as bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

// Renders (or reuses) the case's footage and returns its folder.
std::string Footage(const Case& c) {
  FootageOptions o = CaseFootageOptions(c.lighting, c.camera);
  o.shape.aspect_ratio = c.aspect_ratio;
  o.seed = c.seed;
  o.subframes = kSlices;
  o.reuse = true;
  o.quiet = true;
  const std::string dir = std::string(DIMERLAB_POVRAY_CACHE) + "/" + c.name;
  std::filesystem::create_directories(DIMERLAB_POVRAY_CACHE);
  WriteFootage(HopMotion(o.shape, kFrames, o.fps), o, dir);
  return dir;
}

// The case's footage tracked with the method under test on 2 threads, measured once per build
// of this program and read back by the case's other checks (tests/footage/accuracy_cache.h).
// A camera with a lens that is not a pinhole is tracked with the lens's calibration, as a lab
// that calibrated it passes `track --lens`.
TrackAccuracy Accuracy(const Case& c) {
  const std::string method = TestMethod();
  const std::string dir = Footage(c);
  return CachedTrackAccuracy(dir, method, 2,
                             std::string(DIMERLAB_POVRAY_ACCURACY_CACHE) + "/" + c.name + "." +
                                 method,
                             LensFileOf(c.camera, dir));
}

class PovrayFootage : public ::testing::TestWithParam<Case> {};

// The footage rendered (or found in the cache) with its truth and tracked, once per case before
// the checks that read it (CTest `povray.render.CASE`, their fixture): without it the checks of
// one case, started together on two cores, would each render the same footage, and each track it.
TEST_P(PovrayFootage, RenderedAndTrackedOnce) {
  const std::string dir = Footage(GetParam());
  double radius = 0;
  const auto truth = ReadTruthCsv(dir + "/truth.csv", &radius);
  EXPECT_EQ(truth.size(), kFrames) << dir << "/truth.csv";
  EXPECT_GT(radius, 0) << dir << "/truth.csv";
  EXPECT_EQ(Accuracy(GetParam()).frames, kFrames);
}

TEST_P(PovrayFootage, TrackerMeetsTheIssueTargets) {
  const Case& c = GetParam();
  const TrackAccuracy a = Accuracy(c);
  std::printf("%s\n%s%s", c.name, AccuracyHeader().c_str(), AccuracyRow(a).c_str());
  ASSERT_EQ(a.frames, kFrames);
  const char* names[2] = {"left", "right"};
  for (int k = 0; k < 2; ++k) {
    const SphereAccuracy& s = a.sphere[k];
    ASSERT_EQ(s.good, kFrames) << "every frame of the footage shows both spheres whole";
    EXPECT_GE(s.found_fraction, kFoundTarget) << names[k] << " sphere found";
    EXPECT_LE(s.bias.norm(), kBiasTargetPx)
        << names[k] << " bias (col, row) = (" << s.bias.x() << ", " << s.bias.y() << ") px";
    EXPECT_LE(s.scatter, kScatterTargetPx) << names[k] << " scatter about the bias, px";
  }
  EXPECT_EQ(a.identity_swaps, 0u);
  EXPECT_EQ(a.plate_found, a.frames) << "frames with a plate row";
  EXPECT_LE(a.plate_max_error, kPlateTargetPx) << "plate row, mean error " << a.plate_bias;
}

// The plate row alone, the issue's target (within 0.3 px of the truth in every frame), checked
// apart from the sphere targets so that a case still short on its spheres (WILL_FAIL above)
// keeps its plate row guarded (CTest `povray.plate.CASE`).
TEST_P(PovrayFootage, PlateRowWithinTheTargetInEveryFrame) {
  const Case& c = GetParam();
  const TrackAccuracy a = Accuracy(c);
  std::printf("[ stats    ] %s plate row: bias %+.3f, max %.3f px, %zu of %zu frames\n", c.name,
              a.plate_bias, a.plate_max_error, a.plate_found, a.frames);
  ASSERT_EQ(a.frames, kFrames);
  EXPECT_EQ(a.plate_found, a.frames) << "frames with a plate row";
  EXPECT_LE(a.plate_max_error, kPlateTargetPx) << "plate row, mean error " << a.plate_bias;
}

// Where a case misses the targets, the track file still says how far its absolute positions may
// be off: /template/offset_err (and `dimerlab track`'s warning above 0.1 px). That stated
// uncertainty must cover the bias, within kCoverageSigmas of it and the bias's own sampling
// error, per sphere and axis, in every case the template method runs on (CTest
// `povray.coverage.CASE`); a case with no offset to state (silhouettes, the centroid) skips.
// Where a case meets the targets, the uncertainty is also the issue's at most 0.3 px, never
// inflated past it (cluttered_backdrop stated 0.48-0.70 px for a bias under 0.06:
// PairsModelError, tracking/sphere/appearance_model.cc).
TEST_P(PovrayFootage, StatedOffsetUncertaintyCoversTheBias) {
  const Case& c = GetParam();
  const TrackAccuracy a = Accuracy(c);
  ASSERT_EQ(a.frames, kFrames);
  if (!a.template_run) GTEST_SKIP() << c.name << ": tracked without a template, no offset";
  const char* names[2] = {"left", "right"};
  const char* axes[2] = {"column", "row"};
  for (int k = 0; k < 2; ++k) {
    const SphereAccuracy& s = a.sphere[k];
    std::printf("[ stats    ] %s %s: bias (%+.3f, %+.3f) px, stated +-(%.3f, %.3f), sampling "
                "+-(%.3f, %.3f): (%.1f, %.1f) sigma\n",
                c.name, names[k], s.bias.x(), s.bias.y(), s.stated_err.x(), s.stated_err.y(),
                s.bias_sampling.x(), s.bias_sampling.y(), s.bias_sigmas.x(), s.bias_sigmas.y());
    for (int ax = 0; ax < 2; ++ax) {
      EXPECT_LE(s.bias_sigmas(ax), kCoverageSigmas)
          << names[k] << " " << axes[ax] << ": bias " << s.bias(ax) << " px, stated +-"
          << s.stated_err(ax) << " px";
      if (a.MeetsTargets()) {
        EXPECT_LE(s.stated_err(ax), 0.3) << names[k] << " " << axes[ax];
      }
    }
  }
}

// The scatter alone, per sphere, in every case (CTest `povray.scatter.CASE`), also those short
// of the targets for other reasons (front_softbox's columns): within the issue's 0.05 px, or,
// where the footage's own Cramér-Rao bound is above that (under-exposed), within
// kScatterBoundFactor of the bound.
TEST_P(PovrayFootage, ScatterWithinTheTargetOrTheFootagesBound) {
  const Case& c = GetParam();
  const TrackAccuracy a = Accuracy(c);
  ASSERT_EQ(a.frames, kFrames);
  const char* names[2] = {"left", "right"};
  for (int k = 0; k < 2; ++k) {
    const SphereAccuracy& s = a.sphere[k];
    const double limit = std::isfinite(s.scatter_bound)
                             ? std::max(kScatterTargetPx, kScatterBoundFactor * s.scatter_bound)
                             : kScatterTargetPx;
    std::printf("[ stats    ] %s %s: scatter %.3f px, bound %.3f px, limit %.3f px\n", c.name,
                names[k], s.scatter, s.scatter_bound, limit);
    EXPECT_LE(s.scatter, limit) << names[k] << " scatter about the bias, px (bound "
                                << s.scatter_bound << ")";
  }
}

// The footage of `c` tracked with 1 and with 2 threads, in chunks of 6 frames (4 chunks, each
// acquiring afresh), the method `track` runs by default; through its lens's calibration when
// its camera has one (track --lens).
std::array<tracking::SequenceResult, 2> TrackWithOneAndTwoThreads(const Case& c) {
  const std::string dir = Footage(c);
  double radius = 0;
  ReadTruthCsv(dir + "/truth.csv", &radius);
  std::array<tracking::SequenceResult, 2> r;
  for (int threads : {1, 2}) {
    tracking::SequenceOptions o;
    o.threads = threads;
    o.chunk_frames = 6;
    o.follower.method = tracking::Method::kAuto;
    o.contact_radius_px = radius;
    if (const std::string lens = LensFileOf(c.camera, dir); !lens.empty()) {
      o.lens = std::make_shared<const tracking::LensCalibration>(
          tracking::ReadLensCalibration(lens));
    }
    auto source = tracking::OpenFrameSource(dir);
    r[threads - 1] = tracking::TrackSequence(*source, o);
  }
  return r;
}

void ExpectIdentical(const std::array<tracking::SequenceResult, 2>& r) {
  ASSERT_EQ(r[0].frames.size(), kFrames);
  ASSERT_EQ(r[1].frames.size(), kFrames);
  for (size_t i = 0; i < kFrames; ++i) {
    EXPECT_EQ(r[0].frames[i].plate_row, r[1].frames[i].plate_row) << "frame " << i;
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(r[0].frames[i].centre[k], r[1].frames[i].centre[k]) << "frame " << i;
    }
  }
}

// The learnt appearance refereed by its detections (tracking/detection_agreement.h) and by the
// plate (tracking/plate_agreement.h). The hopping sphere before the ruler, whose first
// appearance the ruler's edges hold (its rows 6 px off), is learnt again from its highlights
// without the pixels that stand still behind it (learn_method.h, RelearnHeldSpheres) and then
// followed: its rows and columns within the targets' 0.1 px of the truth and scattering by no
// more than 0.05 px, and the referee passes it. The resting sphere, whose rows the ruler holds
// (0.09 px per px of the plate's), is learnt again from its own rough centres without them
// and a margin about them, and with its resting rows set by the plate (RelearnHeldByThePlate):
// its rows then move more with the plate, scatter about the truth by no more than the target's
// 0.05 px (0.025; held: 0.135; without the margin kStillBackgroundMarginPx: 0.047), and their
// bias lies within twice their stated uncertainty. On front_point, where both follow the
// spheres, nothing is learnt again.
TEST(PovrayDetectionAgreement, TheSphereARulerHoldsIsLearntAgainAndFollowed) {
  for (const Case& c : {Case{"ruler_above_plate", Lighting::kRulerAbovePlate, 3.9},
                        Case{"front_point", Lighting::kFrontPoint, 3.9}}) {
    const std::string dir = Footage(c);
    double radius = 0;
    const std::vector<TruthRow> truth = ReadTruthCsv(dir + "/truth.csv", &radius);
    tracking::SequenceOptions o;
    o.threads = 2;
    o.follower.method = tracking::Method::kAuto;
    o.contact_radius_px = radius;
    auto source = tracking::OpenFrameSource(dir);
    const tracking::SequenceResult r = tracking::TrackSequence(*source, o);
    ASSERT_EQ(r.method, tracking::Method::kTemplate) << c.name;
    ASSERT_EQ(r.frames.size(), truth.size()) << c.name;
    const bool ruler = std::string(c.name) == "ruler_above_plate";
    for (int k = 0; k < 2; ++k) {
      const tracking::DetectionAgreement& a = r.detection_agreement[k];
      std::printf("[ stats    ] %s sphere %d: relearnt %d, slope %.2f +- %.2f (axis %d), "
                  "learnt %.2f px, rough %.2f px\n",
                  c.name, k, int(r.relearnt[k]), a.slope, a.slope_err, a.axis, a.learnt_sd,
                  a.rough_sd);
      EXPECT_TRUE(a.agrees) << c.name << " sphere " << k;
    }
    for (int k = 0; k < 2; ++k) {
      const tracking::PlateAgreement& p = r.plate_agreement[k];
      std::printf("[ stats    ] %s sphere %d: relearnt by the plate %d, rows on the plate's "
                  "%.2f +- %.2f over %zu resting frames\n",
                  c.name, k, int(r.relearnt_by_plate[k]), p.slope, p.slope_err, p.frames);
      EXPECT_TRUE(p.agrees) << c.name << " sphere " << k;
    }
    EXPECT_EQ(r.relearnt[0], ruler) << c.name;
    EXPECT_EQ(r.relearnt_by_plate[0], ruler) << c.name;
    EXPECT_EQ(r.relearnt[1], ruler) << c.name;
    EXPECT_FALSE(r.relearnt_by_plate[1]) << c.name;
    if (!ruler) continue;
    EXPECT_NE(r.method_reason.find("learnt again without what stands still"), std::string::npos)
        << r.method_reason;
    {
      // The resting left sphere's rows against the truth.
      double sum = 0, sum2 = 0;
      for (size_t i = 0; i < truth.size(); ++i) {
        ASSERT_TRUE(r.frames[i].found[0]) << "frame " << i;
        const double e = r.frames[i].centre[0].y() - truth[i].centre[0].y();
        sum += e, sum2 += e * e;
      }
      const double bias = sum / double(truth.size());
      const double sd = std::sqrt(sum2 / double(truth.size()) - bias * bias);
      std::printf("[ stats    ] ruler's left sphere: row bias %.3f px, scatter %.3f px, stated "
                  "+- %.3f px\n",
                  bias, sd, r.offsets.row[0].err);
      EXPECT_LE(sd, 0.05);
      EXPECT_LE(std::abs(bias), 2 * r.offsets.row[0].err);
    }
    EXPECT_NE(r.method_reason.find("learnt again from its highlights"), std::string::npos)
        << r.method_reason;
    // The right sphere against the truth: mean error and scatter about it per axis.
    Eigen::Vector2d sum(0, 0), sum2(0, 0);
    int n = 0;
    for (size_t i = 0; i < truth.size(); ++i) {
      if (!r.frames[i].found[1]) continue;
      const Eigen::Vector2d e = r.frames[i].centre[1] - truth[i].centre[1];
      sum += e, sum2 += e.cwiseProduct(e), ++n;
    }
    ASSERT_EQ(n, int(truth.size()));
    const Eigen::Vector2d bias = sum / n;
    const Eigen::Vector2d sd = (sum2 / n - bias.cwiseProduct(bias)).cwiseSqrt();
    std::printf("[ stats    ] ruler's right sphere: bias %.3f / %.3f px, scatter %.3f / %.3f px "
                "(col / row)\n",
                bias.x(), bias.y(), sd.x(), sd.y());
    EXPECT_LE(bias.norm(), 0.1);
    EXPECT_LE(sd.x(), 0.05);
    EXPECT_LE(sd.y(), 0.05);
  }
}

// The plate is the edge the dimer stands on at every acquisition, not only at the film's first
// frame: ruler_above_plate tracked in chunks of 3 frames, each acquired afresh. In its frame 3
// the detector takes the ruler's lower edge (11 px above the plate) for the plate, and the
// spheres searched for above it were missed, that frame's plate row 11 px off; they are found
// above the edge below it, on which they stand (FrameFollower::Acquire).
TEST(PovrayRulerInChunks, EveryAcquisitionTakesTheEdgeTheDimerStandsOn) {
  const Case c{"ruler_above_plate", Lighting::kRulerAbovePlate, 3.9};
  const std::string dir = Footage(c);
  double radius = 0;
  const std::vector<TruthRow> truth = ReadTruthCsv(dir + "/truth.csv", &radius);
  tracking::SequenceOptions o;
  o.threads = 2;
  o.chunk_frames = 3;
  o.follower.method = tracking::Method::kAuto;
  o.contact_radius_px = radius;
  auto source = tracking::OpenFrameSource(dir);
  const tracking::SequenceResult r = tracking::TrackSequence(*source, o);
  ASSERT_EQ(r.frames.size(), truth.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    const tracking::FrameTrack& f = r.frames[i];
    EXPECT_LE(std::abs(f.plate_row - truth[i].plate_row), kPlateTargetPx) << "frame " << i;
    for (int k = 0; k < 2; ++k) {
      ASSERT_TRUE(f.found[k]) << "frame " << i << " sphere " << k;
      EXPECT_LE((f.centre[k] - truth[i].centre[k]).norm(), 0.3) << "frame " << i << " sphere " << k;
    }
  }
}

// Bit-identical for 1 and 2 threads, where the sequence-level steps run: the template learnt,
// the plate's contact line measured from the spheres' mirror images and its motion scaled by
// the resting sphere (mirror_plate).
TEST(PovrayFootageThreads, MirrorPlateIdenticalForOneAndTwoThreads) {
  const auto r = TrackWithOneAndTwoThreads(Case{"mirror_plate", Lighting::kMirrorPlate, 3.9});
  EXPECT_TRUE(r[0].plate_shift.applied);
  EXPECT_EQ(r[0].plate_shift.value, r[1].plate_shift.value);
  EXPECT_EQ(r[0].plate_scale.scale, r[1].plate_scale.scale);
  ExpectIdentical(r);
}

// And where the over-exposed plate's level is shared by the frames and every clipped row is
// fitted again at it (tracking/plate/clipped_edge.h): every frame's plate clips here.
TEST(PovrayFootageThreads, OverexposedPlateIdenticalForOneAndTwoThreads) {
  const auto r = TrackWithOneAndTwoThreads(Case{"overexposed", Lighting::kOverexposed, 3.9});
  EXPECT_EQ(r[0].plate_clip.frames, kFrames);
  EXPECT_TRUE(r[0].plate_clip.level.found());
  EXPECT_EQ(r[0].plate_clip.level.value, r[1].plate_clip.level.value);
  EXPECT_EQ(r[0].plate_clip.refitted, r[1].plate_clip.refitted);
  EXPECT_GE(r[0].plate_clip.refitted, kFrames - 1);
  ExpectIdentical(r);
}

// And where the learning is seeded from the highlights, the film's split chosen by the dimer's
// length and the frames that disagree left out (tracking/sphere/highlight_seed.h): the cluttered
// backdrop.
TEST(PovrayFootageThreads, HighlightSeededLearningIdenticalForOneAndTwoThreads) {
  const auto r = TrackWithOneAndTwoThreads(
      Case{"cluttered_backdrop", Lighting::kClutteredBackdrop, 3.9});
  EXPECT_NE(r[0].method_reason.find("from the highlights"), std::string::npos)
      << r[0].method_reason;
  EXPECT_NE(r[0].method_reason.find("left out"), std::string::npos) << r[0].method_reason;
  EXPECT_EQ(r[0].method_reason, r[1].method_reason);
  ExpectIdentical(r);
}

// And where a sphere held by the ruler behind it is learnt again from its highlights without
// the pixels that stand still (tracking/learn_method.h, RelearnHeldSpheres).
TEST(PovrayFootageThreads, RelearntSphereIdenticalForOneAndTwoThreads) {
  const auto r =
      TrackWithOneAndTwoThreads(Case{"ruler_above_plate", Lighting::kRulerAbovePlate, 3.9});
  EXPECT_TRUE(r[0].relearnt[1]) << r[0].method_reason;
  EXPECT_EQ(r[0].relearnt, r[1].relearnt);
  EXPECT_EQ(r[0].method_reason, r[1].method_reason);
  ExpectIdentical(r);
}

// And where every frame is undistorted by the lens's calibration first (track --lens).
TEST(PovrayFootageThreads, UndistortedFramesIdenticalForOneAndTwoThreads) {
  const int camera = CameraIndex("pincushion_lens");
  ASSERT_GE(camera, 0);
  const auto r =
      TrackWithOneAndTwoThreads(Case{"pincushion_lens", Lighting::kFrontPoint, 3.9, camera});
  ASSERT_TRUE(r[0].lens);
  EXPECT_GT(r[0].lens_max_shift_px, 2.0);
  ExpectIdentical(r);
}

// Through a camera turned about its axis (half a degree, 8 degrees), the track file's metres run
// along the plate: the resting left sphere's centre stands R above the plate, and the dimer's
// axis angle is the scene's, both within the issue's 0.1 px bias (read off level axes at half a
// degree, the angle is off by the roll, 8.7 mrad, and the left sphere's height by 0.6 px).
// CTest `povray.metres.CASE`.
class PovrayRolledCamera : public ::testing::TestWithParam<int> {};

TEST_P(PovrayRolledCamera, MetresRunAlongThePlate) {
  const int camera = GetParam();
  const Case c{CameraVariants()[size_t(camera)].name, Lighting::kFrontPoint, 3.9, camera};
  const std::string dir = Footage(c);
  const FootageOptions o = CaseFootageOptions(c.lighting, c.camera);
  dimer::testing::TempDir tmp;
  tracking::TrackArgs t;
  t.input = dir;
  t.output = tmp / "track.h5";
  t.m_per_px = o.camera.m_per_px;
  t.quiet = true;
  tracking::RunTrack(t);
  const Trajectory traj = ReadTrajectory(H5Reader(t.output));
  ASSERT_EQ(traj.size(), kFrames);
  const Motion m = HopMotion(o.shape, kFrames, o.fps);
  const double s = o.camera.m_per_px, r = 0.5 * o.shape.diameter;
  const double length_px = o.shape.CentreDistance() / s;
  double height = 0, angle = 0;
  for (size_t i = 0; i < kFrames; ++i) {
    const Instant truth = m.at(m.t[i]);
    const Eigen::Vector2d axis = truth.right - truth.left;
    height += (traj.tip_left[i].y() - traj.plate_z[i] - r) / s;
    angle += traj.theta[i] - std::atan2(axis.y(), axis.x());
  }
  height /= double(kFrames);
  angle /= double(kFrames);
  std::printf("[ stats    ] %s: resting sphere's centre above the plate - R %+.3f px, axis angle "
              "%+.5f rad (%+.3f px at the far sphere)\n",
              c.name, height, angle, angle * length_px);
  EXPECT_LE(std::abs(height), kBiasTargetPx) << "left sphere's height above the plate - R, px";
  EXPECT_LE(std::abs(angle) * length_px, kBiasTargetPx) << "axis angle error " << angle << " rad";
}

std::vector<int> RolledCameras() {
  std::vector<int> out;
  for (size_t i = 0; i < CameraVariants().size(); ++i) {
    if (CameraVariants()[i].roll_deg != 0) out.push_back(int(i));
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(
    Cameras, PovrayRolledCamera, ::testing::ValuesIn(RolledCameras()),
    [](const ::testing::TestParamInfo<int>& p) { return CameraVariants()[size_t(p.param)].name; });

// And through a camera turned 8 degrees: the plate edge's slope is measured once for the
// sequence, before any chunk runs, from frames of the first chunk.
TEST(PovrayFootageThreads, RolledCameraIdenticalForOneAndTwoThreads) {
  int camera = -1;
  for (size_t i = 0; i < CameraVariants().size(); ++i) {
    if (CameraVariants()[i].roll_deg >= 8) camera = int(i);
  }
  ASSERT_GE(camera, 0);
  const auto r = TrackWithOneAndTwoThreads(
      Case{CameraVariants()[size_t(camera)].name, Lighting::kFrontPoint, 3.9, camera});
  EXPECT_TRUE(r[0].plate_slope.applied) << r[0].plate_slope.reason;
  EXPECT_EQ(r[0].plate_slope.value, r[1].plate_slope.value);
  ExpectIdentical(r);
}

// A high-speed sensor's hot pixels (tracking/io/defect_pixels.h): 60 of them (1 in 3,400 pixels,
// seeded; some in the spheres' path) put on the front_point footage at full scale. Without the
// repair one sphere's scatter was 0.54 px.
TEST(PovrayStuckPixels, HotPixelsAreFoundAndReplacedAndTheTargetsStillMet) {
  const std::string src = Footage(Case{"front_point", Lighting::kFrontPoint, 3.9});
  dimer::testing::TempDir tmp;
  const std::string dir = tmp / "hot";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(src + "/truth.csv", dir + "/truth.csv");
  std::mt19937 rng(7);
  std::vector<cv::Point> hot;
  for (int i = 0; i < 60; ++i) {
    const int col = int(rng() % 640);  // (one statement each: the order of the draws is fixed)
    hot.emplace_back(col, int(rng() % 320));
  }
  std::vector<cv::Mat> frames;
  for (const auto& row : ReadTruthCsv(src + "/truth.csv")) {
    cv::Mat img = cv::imread(src + "/" + row.file, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(img.empty()) << row.file;
    for (const cv::Point& p : hot) img.at<uint8_t>(p) = 255;
    ASSERT_TRUE(cv::imwrite(dir + "/" + row.file, img));
    frames.push_back(img);
  }
  tracking::MemorySource source(frames);
  tracking::SequenceOptions o;
  o.follower.method = tracking::Method::kAuto;
  o.threads = 2;
  const tracking::SequenceResult r = tracking::TrackSequence(source, o);
  std::set<std::pair<int, int>> want, got;
  for (const cv::Point& p : hot) want.insert({p.x, p.y});
  for (const cv::Point& p : r.defects.at) got.insert({p.x, p.y});
  EXPECT_EQ(got, want);
  const TrackAccuracy a = MeasureTrackAccuracy(dir, TestMethod(), 2);
  std::printf("front_point with 60 hot pixels\n%s%s", AccuracyHeader().c_str(),
              AccuracyRow(a).c_str());
  std::string why;
  EXPECT_TRUE(a.MeetsTargets(&why)) << why;
}

// The front_point footage as two Phantom cameras would store it: a 10-bit camera's packed .cine
// (levels 0..1020), and a colour camera's raw Bayer mosaic (RGGB, 8 bits) under a warm lamp
// (red, green and blue see 1, 0.8 and 0.55 of it). Both must meet the targets. Found when this
// was added: the 10-bit file lost the rows (the tracker's levels are fractions of the 16-bit full
// scale; now scaled by the header's RealBPP, tracking/io/level_scale.h), and the mosaic filtered
// on every pixel left scatter 0.068 px (now balanced per file, tracking/io/mosaic_grey.h).
TEST(PovrayCine, TenBitAndColourPhantomFilesMeetTheTargets) {
  const std::string src = Footage(Case{"front_point", Lighting::kFrontPoint, 3.9});
  dimer::testing::TempDir tmp;
  std::vector<cv::Mat> ten, bayer, narrow, wide;
  for (const auto& row : ReadTruthCsv(src + "/truth.csv")) {
    const cv::Mat img = cv::imread(src + "/" + row.file, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(img.type(), CV_8UC1) << row.file;
    cv::Mat t;
    img.convertTo(t, CV_16U, 4);
    ten.push_back(t);
    bayer.push_back(dimer::testing::WarmBayerMosaic(img));
    // The colour camera's film made grey by its own software (a 3x3 filter) and exported as 16-bit
    // frames of 8-bit levels (x 257): a dark backdrop whose noise the filter and the 8-bit step
    // hide. A highlight floor of half a 16-bit level makes every noisy pixel a highlight and puts
    // the spheres 30 px off; the floor is the frame's own level step (learn_method.cc).
    cv::Mat g8, g16;
    tracking::MosaicFilterToGrey(bayer.back()).convertTo(g8, CV_8U);
    g8.convertTo(g16, CV_16U, 257);
    narrow.push_back(g8);
    wide.push_back(g16);
  }
  tracking::CineWriteOptions o;
  o.pixels = tracking::CinePixels::k10BitPacked;
  tracking::WriteCine(tmp / "ten.cine", ten, o);
  o.pixels = tracking::CinePixels::k8Bit;
  o.cfa = 3;
  tracking::WriteCine(tmp / "bayer.cine", bayer, o);
  o.cfa = 0;
  tracking::WriteCine(tmp / "narrow.cine", narrow, o);
  o.pixels = tracking::CinePixels::k16Bit;
  tracking::WriteCine(tmp / "wide.cine", wide, o);
  auto measure = [&](const char* name) {
    const TrackAccuracy a = MeasureTrackAccuracy(src, TestMethod(), 2, true, {}, tmp / name);
    std::printf("front_point as %s\n%s%s", name, AccuracyHeader().c_str(), AccuracyRow(a).c_str());
    return a;
  };
  for (const char* name : {"ten.cine", "bayer.cine"}) {
    std::string why;
    EXPECT_TRUE(measure(name).MeetsTargets(&why)) << name << ": " << why;
  }
  // The filtered film misses the scatter target in 8 bits too (the filter's leak at the
  // highlights): its 16-bit export must track as its 8-bit frames do. Its
  // learning is seeded from highlights that scatter by 2-13 px, and there the registrations'
  // whole-pixel peaks are near ties that float rounding decides: the same seeds (checked by
  // hand) give columns 0.016 px apart for the 8-bit frames and their x 257 copy, and per-frame
  // positions up to 0.05 px apart. The biases must
  // agree within a quarter of the uncertainty the track file states for them, at least 0.01 px.
  const TrackAccuracy a8 = measure("narrow.cine"), a16 = measure("wide.cine");
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(a16.sphere[k].found, a8.sphere[k].found) << k;
    for (int axis = 0; axis < 2; ++axis) {
      const double tolerance = std::max(0.01, 0.25 * a8.sphere[k].stated_err(axis));
      EXPECT_NEAR(a16.sphere[k].bias(axis), a8.sphere[k].bias(axis), tolerance)
          << "sphere " << k << " axis " << axis;
    }
    EXPECT_NEAR(a16.sphere[k].scatter, a8.sphere[k].scatter, 0.01) << k;
  }
  EXPECT_EQ(a16.identity_swaps, 0u);
}

// A lens that is not a pinhole (`track --lens`): the front_point scene through a lens with
// pincushion distortion (k1 = 0.5: 0.67 % at the frame's far corner), the dimer 35 mm right of
// the optical axis, where the lens moves the right sphere's image by 0.6 px and the left's by
// 0.06 (tests/footage/camera_variants.h, pincushion_lens). Tracked as recorded, the right sphere
// is off by that and the dimer reads 0.5 px long; with the lens's calibration (the folder's
// lens.yml, OpenCV's calibration sample's layout), the frames are undistorted first and the
// right sphere is within the 0.1 px target. What the undistortion costs: the tracker reads
// resampled frames ~0.05 px to the right in its columns (the pinhole film shifted by a quarter
// pixel with Lanczos read 0.045 px long; the undistorted frames themselves are within 0.02 px of
// the pinhole's), so this case's left
// column, 0.101 px, is at the target and the case is registered short of it (5 of 9 noise seeds
// meet it); the scatter, rows, plate and stated uncertainties all hold.
TEST(PovrayLens, TheLensCalibrationTakesTheBendOut) {
  const int camera = CameraIndex("pincushion_lens");
  ASSERT_GE(camera, 0);
  const std::string dir = Footage(Case{"pincushion_lens", Lighting::kFrontPoint, 3.9, camera});
  TrackerKnobs with_lens;
  with_lens.lens = LensFileOf(camera, dir);
  ASSERT_TRUE(std::filesystem::exists(with_lens.lens));
  const TrackAccuracy bent = MeasureTrackAccuracy(dir, TestMethod(), 2);
  const TrackAccuracy straight = MeasureTrackAccuracy(dir, TestMethod(), 2, true, with_lens);
  std::printf("pincushion_lens, as recorded and with --lens\n%s%s%s", AccuracyHeader().c_str(),
              AccuracyRow(bent).c_str(), AccuracyRow(straight).c_str());
  // As recorded: the right sphere where the lens put it, 0.6 px out.
  EXPECT_GT(bent.sphere[1].bias.x(), 0.4);
  // Undistorted: within the target, and the right sphere's column within 0.1 px.
  EXPECT_LE(straight.sphere[1].bias.norm(), kBiasTargetPx);
  EXPECT_LE(std::abs(straight.sphere[1].bias.x()), 0.1);
  // The dimer's length (the right column less the left) within 0.2 px, 0.5 as recorded.
  const double length_bent = bent.sphere[1].bias.x() - bent.sphere[0].bias.x();
  const double length_straight = straight.sphere[1].bias.x() - straight.sphere[0].bias.x();
  EXPECT_GT(length_bent, 0.4);
  EXPECT_LT(std::abs(length_straight), 0.2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_LE(straight.sphere[k].scatter, kScatterTargetPx) << k;
    EXPECT_EQ(straight.sphere[k].found, straight.sphere[k].good) << k;
  }
  EXPECT_EQ(straight.identity_swaps, 0u);
  EXPECT_LE(straight.plate_max_error, kPlateTargetPx);
}

// A sphere leaving the frame (a drift carries the dimer across the field of view): the front_point
// footage seen through a 290 px window panning left by 2 px a frame (the spheres move 2.25 px a
// frame in it), so the right sphere reaches the window's edge at frame 13. A cut sphere cannot be
// matched whole, and the best match left inside lay 9-10 px short of it (POV-Ray, found when this
// was added): such a frame must give no right sphere rather than a wrong one
// (tracking/match_scores.h), and the left sphere, whole in every frame, is found in all.
// What `track` says of how precisely it followed each sphere (tracking/track_precision.h): the
// centres' frame-to-frame scatter, measured on the track alone, must be what the truth shows,
// and the footage's bound must flag footage too poor for sub-pixel work. The 20-frame films
// halved (0.4 mm/px, spheres of 11.9 px), some of the noise the halving averaged away put back
// (1.4 grey levels in all; with 2, as the film of the whole pipeline at that scale has, the
// quarter-light film's 20 frames give no learning frame and auto falls back to the centroid):
// front_point is tracked at its bound. The quarter-light film was poor footage (bound 0.17-0.18
// px, the truth scattering 0.28-0.95) while ECC registered the learning frames; the quick step's
// registrations (sphere/fast_follow.h) average a sharper appearance, which tracks it to 0.07-0.11
// px (bound 0.06-0.08), so the flag must say it is not poor; the flag's own rule is held by
// TrackPrecision's unit tests.
TEST(PovrayPrecision, TheScatterIsMeasuredAndPoorFootageIsFlagged) {
  for (const Case& c : {Case{"front_point", Lighting::kFrontPoint, 3.9},
                        Case{"underexposed", Lighting::kUnderexposed, 3.9}}) {
    SCOPED_TRACE(c.name);
    const std::string src = Footage(c);
    double radius = 0;
    const std::vector<TruthRow> truth = ReadTruthCsv(src + "/truth.csv", &radius);
    std::vector<cv::Mat> frames;
    std::mt19937_64 rng(17);
    std::normal_distribution<double> noise(0, 1.0);  // 1.4 in all with the halved 1
    for (const TruthRow& row : truth) {
      const cv::Mat img = cv::imread(src + "/" + row.file, cv::IMREAD_UNCHANGED);
      ASSERT_EQ(img.type(), CV_8UC1) << row.file;
      cv::Mat half;
      cv::resize(img, half, cv::Size(img.cols / 2, img.rows / 2), 0, 0, cv::INTER_AREA);
      for (int y = 0; y < half.rows; ++y) {
        for (int x = 0; x < half.cols; ++x) {
          uint8_t& v = half.at<uint8_t>(y, x);
          v = cv::saturate_cast<uint8_t>(v + noise(rng));
        }
      }
      frames.push_back(half);
    }
    tracking::MemorySource source(frames);
    tracking::SequenceOptions o;
    o.follower.method = tracking::Method::kAuto;
    o.contact_radius_px = radius / 2;
    o.threads = 2;
    const tracking::SequenceResult r = tracking::TrackSequence(source, o);
    ASSERT_EQ(r.frames.size(), truth.size());
    ASSERT_EQ(r.method, tracking::Method::kTemplate) << r.method_reason;
    for (int k = 0; k < 2; ++k) {
      const tracking::SpherePrecision& p = r.precision[k];
      // The truth's frame-to-frame scatter: the errors' sd per axis (a constant offset aside);
      // pixel centres halve as (x + 0.5) / 2 - 0.5.
      Eigen::Vector2d sum(0, 0), sum2(0, 0);
      int n = 0;
      for (size_t i = 0; i < truth.size(); ++i) {
        if (!r.frames[i].found[k]) continue;
        const Eigen::Vector2d t = (truth[i].centre[k].array() + 0.5) / 2 - 0.5;
        const Eigen::Vector2d e = r.frames[i].centre[k] - t;
        sum += e, sum2 += e.cwiseProduct(e), ++n;
      }
      ASSERT_GE(n, 18) << k;
      const Eigen::Vector2d sd = (sum2 / n - (sum / n).cwiseProduct(sum / n)).cwiseSqrt();
      std::printf("[ stats    ] %s sphere %d: measured %.3f / %.3f px, truth's sd %.3f / %.3f, "
                  "bound %.3f / %.3f\n",
                  c.name, k, p.measured.x(), p.measured.y(), sd.x(), sd.y(), p.bound.x(),
                  p.bound.y());
      for (int axis = 0; axis < 2; ++axis) {
        EXPECT_GT(p.measured[axis], 0.5 * sd[axis]) << k << " axis " << axis;
        EXPECT_LT(p.measured[axis], 2.0 * sd[axis]) << k << " axis " << axis;
        EXPECT_GT(p.bound[axis], 0.0) << k << " axis " << axis;
      }
      EXPECT_TRUE(p.followed) << k;
      // Poor exactly where the truth scatters beyond the flag's threshold.
      EXPECT_EQ(p.poor, sd.maxCoeff() > tracking::kPoorFootageBoundPx) << k;
    }
  }
}

TEST(PovrayLeavingTheFrame, ASphereCutByTheFramesEdgeIsNotFoundBesideItself) {
  const std::string src = Footage(Case{"front_point", Lighting::kFrontPoint, 3.9});
  double radius = 0;
  const std::vector<TruthRow> truth = ReadTruthCsv(src + "/truth.csv", &radius);
  constexpr int kWidth = 290, kFirstCol = 150, kPanPx = 2;
  std::vector<cv::Mat> frames;
  for (size_t i = 0; i < truth.size(); ++i) {
    const cv::Mat img = cv::imread(src + "/" + truth[i].file, cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(img.empty()) << truth[i].file;
    const int col = kFirstCol - kPanPx * int(i);
    frames.push_back(img(cv::Rect(col, 0, kWidth, img.rows)).clone());
  }
  tracking::MemorySource source(frames);
  tracking::SequenceOptions o;
  o.follower.method = tracking::Method::kAuto;
  o.contact_radius_px = radius;
  o.threads = 2;
  const tracking::SequenceResult r = tracking::TrackSequence(source, o);
  ASSERT_EQ(r.frames.size(), truth.size());
  size_t right_found_whole = 0, right_whole = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    const double shift = kFirstCol - kPanPx * double(i);
    const double right_edge = truth[i].centre[1].x() - shift + radius;
    for (int k = 0; k < 2; ++k) {
      if (!r.frames[i].found[k]) continue;
      const Eigen::Vector2d t = truth[i].centre[k] - Eigen::Vector2d(shift, 0);
      // The constant offsets are those of the footage's other tests (< 0.3 px); a match beside
      // the sphere is pixels off.
      EXPECT_LT((r.frames[i].centre[k] - t).norm(), 0.5)
          << "frame " << i << ", sphere " << k << " (right edge at col " << right_edge << ")";
    }
    EXPECT_TRUE(r.frames[i].found[0]) << "frame " << i;
    if (right_edge < kWidth - 8) ++right_whole, right_found_whole += r.frames[i].found[1];
  }
  std::printf("[ stats    ] right sphere found in %zu of the %zu frames it is whole in, matches "
              "dropped (score, length) left %zu %zu, right %zu %zu\n",
              right_found_whole, right_whole, r.scores.dropped[0], r.scores.dropped_length[0],
              r.scores.dropped[1], r.scores.dropped_length[1]);
  EXPECT_EQ(right_found_whole, right_whole);
}

// Footage of `motion` with options `o`, rendered (or found) in the cache as `name`.
std::string CachedFilm(const std::string& name, FootageOptions o, const Motion& motion) {
  o.reuse = true;
  o.quiet = true;
  const std::string dir = std::string(DIMERLAB_POVRAY_CACHE) + "/" + name;
  std::filesystem::create_directories(DIMERLAB_POVRAY_CACHE);
  WriteFootage(motion, o, dir);
  return dir;
}

// The dimer drifting out of the field of view (the camera still): the front_point scene with
// the dimer resting on the still plate and sliding right, from 1 px a frame to 4 px a frame by
// frame 8 (a 30 us exposure: it blurs by 0.2 px), the right sphere leaving by the frame's right
// edge over frames 10-22, then the left over 47-58, none in view in the last two of 61 frames.
// Each sphere whole in view (8 px clear of the edge, as above) is found under its own name (no
// identity swap), its mean error within the issue's 0.1 px and every frame within 0.5 px; a
// sphere wholly out of view is not found (the track file's NaN); one at least half in view is
// found (the right one placed by the dimer, the left one alone in view by its own motion:
// tracking/cut_spheres.h), off its whole frames' bias by at most max(0.1 px, 2 stated sigma). (At a steady 4 px a frame from frame 0 both spheres were
// followed 1.6-1.8 px off in frames 1-2, where the follower's first prediction is the
// acquisition's position.) CTest `povray.leaving_the_frame`.
TEST(PovrayLeavingTheFrame, OneSphereLeavesThenTheOtherAndNeitherIsSwappedOrInvented) {
  FootageOptions o = FootageOptions::For(Lighting::kFrontPoint);
  o.exposure_s = 30e-6;
  o.subframes = kSlices;
  constexpr size_t kDriftFrames = 61;
  const double m = o.camera.m_per_px, rs = 0.5 * o.shape.diameter, l = o.shape.CentreDistance();
  std::vector<Pose> poses;
  double x = 0;
  for (size_t i = 0; i < kDriftFrames; ++i) {
    poses.push_back({double(i) / o.fps, x, rs, 0.0, 0.0});
    x += std::min(4.0, 1.0 + 0.375 * double(i)) * m;
  }
  o.camera.centre_x = poses[10].x + 0.5 * l + rs - 320 * m;  // right sphere's edge at col 639.5
  const std::string dir = CachedFilm("leaving_both_edges", o, PoseMotion(o.shape, poses));
  double radius = 0;
  const std::vector<TruthRow> truth = ReadTruthCsv(dir + "/truth.csv", &radius);
  ASSERT_EQ(truth.size(), kDriftFrames);
  std::vector<cv::Mat> frames;
  for (const TruthRow& row : truth) frames.push_back(cv::imread(dir + "/" + row.file,
                                                                cv::IMREAD_UNCHANGED));
  tracking::MemorySource source(frames);
  tracking::SequenceOptions so;
  so.follower.method = tracking::Method::kAuto;
  so.contact_radius_px = radius;
  so.threads = 2;
  const tracking::SequenceResult r = tracking::TrackSequence(source, so);
  ASSERT_EQ(r.frames.size(), kDriftFrames);
  tracking::SequenceResult chunked_one;
  const int width = frames[0].cols;
  const char* names[2] = {"left", "right"};
  for (int k = 0; k < 2; ++k) {
    Eigen::Vector2d sum(0, 0);
    size_t whole = 0, found_whole = 0, out = 0, found_out = 0, half = 0, found_half = 0, cut = 0;
    double cut_worst = 0;  // the worst |error - whole bias| over the stated 2 sigma (0.1 px floor)
    for (size_t i = 0; i < kDriftFrames; ++i) {
      const double left_edge = truth[i].centre[k].x() - radius;
      const bool is_whole = left_edge + 2 * radius < width - 8, is_out = left_edge > width;
      whole += is_whole;
      const tracking::FrameTrack& f = r.frames[i];
      if (is_out) ++out, found_out += f.found[k];
      if (truth[i].centre[k].x() < width - 0.5) ++half, found_half += f.found[k];
      if (!f.found[k]) continue;
      const Eigen::Vector2d e = f.centre[k] - truth[i].centre[k];
      const Eigen::Vector2d crossed = f.centre[k] - truth[i].centre[1 - k];
      EXPECT_LT(e.norm(), crossed.norm()) << names[k] << " frame " << i << ": swapped";
      EXPECT_LT(e.norm(), 0.5) << names[k] << " frame " << i;
      if (is_whole) ++found_whole, sum += e;
    }
    const Eigen::Vector2d bias = found_whole ? Eigen::Vector2d(sum / double(found_whole)) : sum;
    for (size_t i = 0; i < kDriftFrames; ++i) {
      const tracking::FrameTrack& f = r.frames[i];
      if (!f.found[k] || !f.cut[k]) continue;
      ++cut;
      const Eigen::Vector2d e = f.centre[k] - truth[i].centre[k] - bias;
      for (int axis = 0; axis < 2; ++axis) {
        const double allowed = std::max(kBiasTargetPx, 2 * f.sigma_px[k][axis]);
        cut_worst = std::max(cut_worst, std::abs(e[axis]) / allowed);
      }
    }
    std::printf("[ stats    ] %s sphere: found in %zu of the %zu frames it is whole in, %zu of the "
                "%zu it is at least half in view (%zu cut, worst %.2f of the allowed), in %zu of "
                "the %zu it is out of view; bias (%+.3f, %+.3f) px\n",
                names[k], found_whole, whole, found_half, half, cut, cut_worst, found_out, out,
                bias.x(), bias.y());
    EXPECT_EQ(found_whole, whole) << names[k];
    EXPECT_EQ(found_half, half) << names[k];
    EXPECT_GT(cut, 0u) << names[k] << " never found cut: the film is not what it says";
    EXPECT_LE(cut_worst, 1.0) << names[k];
    EXPECT_EQ(found_out, 0u) << names[k];
    EXPECT_GT(out, 0u) << names[k] << " sphere never leaves: the film is not what it says";
    EXPECT_LE(bias.norm(), kBiasTargetPx) << names[k];
  }
  // The cut spheres placed across chunks' seams (7-frame chunks put seams among the cut frames
  // of both exits) are the same for 1 and 2 threads, and found where one chunk finds them.
  for (const int threads : {1, 2}) {
    tracking::SequenceOptions short_chunks = so;
    short_chunks.threads = threads;
    short_chunks.chunk_frames = 7;
    tracking::MemorySource again(frames);
    const tracking::SequenceResult c = tracking::TrackSequence(again, short_chunks);
    ASSERT_EQ(c.frames.size(), kDriftFrames);
    size_t cut_long = 0, cut_short = 0;
    for (size_t i = 0; i < kDriftFrames; ++i) {
      for (int k = 0; k < 2; ++k) {
        cut_long += r.frames[i].found[k] && r.frames[i].cut[k];
        cut_short += c.frames[i].found[k] && c.frames[i].cut[k];
        EXPECT_EQ(c.frames[i].found[k], r.frames[i].found[k]) << threads << " frame " << i;
      }
    }
    // A sphere whole but near the edge is followed whole from the frame before, or placed cut
    // where a chunk starts beside it: the flag may differ, never what is found.
    EXPECT_GT(cut_short, 0u) << threads << " threads";
    EXPECT_LE(cut_short > cut_long ? cut_short - cut_long : cut_long - cut_short, 2u);
    if (threads == 1) {
      chunked_one = c;
    } else {
      for (size_t i = 0; i < kDriftFrames; ++i) {
        for (int k = 0; k < 2; ++k) {
          EXPECT_EQ(c.frames[i].centre[k], chunked_one.frames[i].centre[k]) << "frame " << i;
        }
      }
    }
  }
}

// The drifting film of OneSphereLeavesThenTheOther... (which renders it and runs first), read
// again through `dimerlab track` by the two tests below.
const std::string kLeavingFilm = std::string(DIMERLAB_POVRAY_CACHE) + "/leaving_both_edges";
constexpr const char* kLeavingFilmNotRendered =
    "leaving_both_edges: rendered by OneSphereLeavesThenTheOther..., which runs first";

bool LeavingFilmRendered() { return std::filesystem::exists(kLeavingFilm + "/truth.csv"); }

// `track`'s arguments for that film, its scale given, the track written into `dir`.
tracking::TrackArgs LeavingFilmTrackArgs(const std::filesystem::path& dir) {
  tracking::TrackArgs t;
  t.input = kLeavingFilm;
  t.output = dir / "track.h5";
  t.m_per_px = 0.0002;
  t.quiet = true;
  return t;
}

// What `dimerlab track` writes of the cut spheres of the same film (its first 30 frames: the
// right sphere leaves over frames 10-22): /found is 2 exactly where a sphere is found cut, and
// /pixels/right_cut_err states each one's uncertainty there (its registration, the whole
// sphere beside it cut alike, the length's miss and the offset's: 0.09-0.13 px here) and NaN
// elsewhere. CTest `povray.leaving_the_frame`.
TEST(PovrayLeavingTheFrame, TheTrackFileFlagsTheCutSpheresWithTheirUncertainty) {
  if (!LeavingFilmRendered()) GTEST_SKIP() << kLeavingFilmNotRendered;
  const dimer::testing::TempDir tmp;
  tracking::TrackArgs t = LeavingFilmTrackArgs(tmp.path());
  t.frames = "0:30";
  tracking::RunTrack(t);
  const H5Reader h(t.output);
  const std::vector<uint8_t> found = h.ReadUint8("/found");
  const std::vector<double> err = h.ReadDoubles("/pixels/right_cut_err");
  const std::vector<double> left_err = h.ReadDoubles("/pixels/left_cut_err");
  ASSERT_EQ(found.size(), 60u);
  ASSERT_EQ(err.size(), 60u);
  size_t cut = 0;
  for (size_t i = 0; i < 30; ++i) {
    EXPECT_NE(found[2 * i], 2) << "frame " << i << ": the left sphere is whole in view";
    EXPECT_TRUE(std::isnan(left_err[2 * i]) && std::isnan(left_err[2 * i + 1])) << i;
    if (found[2 * i + 1] == 2) {
      ++cut;
      for (int axis = 0; axis < 2; ++axis) {
        EXPECT_GT(err[2 * i + axis], 0.0) << "frame " << i;
        EXPECT_LT(err[2 * i + axis], 0.3) << "frame " << i;
      }
    } else {
      EXPECT_TRUE(std::isnan(err[2 * i]) && std::isnan(err[2 * i + 1])) << "frame " << i;
    }
  }
  EXPECT_GE(cut, 6u);
}

// `dimerlab track` on the whole of the same film (61 frames): both spheres are in view in fewer
// than half of them, the left one alone in most of the rest and nothing in the last two. A
// drift run's film ends this way; it is tracked, not refused as a film without a dimer
// (dimer_presence.h), and a note says how much of it shows the dimer. CTest
// `povray.leaving_the_frame`.
TEST(PovrayLeavingTheFrame, AFilmWhoseDimerLeavesForGoodIsTrackedWhereItIsInView) {
  if (!LeavingFilmRendered()) GTEST_SKIP() << kLeavingFilmNotRendered;
  const dimer::testing::TempDir tmp;
  tracking::TrackArgs t = LeavingFilmTrackArgs(tmp.path());
  std::string notes;
  t.on_diagnostic = [&notes](const tracking::Diagnostic& d) { notes += d.message + "\n"; };
  tracking::RunTrack(t);
  std::printf("[ stats    ] %s", notes.c_str());
  EXPECT_NE(notes.find("the dimer is in view in "), std::string::npos) << notes;
  const H5Reader h(t.output);
  const std::vector<uint8_t> found = h.ReadUint8("/found");
  ASSERT_EQ(found.size(), 122u);
  size_t both = 0;
  for (size_t i = 0; i < 61; ++i) both += found[2 * i] && found[2 * i + 1];
  EXPECT_LT(2 * both, 61u) << "the film is not what it says";
  EXPECT_EQ(found[2 * 59] + found[2 * 59 + 1] + found[2 * 60] + found[2 * 60 + 1], 0);
}

// A still-plate calibration film: the dimer resting on a still plate in 16 poses (each frame its
// own, sharp), the left sphere on the plate, the right lifted by 0 to 3 degrees, the dimer moved
// by up to 6 mm between poses. A lab's film of this kind put both spheres' rows 2.2-2.4 px low
// in every frame, stating 0.5 px. Per sphere and axis: |bias| within max(0.1 px, 2 x the stated
// uncertainty), which is at most 0.3 px. Two things held it back: following from one pose to
// the next matched the lifted sphere 7-11 px off (an unrefined whole-pixel peak, now searched
// for afresh: frame_follower.cc), and the lifted sphere's contact band, three times its gap's
// second differences (here the poses' changes), held every pose (now capped by the length's:
// ContactRowOffset's noise_cap). The columns read the dimer 0.27 px long (-0.15 and +0.13 px,
// the right's stated +-0.065): the right's is the case's least margin.
TEST(PovrayStillPlatePoses, CalibrationPosesAreUnbiasedWithinTheirStatedUncertainty) {
  FootageOptions o = FootageOptions::For(Lighting::kFrontPoint);
  o.exposure_s = 0;
  o.subframes = 1;
  o.camera.centre_x = 0;
  constexpr int kPoses = 16;
  const double r = 0.5 * o.shape.diameter, l = o.shape.CentreDistance();
  std::vector<Pose> poses;
  for (int i = 0; i < kPoses; ++i) {
    const double theta = (3.0 * ((i * 7) % kPoses) / (kPoses - 1)) * M_PI / 180.0;
    const double left_x = -0.5 * l + 1e-3 * (((i * 5) % 7) - 3);
    poses.push_back({double(i) / o.fps, left_x + 0.5 * l * std::cos(theta),
                     r + 0.5 * l * std::sin(theta), theta, 0.0});
  }
  const std::string dir = CachedFilm("still_plate_poses", o, PoseMotion(o.shape, poses));
  {  // Where the errors are: the frames searched afresh and the frames followed from the last.
    double radius = 0;
    const std::vector<TruthRow> truth = ReadTruthCsv(dir + "/truth.csv", &radius);
    std::vector<cv::Mat> frames;
    for (const TruthRow& row : truth) {
      frames.push_back(cv::imread(dir + "/" + row.file, cv::IMREAD_UNCHANGED));
    }
    tracking::MemorySource source(frames);
    tracking::SequenceOptions so;
    so.follower.method = tracking::Method::kAuto;
    so.contact_radius_px = radius;
    so.threads = 2;
    const tracking::SequenceResult res = tracking::TrackSequence(source, so);
    for (int k = 0; k < 2; ++k) {
      for (bool acquired : {true, false}) {
        Eigen::Vector2d sum(0, 0);
        double worst = 0;
        int n = 0;
        for (size_t i = 0; i < truth.size(); ++i) {
          const tracking::FrameTrack& f = res.frames[i];
          if (!f.found[k] || f.acquired != acquired) continue;
          const Eigen::Vector2d e = f.centre[k] - truth[i].centre[k];
          sum += e, worst = std::max(worst, e.norm()), ++n;
        }
        std::printf("[ stats    ] %s sphere, %d frames %s: mean error (%+.3f, %+.3f) px, worst "
                    "%.2f px\n", k ? "right" : "left", n,
                    acquired ? "searched afresh" : "followed", n ? sum.x() / n : NAN,
                    n ? sum.y() / n : NAN, worst);
      }
    }
  }
  const TrackAccuracy a = MeasureTrackAccuracy(dir, TestMethod(), 2);
  std::printf("still_plate_poses\n%s%s", AccuracyHeader().c_str(), AccuracyRow(a).c_str());
  ASSERT_EQ(a.frames, size_t(kPoses));
  const char* names[2] = {"left", "right"};
  const char* axes[2] = {"column", "row"};
  for (int k = 0; k < 2; ++k) {
    const SphereAccuracy& s = a.sphere[k];
    EXPECT_EQ(s.found, s.good) << names[k];
    std::printf("[ stats    ] %s: bias (%+.3f, %+.3f) px, stated +-(%.3f, %.3f)\n", names[k],
                s.bias.x(), s.bias.y(), s.stated_err.x(), s.stated_err.y());
    for (int ax = 0; ax < 2; ++ax) {
      const double stated = std::isfinite(s.stated_err(ax)) ? s.stated_err(ax) : 0.0;
      EXPECT_LE(std::abs(s.bias(ax)), std::max(kBiasTargetPx, 2 * stated))
          << names[k] << " " << axes[ax] << " stated +-" << s.stated_err(ax);
      if (a.template_run) {
        EXPECT_LE(s.stated_err(ax), 0.3) << names[k] << " " << axes[ax];
      }
    }
  }
  EXPECT_EQ(a.identity_swaps, 0u);
  EXPECT_LE(a.plate_max_error, kPlateTargetPx);
}

// A film with no dimer: one steel sphere alone resting on the oscillating plate (the dimer's
// other sphere out of view, no rod). `track` exits 1 (InputError) with one line and writes
// nothing (tracking/dimer_presence.h). CTest `povray.no_dimer`.
TEST(PovrayNoDimer, OneSphereAloneIsRefusedAndNothingIsWritten) {
  FootageOptions o = FootageOptions::For(Lighting::kFrontPoint);
  o.shape.rod_diameter = 0;
  o.shape.aspect_ratio = 40;  // the other sphere 370 mm away
  o.subframes = kSlices;
  o.camera.centre_x = -0.5 * o.shape.CentreDistance();  // the left sphere mid-frame
  const std::string dir =
      CachedFilm("one_sphere_alone", o, HopMotion(o.shape, 12, o.fps, HopOptions{}));
  dimer::testing::TempDir tmp;
  tracking::TrackArgs t;
  t.input = dir;
  t.output = tmp / "track.h5";
  t.m_per_px = o.camera.m_per_px;
  t.quiet = true;
  std::string error;
  try {
    tracking::RunTrack(t);
  } catch (const InputError& e) {
    error = e.what();
  }
  std::printf("[ stats    ] %s\n", error.c_str());
  EXPECT_NE(error.find("no dimer"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(t.output));
}

// 16-bit frames filling a quarter of the range (8-bit levels x 64: a 14-bit camera's, or a
// 16-bit one's at a quarter of full exposure, as PNG with no header to say so) must track as
// their 8-bit frames do: the same spheres found, each bias within 0.1 px of the 8-bit film's,
// the plate within the target. Found when this was added (the levels' bits guessed at 10 or 12
// only, tracking/io/level_scale.h; the clip looked for at 65535): ring_light's spheres 49 px off,
// defocus_1px's not found, over-exposed's plate 0.41 px off (CTest `povray.quarter_range`).
std::vector<Case> CameraCases();

// The 8-bit footage in `src` written again into `dst` with its levels x `factor` into `depth`
// (rounded, saturated), truth.csv copied. Fails the test where a frame is not 8-bit.
void WriteLevelsCopy(const std::string& src, const std::filesystem::path& dst, double factor,
                     int depth) {
  std::filesystem::copy_file(src + "/truth.csv", dst / "truth.csv");
  for (const auto& row : ReadTruthCsv(src + "/truth.csv")) {
    const cv::Mat img = cv::imread(src + "/" + row.file, cv::IMREAD_UNCHANGED);
    ASSERT_EQ(img.type(), CV_8UC1) << row.file;
    cv::Mat out;
    img.convertTo(out, depth, factor);
    ASSERT_TRUE(cv::imwrite(dst / row.file, out));
  }
}

TEST(PovrayQuarterRange, SixteenBitFramesOfAQuarterOfTheRangeTrackAsTheirEightBitFrames) {
  std::vector<Case> cases = {Case{"overexposed", Lighting::kOverexposed, 3.9},
                             Case{"ring_light", Lighting::kRingLight, 3.9}};
  for (const Case& c : CameraCases()) {
    if (std::string(c.name) == "defocus_1px") cases.push_back(c);
  }
  ASSERT_EQ(cases.size(), 3u);
  for (const Case& c : cases) {
    const std::string src = Footage(c);
    dimer::testing::TempDir tmp;
    ASSERT_NO_FATAL_FAILURE(WriteLevelsCopy(src, tmp.path(), 64, CV_16U));
    const TrackAccuracy a8 = Accuracy(c);
    const TrackAccuracy a16 = MeasureTrackAccuracy(tmp.path().string(), TestMethod(), 2);
    std::printf("%s, 8-bit and as 16-bit x 64\n%s%s%s", c.name, AccuracyHeader().c_str(),
                AccuracyRow(a8).c_str(), AccuracyRow(a16).c_str());
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(a16.sphere[k].found, a8.sphere[k].found) << c.name << " sphere " << k;
      EXPECT_LE((a16.sphere[k].bias - a8.sphere[k].bias).norm(), 0.1)
          << c.name << " sphere " << k;
    }
    EXPECT_EQ(a16.identity_swaps, 0u) << c.name;
    EXPECT_LE(a16.plate_max_error, kPlateTargetPx) << c.name;
  }
}

// Front-lit steel at a lower gain: each film's levels x 0.7 (8-bit, rounded; the noise scaled
// with the signal, so only the levels change). Where the silhouette methods find nothing the
// rough centres come from the highlights, weighed by their light: split at the widest gap
// between columns, a steel rod's glints of the ring light join a sphere (ring_light's right
// sphere not found, the left 49 px off) and an under-exposed film loses 10-15 % of its frames;
// learning frames whose seeds are not a dimer's length apart are left out
// (tracking/sphere/highlight_seed.h). The cluttered backdrop also at x 0.5: a highlight floor
// read from the levels' spread about their median (the backdrop's shading, in whole levels)
// stands over the lamps' reflections (the left sphere 22 px off, the right not found), so the
// floor is read from the noise. ring_light at x 0.7 and x 0.5: its bouncing sphere's row,
// carried over through the two faint outlines and midway with the registered transfer, is
// 0.33 px off; the two transfers are weighed by how alike the two appearances are
// (tracking/sphere/appearance_mismatch.h). Each film: both spheres found, no swap,
// each bias within 3 of its stated uncertainties (the track file's word on its column), the plate
// within the target, and the issue's bias target. CTest `povray.lower_levels`.
TEST(PovrayLowerLevels, FrontLitSteelAtALowerGainIsFoundAndItsStatedUncertaintyHolds) {
  struct Lowered {
    Case c;
    double levels;
  };
  const std::vector<Lowered> cases = {
      {Case{"ring_light", Lighting::kRingLight, 3.9}, 0.7},
      {Case{"ring_light", Lighting::kRingLight, 3.9}, 0.5},
      {Case{"underexposed", Lighting::kUnderexposed, 3.9}, 0.7},
      {Case{"cluttered_backdrop", Lighting::kClutteredBackdrop, 3.9}, 0.7},
      {Case{"cluttered_backdrop", Lighting::kClutteredBackdrop, 3.9}, 0.5}};
  for (const auto& [c, levels] : cases) {
    const std::string src = Footage(c);
    dimer::testing::TempDir tmp;
    ASSERT_NO_FATAL_FAILURE(WriteLevelsCopy(src, tmp.path(), levels, CV_8U));
    const TrackAccuracy a = MeasureTrackAccuracy(tmp.path().string(), TestMethod(), 2);
    std::printf("%s, levels x %.1f\n%s%s", c.name, levels, AccuracyHeader().c_str(),
                AccuracyRow(a).c_str());
    ASSERT_EQ(a.frames, kFrames) << c.name;
    for (int k = 0; k < 2; ++k) {
      const SphereAccuracy& s = a.sphere[k];
      EXPECT_GE(s.found_fraction, kFoundTarget) << c.name << " sphere " << k;
      EXPECT_LE(s.bias_sigmas.x(), 3.0) << c.name << " sphere " << k;
      EXPECT_LE(s.bias_sigmas.y(), 3.0) << c.name << " sphere " << k;
      EXPECT_LE(s.bias.norm(), kBiasTargetPx) << c.name << " sphere " << k;
    }
    EXPECT_EQ(a.identity_swaps, 0u) << c.name;
    EXPECT_LE(a.plate_max_error, kPlateTargetPx) << c.name;
  }
}

// One noise seed is one draw: front_point rendered again with noise seeds 2-9 (the scene and its
// truth unchanged; seed 1 is the front_point case). Over the 18 spheres, each column's bias in
// units of its stated uncertainty (with the bias's sampling error, SphereAccuracy::bias_sigmas)
// must look like a standard normal's: RMS within [0.5, 1.25] of 1 and none beyond 3. The
// outline pairs' own scatter stated 1.3 in RMS and 4.1 at worst here (seed 2's right sphere,
// -0.134 px stated +-0.034), not seeing that neighbouring rays share their noise; the
// jackknife over the learning frames (tracking/sphere/appearance_model.h, LimbColumnOffset) measures
// the spread instead (CTest `povray.noise_seeds`).
TEST(PovrayNoiseSeeds, StatedColumnUncertaintyMatchesTheSpreadOverSeeds) {
  constexpr uint64_t kSeeds = 9;
  double z2 = 0, worst = 0;
  int n = 0;
  for (uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const std::string name = seed == 1 ? "front_point" : "front_point_seed_" + std::to_string(seed);
    const TrackAccuracy a = Accuracy(Case{name.c_str(), Lighting::kFrontPoint, 3.9, -1, seed});
    ASSERT_EQ(a.frames, kFrames) << name;
    ASSERT_TRUE(a.template_run) << name;
    for (int k = 0; k < 2; ++k) {
      const SphereAccuracy& s = a.sphere[k];
      std::printf("[ stats    ] seed %d %s: column bias %+.3f px, stated +-%.3f: %.2f sigma\n",
                  int(seed), k ? "right" : "left", s.bias.x(), s.stated_err.x(),
                  s.bias_sigmas.x());
      ASSERT_TRUE(std::isfinite(s.bias_sigmas.x())) << name << " sphere " << k;
      z2 += s.bias_sigmas.x() * s.bias_sigmas.x();
      worst = std::max(worst, s.bias_sigmas.x());
      ++n;
    }
  }
  const double rms = std::sqrt(z2 / n);
  std::printf("[ stats    ] column bias / stated over %d spheres: RMS %.2f, largest %.2f\n", n,
              rms, worst);
  EXPECT_LE(rms, 1.25) << "the stated column uncertainty is too small";
  EXPECT_GE(rms, 0.5) << "the stated column uncertainty is more than twice the spread";
  EXPECT_LE(worst, 3.0);
}

// `dimerlab track FILM --ar A_r` with no --m-per-px (tracking/dimer_length_scale.h), as a user
// who knows the dimer but not the camera's scale runs it, against the same film tracked with the
// true scale given: the scale within kLengthScaleTarget of the truth, and each sphere's mean row
// error (the rows rest on the radius the scale implies) within the issue's bias target. From
// the spheres' size (no --ar) these films gave the scale 2.2 % (front_point) to 190 %
// (underexposed) off and the rows 0.45-15 px off, or no sphere at all (the camera turned 8
// degrees; bench_tracking_footage --scale). The columns are printed,
// not held: they do not rest on the scale, but on one-sided light and defocus a radius 0.01 px
// different moves a column by 0.05-0.12 px either way, whatever the scale's origin.
// CTest `povray.dimer_length.CASE`.
constexpr double kLengthScaleTarget = 0.003;

class PovrayDimerLength : public ::testing::TestWithParam<Case> {};

TEST_P(PovrayDimerLength, TheDimersLengthGivesTheScaleAndTheRows) {
  const Case& c = GetParam();
  const std::string dir = Footage(c);
  const double truth = CaseFootageOptions(c.lighting, c.camera).camera.m_per_px;
  dimer::testing::TempDir tmp;
  const ScaledTrack given = TrackScaled(dir, tmp / "given.h5", truth, std::nan(""));
  const ScaledTrack by_length =
      TrackScaled(dir, tmp / "by_length.h5", std::nan(""), c.aspect_ratio);
  std::printf("[ stats    ] %s: m/px from the length %+.3f %% off; mean error L (%+.3f, %+.3f) R "
              "(%+.3f, %+.3f) px, with the scale given L (%+.3f, %+.3f) R (%+.3f, %+.3f) px\n",
              c.name, 100.0 * (by_length.m_per_px / truth - 1.0), by_length.bias[0].x(),
              by_length.bias[0].y(), by_length.bias[1].x(), by_length.bias[1].y(),
              given.bias[0].x(), given.bias[0].y(), given.bias[1].x(), given.bias[1].y());
  EXPECT_EQ(by_length.m_per_px_given, 2.0) << "the file says the scale came from --ar";
  EXPECT_LE(std::abs(by_length.m_per_px / truth - 1.0), kLengthScaleTarget)
      << "m/px " << by_length.m_per_px << " against " << truth;
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(by_length.found[k], given.found[k]) << (k == 0 ? "left" : "right");
    EXPECT_LE(std::abs(by_length.bias[k].y()), kBiasTargetPx)
        << (k == 0 ? "left" : "right") << " sphere's mean row error, px (with the scale given "
        << given.bias[k].y() << ")";
  }
}

// A mistaken --ar (A_r - 1, the centre distance over the diameter, given for A_r) is caught by
// the radius the first pass measured from the outline: the radius the length implies is 53 %
// larger, past kOutlineRadiusCheck (stderr warns), while the right A_r is within 4.1 % of it.
// CTest `povray.dimer_length.mistaken_ar`.
TEST(PovrayDimerLengthCheck, AMistakenAspectRatioIsCaughtByTheOutline) {
  const std::string dir = Footage(Case{"front_point", Lighting::kFrontPoint, 3.9});
  dimer::testing::TempDir tmp;
  auto radii = [&](double ar) {
    TrackScaled(dir, tmp / "track.h5", std::nan(""), ar);
    H5Reader h(tmp / "track.h5");
    return std::make_pair(*h.AttrDouble("/", "ar_radius_px"),
                          *h.AttrDouble("/", "ar_outline_radius_px"));
  };
  const auto right = radii(3.9), mistaken = radii(2.9);
  std::printf("[ stats    ] outline radius %.3f px; from the length with A_r 3.9 %.3f px, with "
              "2.9 %.3f px\n", right.second, right.first, mistaken.first);
  ASSERT_GT(right.second, 0) << "front-lit steel: the radius from the outline";
  EXPECT_LE(std::abs(right.first / right.second - 1.0), tracking::kOutlineRadiusCheck);
  EXPECT_GT(std::abs(mistaken.first / mistaken.second - 1.0), tracking::kOutlineRadiusCheck);
}

// The films where the spheres' size failed worst, and the two where it found no sphere at all
// (under-exposed: a silhouette radius of 8 px; the camera turned 8 degrees), which --ar tracks
// from guessed radii (dimer_length_scale.h).
std::vector<Case> DimerLengthCases() {
  std::vector<Case> cases = {Case{"front_point", Lighting::kFrontPoint, 3.9},
                             Case{"front_softbox", Lighting::kFrontSoftbox, 3.9},
                             Case{"one_sided_gain_ramp", Lighting::kOneSidedGainRamp, 3.9},
                             Case{"cluttered_backdrop", Lighting::kClutteredBackdrop, 3.9},
                             Case{"underexposed", Lighting::kUnderexposed, 3.9},
                             Case{"front_point_ar2_0", Lighting::kFrontPoint, 2.0}};
  const std::vector<CameraVariant> v = CameraVariants();
  for (size_t i = 0; i < v.size(); ++i) {
    if (std::string(v[i].name) == "rolled_8_degrees") {
      cases.push_back(Case{v[i].name, Lighting::kFrontPoint, 3.9, int(i)});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(
    Films, PovrayDimerLength, ::testing::ValuesIn(DimerLengthCases()),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

INSTANTIATE_TEST_SUITE_P(
    Lightings, PovrayFootage,
    ::testing::Values(Case{"front_point", Lighting::kFrontPoint, 3.9},
                      Case{"front_softbox", Lighting::kFrontSoftbox, 3.9},
                      Case{"bright_background", Lighting::kBrightBackground, 3.9},
                      Case{"matte", Lighting::kMatte, 3.9},
                      Case{"backlit", Lighting::kBacklit, 3.9},
                      Case{"one_sided_gain_ramp", Lighting::kOneSidedGainRamp, 3.9},
                      Case{"underexposed", Lighting::kUnderexposed, 3.9},
                      Case{"overexposed", Lighting::kOverexposed, 3.9},
                      Case{"mirror_plate", Lighting::kMirrorPlate, 3.9},
                      Case{"ring_light", Lighting::kRingLight, 3.9},
                      Case{"cluttered_backdrop", Lighting::kClutteredBackdrop, 3.9},
                      Case{"ruler_above_plate", Lighting::kRulerAbovePlate, 3.9},
                      Case{"front_point_ar2_0", Lighting::kFrontPoint, 2.0},
                      Case{"front_point_ar2_1", Lighting::kFrontPoint, 2.1},
                      Case{"front_point_ar2_3", Lighting::kFrontPoint, 2.3}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

// Front-lit steel through cameras the tracker was not tuned on (tests/footage/camera_variants.h).
std::vector<Case> CameraCases() {
  std::vector<Case> cases;
  const std::vector<CameraVariant> v = CameraVariants();
  for (size_t i = 0; i < v.size(); ++i) {
    cases.push_back(Case{v[i].name, Lighting::kFrontPoint, 3.9, int(i)});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(
    Cameras, PovrayFootage, ::testing::ValuesIn(CameraCases()),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace dimer::footage
