#include "sim/reference_frames.h"

#include <cmath>

namespace dimer::sim {

State LabFromPlate(const Model& m, double t, const State& q) {
  return LabFromPlate(m, m.Phase(t), q);
}

State LabFromPlate(const Model& m, Model::PlatePhase p, const State& q) {
  const double c = m.cos_a, s = m.sin_a, zp = m.PlateZ(p), vp = m.PlateV(p);
  State o;
  o.x = c * q.x - s * q.z - s * zp;
  o.z = s * q.x + c * q.z + c * zp;
  o.u = c * q.u - s * q.v - s * vp;
  o.v = s * q.u + c * q.v + c * vp;
  o.th = q.th + std::atan2(s, c);
  o.w = q.w;
  return o;
}

State PlateFromLab(const Model& m, double t, const State& lab) {
  const double c = m.cos_a, s = m.sin_a, zp = m.PlateZ(t), vp = m.PlateV(t);
  const double x = lab.x + s * zp, z = lab.z - c * zp;
  const double u = lab.u + s * vp, v = lab.v - c * vp;
  State q;
  q.x = c * x + s * z;
  q.z = -s * x + c * z;
  q.u = c * u + s * v;
  q.v = -s * u + c * v;
  q.th = lab.th - std::atan2(s, c);
  q.w = lab.w;
  return q;
}

Eigen::Vector2d TipLab(const Model& m, const State& lab, int sphere) {
  const double k = SphereSign(sphere) * m.A * m.R;
  return {lab.x + k * std::cos(lab.th), lab.z + k * std::sin(lab.th)};
}

double PlateSurfaceZ(const Model& m, double t, double x) {
  return (m.PlateZ(t) + x * m.sin_a) / m.cos_a;
}

}  // namespace dimer::sim
