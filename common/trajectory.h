#pragma once
// The trajectory shared by `track` and `sim` files (docs/FORMATS.md, "Trajectory"), so that `compare` reads one type.
// Lab frame, SI units: x to the right, z up, z measured from the plate's mean surface.
// "left" is the sphere with the smaller x in the first sample where both are known; the
// identity is kept through the sequence. Missing values are NaN.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace dimer {

struct Trajectory {
  std::vector<double> t;                      // s
  std::vector<Eigen::Vector2d> tip_left;      // (x, z) of the left sphere centre, m
  std::vector<Eigen::Vector2d> tip_right;     // (x, z) of the right sphere centre, m
  std::vector<double> plate_z;                // plate surface height under the dimer, m
  std::vector<double> theta;                  // axis angle, rad, counter-clockwise, left -> right

  size_t size() const { return t.size(); }
  void Reserve(size_t n);
  void Append(double time, const Eigen::Vector2d& left, const Eigen::Vector2d& right,
              double plate, double angle);
  // Throws std::logic_error if the columns differ in length or time is not increasing.
  void CheckConsistent() const;
};

}  // namespace dimer
