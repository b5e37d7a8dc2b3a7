#pragma once
// Acquisition: finding the plate and the two spheres in a whole frame, with no prior. Used on
// the first frame of each chunk and whenever tracking loses a sphere; in between, the tracker
// only looks at windows around its predictions (frame_follower.h).
//
// Spheres are separated from the rod without knowing the geometry: above the plate, the frame
// is thresholded a few noise sigmas above its background into a silhouette, holes are filled (a mirror sphere's dark reflections),
// and the distance transform peaks at a sphere centre with the value ~R, while the rod, thin,
// never gets far from its edge. The two highest peaks, separated by more than a radius, are the
// spheres.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace dimer::tracking {

// +1 when objects are brighter than the background (front light), -1 when darker (backlit):
// the background is the frame's median, and the objects are the farther tail.
int DetectPolarity(const cv::Mat& frame);

struct Detection {
  double plate_row = 0;                 // coarse plate row (whole px), NaN if none
  std::vector<Eigen::Vector2d> centres; // 0, 1 or 2 coarse sphere centres (+-1 px)
  std::vector<double> radii_px;         // distance-transform radius of each
  std::vector<double> top_rows;         // the top of each one's blob, px
  // The image's strongest edge's row where the plate is another edge; NaN where it is the plate.
  double strongest_edge_row = std::numeric_limits<double>::quiet_NaN();
  bool plate_by_dimer = false;          // the dimer's lowest point moved the plate (below)
};

// `slope`: the plate edge's, rows per column (plate_slope.h): the plate left out is the band
// under the sloping line, and `plate_row` is the line's row at the frame's centre column.
// The plate is the edge the dimer stands on (plate/plate_under_dimer.h): the spheres are found
// above the image's choice of edge (FindPlateRowCoarse), and where one is missing or the lowest
// sphere's lowest point is more than kPlateMeetPx above that edge or more than kPlateBandHalfPx
// below it (farther than a plate whose top is in view puts its contact line below its far edge)
// and meets another candidate edge, the plate is that one and the spheres are found again above
// it (plate/plate_under_dimer.h). The lowest point is the sphere's top (its blob's, up the
// column of its centre: right even where a wrong edge cut the sphere's lower part away or a
// bright band joined it) plus a diameter of `radius_px` (the radius the tracker knows; NaN: the
// smallest distance-transform radius found).
Detection DetectSpheres(const cv::Mat& frame, int polarity, double slope = 0,
                        double radius_px = std::numeric_limits<double>::quiet_NaN());

}  // namespace dimer::tracking
