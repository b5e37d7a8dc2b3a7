#include "common/trajectory.h"

#include <cmath>
#include <stdexcept>

namespace dimer {

void Trajectory::Reserve(size_t n) {
  t.reserve(n);
  tip_left.reserve(n);
  tip_right.reserve(n);
  plate_z.reserve(n);
  theta.reserve(n);
}

void Trajectory::Append(double time, const Eigen::Vector2d& left, const Eigen::Vector2d& right,
                        double plate, double angle) {
  t.push_back(time);
  tip_left.push_back(left);
  tip_right.push_back(right);
  plate_z.push_back(plate);
  theta.push_back(angle);
}

void Trajectory::CheckConsistent() const {
  const size_t n = t.size();
  if (tip_left.size() != n || tip_right.size() != n || plate_z.size() != n || theta.size() != n) {
    throw std::logic_error("Trajectory: columns of different lengths");
  }
  for (size_t i = 1; i < n; ++i) {
    if (!(t[i] > t[i - 1])) throw std::logic_error("Trajectory: time not increasing");
  }
}

}  // namespace dimer
