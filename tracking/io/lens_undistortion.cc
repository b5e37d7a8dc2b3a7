#include "tracking/io/lens_undistortion.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <sstream>

#include "common/error.h"

namespace dimer::tracking {
namespace {

// The first of `names` the file has, or an empty node; *found is its name.
cv::FileNode FirstOf(const cv::FileStorage& fs, std::initializer_list<const char*> names,
                     std::string* found = nullptr) {
  for (const char* n : names) {
    cv::FileNode node = fs[n];
    if (!node.empty()) {
      if (found) *found = n;
      return node;
    }
  }
  return cv::FileNode();
}

// A node's value as the file writes it, for an error message.
std::string Shown(const cv::FileNode& node) {
  if (node.isInt()) return std::to_string(int(node));
  if (node.isReal()) return cv::format("%g", double(node));
  if (node.isString()) return "'" + std::string(node) + "'";
  return "not a number";
}

// The image size field `name`: an integer in 1..65536 (a larger one overflowed the size's area,
// and a string became INT_MAX). Returns the reason it is not, or "".
std::string ImageSizeProblem(const cv::FileNode& node, const std::string& name) {
  if (node.isInt() && int(node) >= 1 && int(node) <= 65536) return "";
  return name + " is " + Shown(node) + ", not an integer in 1..65536";
}

// The rows x cols a matrix node says, read from its own entries before OpenCV allocates them
// (cols 'abc' read as INT_MAX made OpenCV ask for 80 GiB); the data must hold as many numbers.
// Returns the reason it is not a matrix of `want` (rows, cols) -> bool, or "".
template <typename Want>
std::string MatrixProblem(const cv::FileNode& node, const std::string& name, const Want& want,
                          const std::string& unit, const std::string& expected, int* count) {
  if (!node.isMap()) return name + " is not an OpenCV matrix (rows, cols, dt, data)";
  const cv::FileNode rows = node["rows"], cols = node["cols"], data = node["data"];
  if (!rows.isInt() || !cols.isInt()) {
    return name + " has rows " + Shown(rows) + " and cols " + Shown(cols) + ", not integers";
  }
  const int r = int(rows), c = int(cols);
  if (!want(r, c)) {
    return name + " is " + std::to_string(r) + " x " + std::to_string(c) + " (" +
           std::to_string(int64_t(r) * c) + " " + unit + "), not " + expected;
  }
  if (!data.isSeq() || data.size() != size_t(r) * size_t(c)) {
    return name + " has " + (data.isSeq() ? std::to_string(data.size()) : std::string("no")) +
           " data values for its " + std::to_string(r) + " x " + std::to_string(c);
  }
  *count = r * c;
  return "";
}

// A YAML document marker with text beside it ("---%YAML:1." and a later "0---") sends OpenCV
// 4.6's YAML parser into an endless loop (tests/fuzz/hangs); OpenCV writes "---" alone on its
// line, so a line holding "---" and anything else is refused. Returns the reason, or "".
std::string DocumentMarkerProblem(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  for (size_t row = 1; std::getline(lines, line); ++row) {
    if (line.find("---") == std::string::npos) continue;
    line.erase(line.find_last_not_of(" \t\r") + 1);
    if (line != "---") {
      return "line " + std::to_string(row) + ": \"---\" not alone on its line (a YAML document "
             "marker stands alone)";
    }
  }
  return "";
}

// OpenCV 4.6's parsers read past the end of their buffer on a NUL byte inside the text or on
// XML that ends inside a tag (a truncated copy): both crashed it (tests/fuzz/fuzz_lens). A
// calibration file is text, and every XML file OpenCV writes ends with its closing root tag, so
// such files are refused before OpenCV parses them (gzip-compressed ones, which OpenCV reads
// too, are left to it). Returns the reason, or "".
std::string UnparsableTextProblem(const std::string& path) {
  if (path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0) return "";
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    return "a NUL byte at offset " + std::to_string(nul) + ": not a text calibration file";
  }
  if (std::string marker = DocumentMarkerProblem(text); !marker.empty()) return marker;
  const size_t start = text.find_first_not_of(" \t\r\n");
  if (start == std::string::npos || text.compare(start, 5, "<?xml") != 0) return "";
  const size_t end = text.find_last_not_of(" \t\r\n");
  const std::string closing = "</opencv_storage>";
  if (end + 1 < closing.size() || text.compare(end + 1 - closing.size(), closing.size(), closing)) {
    return "XML that does not end with " + closing + " (truncated?)";
  }
  return "";
}

// The camera matrix and distortion coefficients into `c`; what is wrong with them, or "".
std::string ReadMatrices(const cv::FileStorage& fs, LensCalibration* c) {
  std::string k_name, d_name;
  const cv::FileNode k =
      FirstOf(fs, {"camera_matrix", "Camera_Matrix", "cameraMatrix", "K"}, &k_name);
  const cv::FileNode d = FirstOf(
      fs, {"distortion_coefficients", "Distortion_Coefficients", "distCoeffs", "D"}, &d_name);
  if (k.empty()) return "no camera matrix (camera_matrix)";
  if (d.empty()) return "no distortion coefficients (distortion_coefficients)";
  int count = 0;
  std::string problem = MatrixProblem(
      k, k_name, [](int rows, int cols) { return rows == 3 && cols == 3; }, "values", "3 x 3",
      &count);
  if (!problem.empty()) return problem;
  problem = MatrixProblem(
      d, d_name,
      [](int rows, int cols) {
        const int64_t n = int64_t(rows) * cols;
        return (rows == 1 || cols == 1) && (n == 4 || n == 5 || n == 8 || n == 12 || n == 14);
      },
      "coefficients", "one row or column of 4, 5, 8, 12 or 14", &count);
  if (!problem.empty()) return problem;
  cv::Mat km, dm;
  k >> km;
  d >> dm;
  if (km.rows != 3 || km.cols != 3) return "the camera matrix is not 3 x 3";
  km.convertTo(km, CV_64F);
  c->camera = cv::Matx33d(km);
  dm.convertTo(dm, CV_64F);
  const int n = int(dm.total());
  if (!(n == 4 || n == 5 || n == 8 || n == 12 || n == 14)) {
    return "the distortion has " + std::to_string(n) + " coefficients (4, 5, 8, 12 or 14)";
  }
  c->distortion.assign(dm.ptr<double>(), dm.ptr<double>() + n);
  return "";
}

// A pinhole camera's matrix (fx 0 cx; 0 fy cy; 0 0 1) and finite coefficients, or what is not.
std::string CameraProblem(const LensCalibration& c) {
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(c.camera.val[i])) return "the camera matrix is not finite";
  }
  for (double v : c.distortion) {
    if (!std::isfinite(v)) return "a distortion coefficient is not finite";
  }
  if (!(c.camera(0, 0) > 0 && c.camera(1, 1) > 0) || c.camera(1, 0) != 0 ||
      c.camera(2, 0) != 0 || c.camera(2, 1) != 0 || c.camera(2, 2) != 1) {
    return "the camera matrix is not fx 0 cx; 0 fy cy; 0 0 1 with fx, fy > 0";
  }
  return "";
}

