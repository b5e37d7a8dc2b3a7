#include "sim/persistent_contact.h"

#include <Eigen/Dense>
#include <cmath>

#include "sim/constants.h"
#include "sim/flat_contacts.h"

namespace dimer::sim {

ContactForces SolveContactForces(const Model& m, double t, const State& q,
                                 const ContactConfig& cfg) {
  return SolveContactForces(m, m.SinPhase(t), q, cfg);
}

namespace {

// Both contacts' arms from one sin/cos of theta (the same values as ContactArm).
std::array<Arm, 2> ContactArms(const Model& m, double th) {
  const double c = std::cos(th), s = std::sin(th);
  const double k = m.A * m.R;
  return {Arm{-k * c, -k * s - m.R}, Arm{k * c, k * s - m.R}};
}

// Accelerations from the forces (docs/MODEL.md): u' = g_x + sum F_T, v' = g_z + sum N,
// w' = (1/I) sum (r_x N - r_z F_T).
void SetAccelerations(const Model& m, double gx, double gz, const std::array<Arm, 2>& arm,
                      ContactForces* out) {
  out->ax = gx + out->f[0] + out->f[1];
  out->az = gz + out->n[0] + out->n[1];
  out->aw = m.inv_I * (arm[0].rx * out->n[0] + arm[1].rx * out->n[1] - arm[0].rz * out->f[0] -
                       arm[1].rz * out->f[1]);
}

// One resting sphere s: a 2x2 system (N, F_T) for sticking, a scalar one for sliding, solved
// in closed form. Rows as in SolveGeneral: dV/dt = 0, and dU/dt = 0 or F_T = -sgn(U) mu N.
ContactForces SolveOne(const Model& m, double gx, double gz, double w2,
                       const std::array<Arm, 2>& arm, int s, int slide) {
  const Arm& r = arm[s];
  const double k = m.inv_I;
  const double cn = -gz + w2 * (r.rz + m.R);  // normal row: (1 + k rx^2) N - k rx rz F = cn
  ContactForces out;
  if (slide == 0) {
    const double ct = -gx + w2 * r.rx;        // stick row: -k rx rz N + (1 + k rz^2) F = ct
    const double det = 1.0 + k * (r.rx * r.rx + r.rz * r.rz);  // >= 1
    out.n[s] = ((1.0 + k * r.rz * r.rz) * cn + k * r.rx * r.rz * ct) / det;
    out.f[s] = ((1.0 + k * r.rx * r.rx) * ct + k * r.rx * r.rz * cn) / det;
  } else {
    // Vanishes at Painleve's boundary: N is then infinite, as the general solve's.
    const double d = 1.0 + k * r.rx * (r.rx + slide * m.mu * r.rz);
    out.n[s] = cn / d;
    out.f[s] = -slide * m.mu * out.n[s];
  }
  SetAccelerations(m, gx, gz, arm, &out);
  if (!(std::isfinite(out.n[s]) && std::isfinite(out.f[s]))) out.ok = false;
  return out;
}

// Both spheres resting (the dimer lies flat, r_z equal): the two normal rows fix the normal and
// angular accelerations, a z' + r_x,s w' = w^2 (r_z,s + R), whatever the friction; the force
// balance then gives the sum of the normal forces and the torque their difference, with the
// friction law of each contact. Returns false (caller solves generally) when a divisor is
// near zero (a slide-slide configuration with A_r - 1 = mu, or not flat).
bool SolveFlatPair(const Model& m, double gx, double gz, double w2, const std::array<Arm, 2>& arm,
                   const ContactConfig& cfg, ContactForces* out) {
  const Arm &r0 = arm[0], &r1 = arm[1];
  const double scale = m.A * m.R;
  if (!(std::abs(r0.rz - r1.rz) <= 1e-12 * m.R)) return false;
  const double drx = r0.rx - r1.rx;  // +-2 A R
  const double aw = (w2 * (r0.rz + m.R) - w2 * (r1.rz + m.R)) / drx;
  const double az = w2 * (r0.rz + m.R) - r0.rx * aw;
  const double n_sum = az - gz;
  const double torque = aw / m.inv_I;  // r_x0 N0 + r_x1 N1 - r_z0 F0 - r_z1 F1
  const int sl0 = cfg.slide[0], sl1 = cfg.slide[1];
  double n1, f0, f1;
  if (sl0 == 0 && sl1 == 0) {
    // Only the sum of the tangential forces is determined (same lever arm r_z); shared like the
    // normal ones (flat_contacts.h), or evenly (the minimum norm) when they do not press.
    const double ax = 0.5 * ((w2 * r0.rx + r0.rz * aw) + (w2 * r1.rx + r1.rz * aw));
    const double f_sum = ax - gx;
    const double rz = 0.5 * (r0.rz + r1.rz);
    const double n0 = (torque + rz * f_sum - r1.rx * n_sum) / drx;
    n1 = n_sum - n0;
    if (n_sum > 0) {
      f0 = f_sum * n0 / n_sum;
      f1 = f_sum * n1 / n_sum;
    } else {
      f0 = f1 = 0.5 * f_sum;
    }
    out->n = {n0, n1};
    out->f = {f0, f1};
  } else if (sl0 != 0 && sl1 != 0) {
    // F_j = -sgn(U_j) mu N_j: torque = p0 N0 + p1 N1 with p_j = r_xj + sgn(U_j) mu r_zj.
    const double p0 = r0.rx + sl0 * m.mu * r0.rz, p1 = r1.rx + sl1 * m.mu * r1.rz;
    if (!(std::abs(p0 - p1) > 1e-6 * scale)) return false;
    const double n0 = (torque - p1 * n_sum) / (p0 - p1);
    n1 = n_sum - n0;
    out->n = {n0, n1};
    out->f = {-sl0 * m.mu * n0, -sl1 * m.mu * n1};
  } else {
    // Sphere i sticks, j slides: the stick row fixes u', hence F_i = u' - g_x - F_j.
    const int i = sl0 == 0 ? 0 : 1, j = 1 - i;
    const Arm &ri = arm[i], &rj = arm[j];
    const double sj = cfg.slide[j] * m.mu;
    const double ax = w2 * ri.rx + ri.rz * aw;
    // torque = r_xi N_i + r_xj N_j - r_zi (ax - g_x + sj N_j) + r_zj sj N_j, N_i = n_sum - N_j
    const double qj = rj.rx + sj * (rj.rz - ri.rz);
    const double denom = qj - ri.rx;
    if (!(std::abs(denom) > 1e-6 * scale)) return false;
    const double nj = (torque + ri.rz * (ax - gx) - ri.rx * n_sum) / denom;
    const double ni = n_sum - nj;
    out->n[i] = ni;
    out->n[j] = nj;
    out->f[j] = -sj * nj;
    out->f[i] = ax - gx - out->f[j];
  }
  SetAccelerations(m, gx, gz, arm, out);
  out->ok = std::isfinite(out->n[0] + out->n[1] + out->f[0] + out->f[1]);
  return true;
}

// Any configuration (the reference formulation, used where no closed form applies): the
// constraint rows as a 4x4 system, solved by a complete orthogonal decomposition.
ContactForces SolveGeneral(const Model& m, double gx, double gz, double w2,
                           const std::array<Arm, 2>& arm, const ContactConfig& cfg) {
  ContactForces out;
  int idx[2], n = 0;
  for (int s = 0; s < 2; ++s)
    if (cfg.resting[s]) idx[n++] = s;
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

}  // namespace

ContactForces SolveContactForces(const Model& m, Model::PlatePhase phase, const State& q,
                                 const ContactConfig& cfg) {
  const double gz = m.Gz(phase), gx = m.Gx(), w2 = q.w * q.w;
  const std::array<Arm, 2> arm = ContactArms(m, q.th);
  switch (cfg.Count()) {
    case 0: {
      ContactForces out;
      SetAccelerations(m, gx, gz, arm, &out);
      return out;
    }
    case 1: {
      const int s = cfg.resting[0] ? 0 : 1;
      return SolveOne(m, gx, gz, w2, arm, s, cfg.slide[s]);
    }
    default: {
      ContactForces out;
      if (SolveFlatPair(m, gx, gz, w2, arm, cfg, &out)) return out;
      return SolveGeneral(m, gx, gz, w2, arm, cfg);
    }
  }
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
  // adds it (a plain assignment v = -w r_x can). In closed form, since the constraint rows
  // J (V_s, and U_s when sticking) have few shapes; M = diag(1, 1, I).
  if (cfg.Count() == 2) {
    // Flat (theta = k pi just above, r_x = -+A R): the two V rows force v = w = 0. A sticking
    // contact's U row then forces u = 0 too (J has rank 3); two sliding contacts keep u (the
    // mass-metric projection onto the null space, the u axis).
    q->v = 0;
    q->w = 0;
    if (cfg.slide[0] == 0 || cfg.slide[1] == 0) q->u = 0;
    return;
  }
  const int s = cfg.resting[0] ? 0 : cfg.resting[1] ? 1 : -1;
  if (s < 0) return;
  const Arm r = ContactArm(m, q->th, s);
  if (cfg.slide[s] == 0) {
    // J = [V row; U row]; its null space is spanned by d = (r_z, -r_x, 1) (rolling about the
    // contact point): vel' = d (d^T M vel) / (d^T M d).
    const double I = 1.0 / m.inv_I;
    const double c = (r.rz * q->u - r.rx * q->v + I * q->w) / (r.rz * r.rz + r.rx * r.rx + I);
    q->u = r.rz * c;
    q->v = -r.rx * c;
    q->w = c;
  } else {
    // J = V row (0, 1, r_x): impulse lambda = -V / (J M^-1 J^T), vel' = vel + M^-1 J^T lambda.
    const double lambda = -(q->v + r.rx * q->w) / (1.0 + m.inv_I * r.rx * r.rx);
    q->v += lambda;
    q->w += m.inv_I * r.rx * lambda;
  }
}

bool LayFlatOnTouchingSphere(const Model& m, const ContactConfig& cfg, State* q) {
  if (cfg.Count() != 1) return false;
  const int other = cfg.resting[0] ? 1 : 0;
  const double gap = Gap(m, *q, other);
  // Deeper than the touching band is a missed impact, not this: left for the penetration check.
  if (!(gap < 0 && gap >= -kTouchTol_m)) return false;
  q->th = std::round(q->th / M_PI) * M_PI;
  q->z = m.R;
  ProjectOnContacts(m, cfg, q);
  return true;
}

}  // namespace dimer::sim
