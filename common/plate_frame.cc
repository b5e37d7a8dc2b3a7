#include "common/plate_frame.h"

#include <cmath>
#include <numbers>

namespace dimer {
namespace {

// (x, z) turned by -alpha: components along the plate (cos, sin) and its normal (-sin, cos).
Eigen::Vector2d Turn(const Eigen::Vector2d& p, double c, double s) {
  return {c * p.x() + s * p.y(), -s * p.x() + c * p.y()};
}

}  // namespace

Trajectory InPlateFrame(Trajectory lab, double tilt_deg) {
  if (tilt_deg == 0) return lab;
  const double a = tilt_deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  for (size_t i = 0; i < lab.size(); ++i) {
    // The plate's surface point under the dimer, (x_mid, plate_z), lies on the plate: its
    // normal coordinate is the plate's displacement, whatever x_mid is.
    const double x_mid = 0.5 * (lab.tip_left[i].x() + lab.tip_right[i].x());
    lab.plate_z[i] = -s * x_mid + c * lab.plate_z[i];
    lab.tip_left[i] = Turn(lab.tip_left[i], c, s);
    lab.tip_right[i] = Turn(lab.tip_right[i], c, s);
    lab.theta[i] -= a;
  }
  return lab;
}

std::array<double, 6> StateInPlateFrame(const std::array<double, 6>& lab, double tilt_deg) {
  if (tilt_deg == 0) return lab;
  const double a = tilt_deg * std::numbers::pi / 180, c = std::cos(a), s = std::sin(a);
  return {c * lab[0] + s * lab[1], -s * lab[0] + c * lab[1], lab[2] - a,
          c * lab[3] + s * lab[4], -s * lab[3] + c * lab[4], lab[5]};
}

}  // namespace dimer
