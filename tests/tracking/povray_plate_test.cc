// The plate row alone on the POV-Ray footage (tests/footage): the target, within 0.3 px
// of the truth in every frame, checked apart from the sphere targets so that a case still short
// on its spheres (povray_footage_test, WILL_FAIL there) keeps its plate row guarded.
//
// Same footage as povray_footage_test (same options, so the same scene hash and cache folder),
// same method (DIMERLAB_POVRAY_METHOD, else DIMERLAB_POVRAY_TEST_METHOD), the scale told.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <string>

#include "tests/footage/povray_footage.h"
#include "tests/footage/track_accuracy.h"

#ifndef DIMERLAB_POVRAY_TEST_METHOD
#define DIMERLAB_POVRAY_TEST_METHOD "centroid"
#endif
#ifndef DIMERLAB_POVRAY_CACHE
#define DIMERLAB_POVRAY_CACHE "povray_footage_cache"
#endif

namespace dimer::footage {
namespace {

constexpr size_t kFrames = 20;  // as povray_footage_test: same footage
constexpr int kSlices = 2;

struct Case {
  const char* name;
  Lighting lighting;
  double aspect_ratio;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::string Footage(const Case& c) {
  FootageOptions o = FootageOptions::For(c.lighting);
  o.shape.aspect_ratio = c.aspect_ratio;
  o.subframes = kSlices;
  o.reuse = true;
  o.quiet = true;
  const std::string dir = std::string(DIMERLAB_POVRAY_CACHE) + "/" + c.name;
  std::filesystem::create_directories(DIMERLAB_POVRAY_CACHE);
  WriteFootage(HopMotion(o.shape, kFrames, o.fps), o, dir);
  return dir;
}

class PovrayPlate : public ::testing::TestWithParam<Case> {};

TEST_P(PovrayPlate, PlateRowWithinTheTargetInEveryFrame) {
  const Case& c = GetParam();
  const char* env = std::getenv("DIMERLAB_POVRAY_METHOD");
  const TrackAccuracy a =
      MeasureTrackAccuracy(Footage(c), env && *env ? env : DIMERLAB_POVRAY_TEST_METHOD, 2);
  std::printf("[ stats    ] %s plate row: bias %+.3f, max %.3f px, %zu of %zu frames\n", c.name,
              a.plate_bias, a.plate_max_error, a.plate_found, a.frames);
  ASSERT_EQ(a.frames, kFrames);
  EXPECT_EQ(a.plate_found, a.frames) << "frames with a plate row";
  EXPECT_LE(a.plate_max_error, kPlateTargetPx) << "plate row, mean error " << a.plate_bias;
}

INSTANTIATE_TEST_SUITE_P(
    Lightings, PovrayPlate,
    ::testing::Values(Case{"front_point", Lighting::kFrontPoint, 3.9},
                      Case{"front_softbox", Lighting::kFrontSoftbox, 3.9},
                      Case{"bright_background", Lighting::kBrightBackground, 3.9},
                      Case{"matte", Lighting::kMatte, 3.9},
                      Case{"backlit", Lighting::kBacklit, 3.9},
                      Case{"one_sided_gain_ramp", Lighting::kOneSidedGainRamp, 3.9},
                      Case{"underexposed", Lighting::kUnderexposed, 3.9},
                      Case{"overexposed", Lighting::kOverexposed, 3.9},
                      Case{"mirror_plate", Lighting::kMirrorPlate, 3.9},
                      Case{"front_point_ar2_0", Lighting::kFrontPoint, 2.0},
                      Case{"front_point_ar2_1", Lighting::kFrontPoint, 2.1},
                      Case{"front_point_ar2_3", Lighting::kFrontPoint, 2.3}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace dimer::footage