// The calibrated image size, where the file gives it, into `c`; what is wrong with it, or "".
std::string ReadImageSize(const cv::FileStorage& fs, LensCalibration* c) {
  std::string w_name, h_name;
  const cv::FileNode w = FirstOf(fs, {"image_width", "image_Width"}, &w_name);
  const cv::FileNode h = FirstOf(fs, {"image_height", "image_Height"}, &h_name);
  if (w.empty() != h.empty()) {
    return std::string(w.empty() ? "image_height" : "image_width") + " without " +
           (w.empty() ? "image_width" : "image_height");
  }
  if (w.empty()) return "";
  for (const auto& [node, name] : {std::pair{w, w_name}, std::pair{h, h_name}}) {
    const std::string problem = ImageSizeProblem(node, name);
    if (!problem.empty()) return problem;
  }
  c->image_size = cv::Size(int(w), int(h));
  return "";
}

}  // namespace

LensCalibration ReadLensCalibration(const std::string& path) {
  auto fail = [&](const std::string& what) { throw InputError(path + ": " + what); };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail("no such file (--lens)");
  LensCalibration c;
  c.path = path;
  if (const std::string problem = UnparsableTextProblem(path); !problem.empty()) fail(problem);
  try {
    cv::FileStorage fs(path, cv::FileStorage::READ);
    if (!fs.isOpened()) fail("not an OpenCV calibration file (YAML, XML or JSON)");
    if (std::string problem = ReadMatrices(fs, &c); !problem.empty()) fail(problem);
    if (std::string problem = CameraProblem(c); !problem.empty()) fail(problem);
    if (std::string problem = ReadImageSize(fs, &c); !problem.empty()) fail(problem);
    const cv::FileNode e = FirstOf(fs, {"avg_reprojection_error", "Avg_Reprojection_Error"});
    if (!e.empty() && e.isReal()) c.reprojection_error = double(e);
  } catch (const InputError&) {
    throw;
  } catch (const cv::Exception& ex) {
    fail(std::string("unreadable as an OpenCV calibration file: ") + ex.err);
  } catch (const std::exception& ex) {
    // OpenCV's parser lets the standard library's own exceptions out too: std::length_error on
    // an empty key in a map (found by tests/fuzz/fuzz_lens).
    fail(std::string("unreadable as an OpenCV calibration file: ") + ex.what());
  }
  return c;
}

LensUndistortion::LensUndistortion(const LensCalibration& c, cv::Size frame) {
  if (c.image_size.width > 0 && c.image_size != frame) {  // not area(): 65536^2 overflows int
    throw InputError(c.path + ": calibrated for " + std::to_string(c.image_size.width) + "x" +
                     std::to_string(c.image_size.height) + " images, the frames are " +
                     std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                     " (--lens)");
  }
  const cv::Mat k(c.camera);
  cv::initUndistortRectifyMap(k, c.distortion, cv::noArray(), k, frame, CV_32FC1, map_x_,
                              map_y_);
  for (int y = 0; y < frame.height; ++y) {
    const float* mx = map_x_.ptr<float>(y);
    const float* my = map_y_.ptr<float>(y);
    for (int x = 0; x < frame.width; ++x) {
      max_shift_px_ = std::max(max_shift_px_, std::hypot(double(mx[x]) - x, double(my[x]) - y));
    }
  }
}

cv::Mat LensUndistortion::Apply(const cv::Mat& frame) const {
  cv::Mat out;
  // Lanczos (8 x 8): on exact discs it keeps their centroids within 0.010 px where bicubic was
  // 0.027 off; bilinear (0.008) smooths by an amount that varies with the fraction it reads at.
  // On the POV-Ray lens films all three gave the same columns; Lanczos costs ~1.2 ms a 320 x 160
  // frame (see povray.lens).
  cv::remap(frame, out, map_x_, map_y_, cv::INTER_LANCZOS4, cv::BORDER_REPLICATE);
  return out;
}

}  // namespace dimer::tracking
