#pragma once
// The mutable state of the dimer, in the plate frame (model.h): CM position (x, z) with z from
// the plate surface, axis angle th (counter-clockwise, left -> right sphere), and velocities
// relative to the plate. Contact geometry of sphere s (0 left, 1 right) lives here too, since
// every stage needs it (docs/MODEL.md, "Contact kinematics").
#include <array>
#include <cmath>

#include "sim/model.h"

namespace dimer::sim {

struct State {
  double x = 0, z = 0, th = 0;  // m, m, rad
  double u = 0, v = 0, w = 0;   // m/s, m/s, rad/s
};

enum Sphere : int { kLeft = 0, kRight = 1 };
inline double SphereSign(int s) { return s == kRight ? 1.0 : -1.0; }

// Offset r from the CM to the lowest point of sphere s.
struct Arm {
  double rx, rz;
};
inline Arm ContactArm(const Model& m, double th, int s) {
  const double k = SphereSign(s) * m.A * m.R;
  return {k * std::cos(th), k * std::sin(th) - m.R};
}

// Gap h_s (height of the lowest point above the plate), slip U_s and normal velocity V_s.
inline double Gap(const Model& m, const State& q, int s) {
  return q.z + ContactArm(m, q.th, s).rz;
}
inline double SlipU(const Arm& r, const State& q) { return q.u - q.w * r.rz; }
inline double NormalV(const Arm& r, const State& q) { return q.v + q.w * r.rx; }

// Kinetic + potential energy per unit mass in the plate frame with a still plate
// (used by energy tests; with a moving plate energy is exchanged with the drive).
inline double Energy(const Model& m, const State& q) {
  const double I = 1.0 / m.inv_I;
  return 0.5 * (q.u * q.u + q.v * q.v + I * q.w * q.w) + kGravity * (q.z * m.cos_a + q.x * m.sin_a);
}

}  // namespace dimer::sim
