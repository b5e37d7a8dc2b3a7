// `track --lens`: a lab's OpenCV calibration file read in both of OpenCV's layouts, bad files
// named with what is wrong, and frames undistorted so that a disc the lens moved by a pixel or
// two lands where a pinhole camera would have put it.
#include "tracking/io/lens_undistortion.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "tests/common/test_tmpdir.h"

namespace dimer::tracking {
namespace {

void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// The calibration sample's layout (samples/cpp/calibration.cpp), YAML.
std::string SampleYaml(double k1, int width = 320, int height = 160) {
  return "%YAML:1.0\n---\nimage_width: " + std::to_string(width) +
         "\nimage_height: " + std::to_string(height) +
         "\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n"
         "   data: [ 1000., 0., 159.5, 0., 1000., 79.5, 0., 0., 1. ]\n"
         "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n"
         "   data: [ " +
         std::to_string(k1) + ", 0., 0., 0., 0. ]\navg_reprojection_error: 0.25\n";
}

// The message of the InputError `path` gives, or "" if none.
std::string ErrorOf(const std::string& path) {
  try {
    ReadLensCalibration(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(LensCalibration, ReadsTheCalibrationSamplesAndTheTutorialsLayouts) {
  dimer::testing::TempDir dir;
  WriteText(dir / "sample.yml", SampleYaml(0.3));
  const LensCalibration a = ReadLensCalibration(dir / "sample.yml");
  EXPECT_EQ(a.camera(0, 0), 1000.0);
  EXPECT_EQ(a.camera(0, 2), 159.5);
  EXPECT_EQ(a.camera(1, 2), 79.5);
  ASSERT_EQ(a.distortion.size(), 5u);
  EXPECT_DOUBLE_EQ(a.distortion[0], 0.3);
  EXPECT_EQ(a.image_size, cv::Size(320, 160));
  EXPECT_DOUBLE_EQ(a.reprojection_error, 0.25);
  // The tutorial's (camera_calibration.cpp) XML: capitalised names, no image size needed.
  WriteText(dir / "tutorial.xml",
            "<?xml version=\"1.0\"?>\n<opencv_storage>\n"
            "<Camera_Matrix type_id=\"opencv-matrix\"><rows>3</rows><cols>3</cols><dt>d</dt>"
            "<data>800. 0. 320. 0. 810. 240. 0. 0. 1.</data></Camera_Matrix>\n"
            "<Distortion_Coefficients type_id=\"opencv-matrix\"><rows>4</rows><cols>1</cols>"
            "<dt>d</dt><data>-0.1 0.02 0.001 -0.002</data></Distortion_Coefficients>\n"
            "</opencv_storage>\n");
  const LensCalibration b = ReadLensCalibration(dir / "tutorial.xml");
  EXPECT_EQ(b.camera(1, 1), 810.0);
  ASSERT_EQ(b.distortion.size(), 4u);
  EXPECT_DOUBLE_EQ(b.distortion[3], -0.002);
  EXPECT_EQ(b.image_size.area(), 0);
}

TEST(LensCalibration, BadFilesAreNamedWithWhatIsWrong) {
  dimer::testing::TempDir dir;
  const std::string missing = dir / "missing.yml";
  EXPECT_NE(ErrorOf(missing).find(missing + ": no such file"), std::string::npos);
  WriteText(dir / "garbage.yml", "this is not { a calibration");
  EXPECT_NE(ErrorOf(dir / "garbage.yml").find(dir / "garbage.yml"), std::string::npos);
  WriteText(dir / "nomatrix.yml",
            "%YAML:1.0\n---\ndistortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n"
            "   dt: d\n   data: [ 0., 0., 0., 0., 0. ]\n");
  EXPECT_NE(ErrorOf(dir / "nomatrix.yml").find("no camera matrix"), std::string::npos);
  std::string three = SampleYaml(0.1);
  three.replace(three.find("rows: 5"), 7, "rows: 3");
  three.replace(three.find(", 0., 0., 0., 0. ]"), 18, ", 0., 0. ]");
  WriteText(dir / "three.yml", three);
  EXPECT_NE(ErrorOf(dir / "three.yml").find("3 coefficients"), std::string::npos);
  std::string skew = SampleYaml(0.1);
  skew.replace(skew.find("0., 0., 1. ]"), 12, "0.5, 0., 1. ]");
  WriteText(dir / "skew.yml", skew);
  EXPECT_NE(ErrorOf(dir / "skew.yml").find("is not fx 0 cx"), std::string::npos);
  // Made for other images: said when the frames are known.
  WriteText(dir / "other.yml", SampleYaml(0.1, 640, 480));
  const LensCalibration other = ReadLensCalibration(dir / "other.yml");
  try {
    LensUndistortion u(other, cv::Size(320, 160));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("calibrated for 640x480 images, the frames are 320x160"),
              std::string::npos)
        << e.what();
  }
}

// The image size must be an integer in 1..65536 and the matrices' rows and cols what they must
// be, checked before OpenCV reads the data ('abc' columns made it ask for 80 GiB): each bad file
// is one line naming the file and the field.
TEST(LensCalibration, BadImageSizesAndMatrixShapesAreOneLineErrorsNamingTheField) {
  dimer::testing::TempDir dir;
  for (const std::string bad : {"=", "abc", "1e12", "-200", "0", "65537", "320.5"}) {
    std::string yaml = SampleYaml(0.1);
    yaml.replace(yaml.find("image_width: 320"), 16, "image_width: " + bad);
    const std::string path = dir / "width.yml";
    WriteText(path, yaml);
    const std::string e = ErrorOf(path);
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    EXPECT_EQ(e.rfind(path + ": image_width is ", 0), 0u) << bad << ": " << e;
    EXPECT_NE(e.find("not an integer in 1..65536"), std::string::npos) << bad << ": " << e;
  }
  std::string no_height = SampleYaml(0.1);
  no_height.erase(no_height.find("image_height: 160\n"), 18);
  WriteText(dir / "no_height.yml", no_height);
  EXPECT_NE(ErrorOf(dir / "no_height.yml").find("image_width without image_height"),
            std::string::npos);
  // The largest size is read, and its check does not overflow (area() would).
  WriteText(dir / "largest.yml", SampleYaml(0.1, 65536, 65536));
  const LensCalibration largest = ReadLensCalibration(dir / "largest.yml");
  EXPECT_THROW(LensUndistortion(largest, cv::Size(320, 160)), InputError);

  const std::string xml_head = "<?xml version=\"1.0\"?>\n<opencv_storage>\n";
  const std::string distortion =
      "<Distortion_Coefficients type_id=\"opencv-matrix\"><rows>4</rows><cols>1</cols>"
      "<dt>d</dt><data>-0.1 0.02 0.001 -0.002</data></Distortion_Coefficients>\n";
  WriteText(dir / "cols.xml",
            xml_head +
                "<Camera_Matrix type_id=\"opencv-matrix\"><rows>3</rows><cols>abc</cols>"
                "<dt>d</dt><data>800. 0. 320. 0. 810. 240. 0. 0. 1.</data></Camera_Matrix>\n" +
                distortion + "</opencv_storage>\n");
  std::string e = ErrorOf(dir / "cols.xml");
  EXPECT_EQ(e, dir / "cols.xml" + ": Camera_Matrix has rows 3 and cols 'abc', not integers");
  WriteText(dir / "wide.xml",
            xml_head +
                "<Camera_Matrix type_id=\"opencv-matrix\"><rows>3</rows><cols>100000</cols>"
                "<dt>d</dt><data>800. 0. 320. 0. 810. 240. 0. 0. 1.</data></Camera_Matrix>\n" +
                distortion + "</opencv_storage>\n");
  e = ErrorOf(dir / "wide.xml");
  EXPECT_EQ(e, dir / "wide.xml" + ": Camera_Matrix is 3 x 100000 (300000 values), not 3 x 3");
  std::string square = SampleYaml(0.1);
  square.replace(square.find("rows: 5\n   cols: 1"), 18, "rows: 5\n   cols: 2");
  WriteText(dir / "square.yml", square);
  e = ErrorOf(dir / "square.yml");
  EXPECT_NE(e.find("distortion_coefficients is 5 x 2 (10 coefficients), not one row or column"),
            std::string::npos) << e;
  std::string short_data = SampleYaml(0.1);
  short_data.replace(short_data.find(", 0., 0., 1. ]"), 14, ", 0., 1. ]");
  WriteText(dir / "short.yml", short_data);
  e = ErrorOf(dir / "short.yml");
  EXPECT_NE(e.find("camera_matrix has 8 data values for its 3 x 3"), std::string::npos) << e;
}

// What crashed OpenCV 4.6's parsers inside ReadLensCalibration (tests/fuzz/fuzz_lens): XML that
// ends inside a tag, a NUL byte in the text, an empty key in a map (std::length_error out of
// OpenCV). Each is a one-line error naming the file.
TEST(LensCalibration, TextThatCrashedOpenCvsParserIsRefusedInOneLine) {
  dimer::testing::TempDir dir;
  WriteText(dir / "truncated.xml",
            "<?xml version=\"1.0\"?>\n<opencv_storage>\n<Camera_Matrix type_id=");
  EXPECT_EQ(ErrorOf(dir / "truncated.xml"),
            dir / "truncated.xml" +
                ": XML that does not end with </opencv_storage> (truncated?)");
  std::string nul = SampleYaml(0.1);
  nul[20] = '\0';
  WriteText(dir / "nul.yml", nul);
  EXPECT_EQ(ErrorOf(dir / "nul.yml"),
            dir / "nul.yml" + ": a NUL byte at offset 20: not a text calibration file");
  WriteText(dir / "key.yml", "%YAML:1.0\n---\nD:\n   rows: 5\n   : ocsl1\n");  // an empty key
  EXPECT_EQ(ErrorOf(dir / "key.yml"),
            dir / "key.yml" + ": unreadable as an OpenCV calibration file: basic_string::_M_create");
  // The fuzz target's hang: OpenCV's YAML parser loops for ever on a document marker with text
  // beside it; the file is refused before it is parsed. A calibration as OpenCV writes it,
  // "---" alone on its line, still reads.
  WriteText(dir / "loop.yml", "%YAML:1.0\n---%YAML:1.\n0---\na: 1\n");
  EXPECT_EQ(ErrorOf(dir / "loop.yml"),
            dir / "loop.yml" +
                ": line 2: \"---\" not alone on its line (a YAML document marker stands alone)");
  WriteText(dir / "spaces.yml", SampleYaml(0.1));
  EXPECT_EQ(ErrorOf(dir / "spaces.yml"), "");
}

// Bright discs of radius 6 px seen through a lens with k1 = 0.3 (f = 1000 px): each pixel is the
// mean of 8 x 8 samples, each sample's light coming from its undistorted position (the radial
// model inverted by fixed-point iteration, as a lens maps the scene onto the sensor).
constexpr double kF = 1000, kCx = 159.5, kCy = 79.5, kK1 = 0.3, kDiscR = 6;

cv::Point2d Undistort(cv::Point2d d) {
  const double xd = (d.x - kCx) / kF, yd = (d.y - kCy) / kF;
  double x = xd, y = yd;
  for (int i = 0; i < 30; ++i) {
    const double s = 1 + kK1 * (x * x + y * y);
    x = xd / s;
    y = yd / s;
  }
  return {kCx + kF * x, kCy + kF * y};
}

cv::Point2d Distort(cv::Point2d u) {
  const double x = (u.x - kCx) / kF, y = (u.y - kCy) / kF, s = 1 + kK1 * (x * x + y * y);
  return {kCx + kF * x * s, kCy + kF * y * s};
}

cv::Mat DistortedDiscs(const std::vector<cv::Point2d>& centres) {
  cv::Mat img(160, 320, CV_8U);
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      int inside = 0;
      for (int i = 0; i < 8; ++i) {
        for (int j = 0; j < 8; ++j) {
          const cv::Point2d u = Undistort({c - 0.4375 + j / 8.0, r - 0.4375 + i / 8.0});
          for (const cv::Point2d& p : centres) {
            inside += std::hypot(u.x - p.x, u.y - p.y) < kDiscR;
          }
        }
      }
      img.at<uint8_t>(r, c) = cv::saturate_cast<uint8_t>(20 + 200.0 * inside / 64.0);
    }
  }
  return img;
}

// Intensity-weighted centroid above the background within 10 px of `near`.
cv::Point2d Centroid(const cv::Mat& img, cv::Point2d near) {
  double s = 0, sx = 0, sy = 0;
  for (int r = int(near.y) - 10; r <= int(near.y) + 10; ++r) {
    for (int c = int(near.x) - 10; c <= int(near.x) + 10; ++c) {
      if (std::hypot(c - near.x, r - near.y) > 10) continue;
      const double w = std::max(0.0, double(img.at<uint8_t>(r, c)) - 20.0);
      s += w, sx += w * c, sy += w * r;
    }
  }
  return {sx / s, sy / s};
}

TEST(LensUndistortion, PutsADistortedDiscWhereThePinholeSawIt) {
  dimer::testing::TempDir dir;
  WriteText(dir / "lens.yml", SampleYaml(kK1));
  const LensCalibration cal = ReadLensCalibration(dir / "lens.yml");
  const LensUndistortion lens(cal, cv::Size(320, 160));
  // Near the axis, half way out and near the frame's edges (where the lens moves them 0.1-2 px).
  const std::vector<cv::Point2d> truth = {{161.3, 81.7}, {231.25, 40.6}, {28.8, 121.1},
                                          {300.4, 140.3}, {20.7, 18.2}};
  const cv::Mat recorded = DistortedDiscs(truth);
  const cv::Mat pinhole = lens.Apply(recorded);
  ASSERT_EQ(pinhole.type(), CV_8U);
  ASSERT_EQ(pinhole.size(), recorded.size());
  // The lens moves pixels by up to 1.7 px in this frame (at its corners).
  const cv::Point2d corner = Distort({0, 0});
  EXPECT_NEAR(lens.max_shift_px(), std::hypot(corner.x, corner.y), 0.01);
  for (const cv::Point2d& p : truth) {
    const cv::Point2d before = Centroid(recorded, Distort(p));
    const cv::Point2d after = Centroid(pinhole, p);
    const double moved = std::hypot(Distort(p).x - p.x, Distort(p).y - p.y);
    // Recorded, the disc is where the lens put it (its centroid within 0.02 px of the distorted
    // centre: a disc 6 px across is bent little), not where the pinhole would have.
    EXPECT_NEAR(before.x, Distort(p).x, 0.02) << p;
    EXPECT_NEAR(before.y, Distort(p).y, 0.02) << p;
    // Undistorted, it is back within 0.02 px (0.005-0.010 seen): OpenCV's remap samples at 1/32
    // px steps, so each pixel may be read up to 1/64 px from where it should.
    EXPECT_NEAR(after.x, p.x, 0.02) << p << " moved by the lens " << moved << " px";
    EXPECT_NEAR(after.y, p.y, 0.02) << p << " moved by the lens " << moved << " px";
  }
}

TEST(LensUndistortion, NoDistortionLeavesEveryPixelAsItWas) {
  dimer::testing::TempDir dir;
  WriteText(dir / "lens.yml", SampleYaml(0.0));
  const LensUndistortion lens(ReadLensCalibration(dir / "lens.yml"), cv::Size(320, 160));
  EXPECT_LT(lens.max_shift_px(), 1e-9);
  cv::Mat frame(160, 320, CV_16U);
  cv::randu(frame, 0, 65535);
  const cv::Mat out = lens.Apply(frame);
  ASSERT_EQ(out.type(), CV_16U);
  EXPECT_EQ(cv::norm(out, frame, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace dimer::tracking
