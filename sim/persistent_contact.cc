#include "sim/persistent_contact.h"

#include <Eigen/Dense>
#include <cmath>

#include "sim/constants.h"
#include "sim/flat_contacts.h"

namespace dimer::sim {

ContactForces SolveContactForces(const Model& m, double t, const State& q,
                                 const ContactConfig& cfg) {
  ContactForces out;
  int idx[2], n = 0;
  for (int s = 0; s < 2; ++s)
    if (cfg.resting[s]) idx[n++] = s;
  const double gz = m.Gz(t), gx = m.Gx(), w2 = q.w * q.w;
  Arm arm[2] = {ContactArm(m, q.th, kLeft), ContactArm(m, q.th, kRight)};
  // Unknowns: N of contact k at column k, F_T at column n + k. Accelerations are
  // acc = acc_free + B x, with B's columns the response to a unit force.
  Eigen::Matrix<double, 3, 4> B = Eigen::Matrix<double, 3, 4>::Zero();
  for (int k = 0; k < n; ++k) {
    const Arm& r = arm[idx[k]];
    B.col(k) << 0.0, 1.0, m.inv_I * r.rx;
    B.col(n + k) << 1.0, 0.0, -m.inv_I * r.rz;
  }
  const Eigen::Vector3d acc_free(gx, gz, 0.0);
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  for (int k = 0; k < n; ++k) {
    const Arm& r = arm[idx[k]];
    const Eigen::RowVector3d jn(0.0, 1.0, r.rx), jt(1.0, 0.0, -r.rz);
    // dV/dt = jn . acc - w^2 (r_z + R) = 0
    a.row(k).head(2 * n) = jn * B.leftCols(2 * n);
    b(k) = -(jn * acc_free - w2 * (r.rz + m.R));
    const int sl = cfg.slide[idx[k]];
    if (sl == 0) {  // dU/dt = jt . acc - w^2 r_x = 0
      a.row(n + k).head(2 * n) = jt * B.leftCols(2 * n);
      b(n + k) = -(jt * acc_free - w2 * r.rx);
    } else {  // F_T + sgn(U) mu N = 0
      a(n + k, n + k) = 1.0;
      a(n + k, k) = sl * m.mu;
    }
  }
  Eigen::Vector4d x = Eigen::Vector4d::Zero();
  if (n == 1) {
    x.head<2>() = a.topLeftCorner<2, 2>().partialPivLu().solve(b.head<2>());
  } else if (n == 2) {
    x = a.completeOrthogonalDecomposition().solve(b);
    if ((a * x - b).norm() > 1e-9 * (1.0 + b.norm())) out.ok = false;
  }
  if (!x.allFinite()) out.ok = false;
  const bool flat = std::abs(arm[0].rz - arm[1].rz) <= 1e-12 * m.R;
  if (n == 2 && cfg.slide[0] == 0 && cfg.slide[1] == 0 && flat) {
    ShareTangentialByNormal(x);  // flat, both sticking (flat_contacts.h)
  }
  for (int k = 0; k < n; ++k) {
    out.n[idx[k]] = x(k);
    out.f[idx[k]] = x(n + k);
  }
  const Eigen::Vector3d acc = acc_free + B * x;
  out.ax = acc(0);
  out.az = acc(1);
  out.aw = acc(2);
  return out;
}

ModeChoice ChooseContactMode(const Model& m, double t, const State& q,
                             std::array<bool, 2> candidates) {
  ModeChoice mc;
  mc.cfg.resting = candidates;
  const double zero_u = kSlipZeroRel * m.vel_scale;
  for (int s = 0; s < 2; ++s) {
    const double u = SlipU(ContactArm(m, q.th, s), q);
    mc.cfg.slide[s] = std::abs(u) <= zero_u ? 0 : (u > 0 ? 1 : -1);
  }
  for (int iter = 0; iter < 8; ++iter) {
    mc.forces = SolveContactForces(m, t, q, mc.cfg);
    bool changed = false;
    // A sticking contact outside the static cone starts to slide against the needed force.
    for (int s = 0; s < 2 && !changed; ++s) {
      if (!mc.cfg.resting[s] || mc.cfg.slide[s] != 0) continue;
      if (std::abs(mc.forces.f[s]) > m.mu_s * mc.forces.n[s] && mc.forces.n[s] > 0) {
        mc.cfg.slide[s] = mc.forces.f[s] > 0 ? -1 : 1;
        changed = true;
      }
    }
    if (changed) continue;
    // The most negative normal force lifts off first.
    int worst = -1;
    for (int s = 0; s < 2; ++s) {
      if (mc.cfg.resting[s] && mc.forces.n[s] < 0 &&
          (worst < 0 || mc.forces.n[s] < mc.forces.n[worst])) {
        worst = s;
      }
    }
    if (worst < 0) return mc;
    // Painleve: a sliding contact with N < 0 whose free motion would still press into the
    // plate has no consistent force; the caller resolves it by an impact without collision.
    if (mc.cfg.slide[worst] != 0) {
      ContactConfig without = mc.cfg;
      without.resting[worst] = false;
      const ContactForces fw = SolveContactForces(m, t, q, without);
      const Arm r = ContactArm(m, q.th, worst);
      const double vdot = fw.az + fw.aw * r.rx - q.w * q.w * (r.rz + m.R);
      if (vdot < 0) {
        mc.painleve_sphere = worst;
        return mc;
      }
    }
    mc.cfg.resting[worst] = false;
  }
  return mc;
}

void ProjectOnContacts(const Model& m, const ContactConfig& cfg, State* q) {
  // Positions: the resting spheres' gaps are set to zero (both resting: flat, theta = k pi).
  if (cfg.Count() == 2) {
    q->th = std::round(q->th / M_PI) * M_PI;
    q->z = m.R;
  } else {
    for (int s = 0; s < 2; ++s) {
      if (cfg.resting[s]) q->z = -ContactArm(m, q->th, s).rz;
    }
  }
  // Velocities: the projection that is orthogonal in the mass metric, i.e. the result of the
  // smallest impulses that zero V (and U when sticking). It removes kinetic energy, never
  // adds it (a plain assignment v = -w r_x can).
  Eigen::Matrix<double, 4, 3> J;
  int rows = 0;
  for (int s = 0; s < 2; ++s) {
    if (!cfg.resting[s]) continue;
    const Arm r = ContactArm(m, q->th, s);
    J.row(rows++) << 0.0, 1.0, r.rx;
    if (cfg.slide[s] == 0) J.row(rows++) << 1.0, 0.0, -r.rz;
  }
  if (rows == 0) return;
  // Run-time sizes up to 4 with fixed storage: no heap allocation in the integration loop.
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
  using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 4, 1>;
  const Small Jr = J.topRows(rows);
  const Eigen::Vector3d minv(1.0, 1.0, m.inv_I);
  const Small JMinv = Jr * minv.asDiagonal();
  const Small A = JMinv * Jr.transpose();
  Eigen::Vector3d vel(q->u, q->v, q->w);
  const SmallVec impulse = A.completeOrthogonalDecomposition().solve(-(Jr * vel));
  vel += JMinv.transpose() * impulse;
  q->u = vel(0);
  q->v = vel(1);
  q->w = vel(2);
}

}  // namespace dimer::sim
