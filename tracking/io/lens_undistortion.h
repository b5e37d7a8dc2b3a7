#pragma once
// A real lens bends straight lines: a lens with 1 % of barrel distortion at the frame's corner
// (360 px from the optical axis) moves a point 300 px from the axis by ~2 px, and its scale
// there differs from the axis's by ~2 %. A plate edge across the frame bows by a pixel, and a
// dimer that drifts across the frame changes its length and speed in pixels as it goes. Labs
// calibrate their lens with a chessboard (OpenCV's calibration sample or tutorial) and keep the
// result as an OpenCV FileStorage file; `track --lens FILE` reads it and undistorts every frame
// before anything is measured on it, so the tracker sees the pinhole camera it assumes.
//
// The undistorted frame keeps the calibration's camera matrix (cv::initUndistortRectifyMap with
// newCameraMatrix = the camera matrix): the scale at the optical axis, where `--m-per-px` is
// usually measured, is the same before and after, and nothing is cropped or zoomed.
#include <opencv2/core.hpp>

#include <limits>
#include <string>
#include <vector>

namespace dimer::tracking {

struct LensCalibration {
  std::string path;                // the file it was read from
  cv::Matx33d camera;              // fx 0 cx; 0 fy cy; 0 0 1 (px)
  std::vector<double> distortion;  // OpenCV's order: k1 k2 p1 p2 [k3 [k4 k5 k6 [s1 s2 s3 s4]]]
  cv::Size image_size;             // the calibration images' size; 0 x 0: the file does not say
  double reprojection_error = std::numeric_limits<double>::quiet_NaN();  // px, if the file says
};

// Reads an OpenCV FileStorage file (YAML, XML or JSON): the camera matrix under
// `camera_matrix` or `Camera_Matrix` (the calibration sample's and the tutorial's names, or
// `cameraMatrix`, `K`), the distortion under `distortion_coefficients`,
// `Distortion_Coefficients`, `distCoeffs` or `D` (4, 5, 8, 12 or 14 values), and if present the
// image size (`image_width` / `image_height`, either capitalisation) and
// `avg_reprojection_error`. Throws InputError "PATH: ..." naming what is missing or wrong.
LensCalibration ReadLensCalibration(const std::string& path);

// The undistortion of one frame size, computed once; Apply is const and may run on any number
// of threads at once.
class LensUndistortion {
 public:
  // Throws InputError naming the calibration file when it was made for another image size.
  LensUndistortion(const LensCalibration& calibration, cv::Size frame_size);

  // The frame as the pinhole camera would have taken it: same size and type, each pixel
  // interpolated (Lanczos, at OpenCV's 1/32 px steps) from where the lens put it; outside the
  // frame, its border.
  cv::Mat Apply(const cv::Mat& frame) const;

  // The largest distance between a pixel and where its light was recorded, px: how much the
  // lens moved anything in this frame size.
  double max_shift_px() const { return max_shift_px_; }

 private:
  cv::Mat map_x_, map_y_;  // CV_32FC1: where in the recorded frame each output pixel comes from
  double max_shift_px_ = 0;
};

}  // namespace dimer::tracking
