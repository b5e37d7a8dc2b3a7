#include "sim/impact_law.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/constants.h"

namespace dimer::sim {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Friction { kSlide, kStick };

struct ContactRow {
  Vec3 jt, jn;   // U = jt . (u, v, w), V = jn . (u, v, w)
  double target = 0;
  Friction mode = Friction::kSlide;
  double sigma = 0;  // slip direction while sliding
  bool active = false;
};

// Generalized velocity change per unit impulse along direction j: M^-1 j^T.
Vec3 Response(const Model& m, const Vec3& j) { return {j(0), j(1), j(2) * m.inv_I}; }

struct Rates {
  std::array<double, 2> dn{}, dt{};
  Vec3 dvel = Vec3::Zero();
  bool ok = true;
};

// Impulse rates for the active contacts (see header): sum of dN = 1, equal deficit rates when
// two are active, and the friction law of each active contact.
Rates SolveRates(const Model& m, const std::array<ContactRow, 2>& c) {
  int idx[2], n = 0;
  for (int i = 0; i < 2; ++i)
    if (c[i].active) idx[n++] = i;
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  // Unknowns: dN of active k at column k, dT at column n + k.
  auto col_vec = [&](int k) -> Vec3 {
    return k < n ? Response(m, c[idx[k]].jn) : Response(m, c[idx[k - n]].jt);
  };
  int row = 0;
  for (int k = 0; k < n; ++k) a(row, k) = 1.0;
  b(row++) = 1.0;
  if (n == 2) {
    for (int k = 0; k < 2 * n; ++k) a(row, k) = (c[idx[0]].jn - c[idx[1]].jn).dot(col_vec(k));
    ++row;
  }
  for (int k = 0; k < n; ++k) {
    const ContactRow& ci = c[idx[k]];
    if (ci.mode == Friction::kSlide) {
      a(row, n + k) = 1.0;
      a(row, k) = ci.sigma * m.mu_hat;
    } else {
      for (int j = 0; j < 2 * n; ++j) a(row, j) = ci.jt.dot(col_vec(j));
    }
    ++row;
  }
  const int dim = 2 * n;
  Eigen::MatrixXd as = a.topLeftCorner(dim, dim);
  Eigen::VectorXd x = as.completeOrthogonalDecomposition().solve(b.head(dim));
  Rates r;
  if (!x.allFinite() || (as * x - b.head(dim)).norm() > 1e-9) r.ok = false;
  if (n == 2 && c[idx[0]].mode == Friction::kStick && c[idx[1]].mode == Friction::kStick &&
      (c[idx[0]].jt - c[idx[1]].jt).norm() <= 1e-12 * c[idx[0]].jt.norm()) {
    // Flat, both sticking: only the sum of the tangential impulses matters; share it in
    // proportion to the normal impulses (see persistent_contact.cc for the same choice).
    const double n_sum = x(0) + x(1), t_sum = x(2) + x(3);
    if (n_sum > 0) {
      x(2) = t_sum * x(0) / n_sum;
      x(3) = t_sum * x(1) / n_sum;
    }
  }
  for (int k = 0; k < n; ++k) {
    r.dn[idx[k]] = x(k);
    r.dt[idx[k]] = x(n + k);
    r.dvel += col_vec(k) * x(k) + col_vec(n + k) * x(n + k);
  }
  return r;
}

// Adjust the active set and friction modes until the rates are admissible: no negative normal
// share, stick only inside the impact friction cone.
Rates AdmissibleRates(const Model& m, std::array<ContactRow, 2>& c, std::array<bool, 2>& slid,
                      std::array<double, 2>& first_sigma, std::array<bool, 2>& reversed) {
  Rates r;
  for (int iter = 0; iter < 8; ++iter) {
    r = SolveRates(m, c);
    bool changed = false;
    for (int i = 0; i < 2 && !changed; ++i) {
      if (!c[i].active) continue;
      if (c[i].active && c[0].active && c[1].active && r.dn[i] < 0) {
        c[i].active = false;  // its deficit rises faster alone: it leaves the active set
        changed = true;
      } else if (c[i].mode == Friction::kStick &&
                 std::abs(r.dt[i]) > m.mu_hat_s * r.dn[i] * (1 + 1e-12)) {
        c[i].mode = Friction::kSlide;  // slip develops against the friction it would need
        c[i].sigma = r.dt[i] > 0 ? -1.0 : 1.0;
        if (slid[i] && first_sigma[i] != c[i].sigma) reversed[i] = true;
        if (!slid[i]) first_sigma[i] = c[i].sigma;
        slid[i] = true;
        changed = true;
      }
    }
    if (!changed) return r;
  }
  r.ok = false;
  return r;
}

}  // namespace

namespace {

// Newton's law with every restitution target scaled by `lambda` (1: the plain law).
ImpactOutcome ResolveNewton(const Model& m, const State& before, std::array<bool, 2> touching,
                            std::array<bool, 2> forced, double lambda) {
  ImpactOutcome out;
  Vec3 vel(before.u, before.v, before.w);
  const double zero_u = kSlipZeroRel * m.vel_scale;
  std::array<ContactRow, 2> c;
  std::array<bool, 2> slid{}, reversed{};
  std::array<double, 2> first_sigma{};
  for (int s = 0; s < 2; ++s) {
    const Arm r = ContactArm(m, before.th, s);
    c[s].jt = Vec3(1.0, 0.0, -r.rz);
    c[s].jn = Vec3(0.0, 1.0, r.rx);
    const double vb = c[s].jn.dot(vel);
    out.v_before[s] = vb;
    const bool slow = std::abs(vb) < m.v_collapse;
    c[s].target = -(slow ? 0.0 : lambda * m.eps) * std::min(vb, 0.0);
    out.collapsed[s] = touching[s] && slow && vb < 0;
  }
  auto deficit = [&](int s) { return c[s].jn.dot(vel) - c[s].target; };
  auto activate = [&](int s) {
    c[s].active = true;
    const double u = c[s].jt.dot(vel);
    if (std::abs(u) <= zero_u) {
      c[s].mode = Friction::kStick;
    } else {
      c[s].mode = Friction::kSlide;
      c[s].sigma = u > 0 ? 1.0 : -1.0;
      if (slid[s] && first_sigma[s] != c[s].sigma) reversed[s] = true;
      if (!slid[s]) first_sigma[s] = c[s].sigma;
      slid[s] = true;
    }
  };
  const double deficit_tol = 1e-13 * m.vel_scale;  // equal deficits, to round-off
  bool first = true;
  for (; out.segments < kMaxImpactSegments; ++out.segments) {
    // Active set: touching contacts at the lowest deficit (forced ones at the first segment).
    double gmin = kInf;
    for (int s = 0; s < 2; ++s)
      if (touching[s]) gmin = std::min(gmin, deficit(s));
    const bool any_forced = first && (forced[0] || forced[1]);
    if (!(gmin < -deficit_tol) && !any_forced) break;
    for (int s = 0; s < 2; ++s) {
      const bool should = touching[s] && (deficit(s) <= gmin + deficit_tol || (first && forced[s]));
      if (should && !c[s].active) activate(s);
      if (!should) c[s].active = false;
    }
    first = false;
    Rates r = AdmissibleRates(m, c, slid, first_sigma, reversed);
    if (!r.ok) {
      out.ok = false;
      break;
    }
    // The next event along P (total normal impulse), all in closed form.
    double dp = kInf;
    bool ends = false;
    int lead = c[0].active ? 0 : 1;
    const double g_lead = deficit(lead), gd_lead = c[lead].jn.dot(r.dvel);
    if (gd_lead > 0 && g_lead < 0) {
      dp = -g_lead / gd_lead;
      ends = true;
    }
    for (int s = 0; s < 2; ++s) {
      if (!touching[s]) continue;
      if (!c[s].active) {
        const double gd = c[s].jn.dot(r.dvel);
        if (gd_lead > gd) {
          const double d = (deficit(s) - g_lead) / (gd_lead - gd);
          if (d < dp) dp = std::max(d, 0.0), ends = false;
        }
      } else if (c[s].mode == Friction::kSlide) {
        const double u = c[s].jt.dot(vel), ud = c[s].jt.dot(r.dvel);
        // A slip that has just started from rest is at round-off size with either sign:
        // it cannot "stop" again before it has grown.
        if (u * ud < 0 && std::abs(u) > zero_u && -u / ud < dp) dp = -u / ud, ends = false;
      }
    }
    if (!std::isfinite(dp)) {
      out.ok = false;
      break;
    }
    vel += r.dvel * dp;
    for (int s = 0; s < 2; ++s) {
      out.pn[s] += r.dn[s] * dp;
      out.pt[s] += r.dt[s] * dp;
    }
    // Slip that just stopped sticks from now on (checked against mu_hat_s at the next solve).
    for (int s = 0; s < 2; ++s) {
      if (c[s].active && c[s].mode == Friction::kSlide &&
          std::abs(c[s].jt.dot(vel)) <= zero_u + 1e-12 * std::abs(c[s].jt.dot(r.dvel) * dp)) {
        c[s].mode = Friction::kStick;
      }
    }
    if (ends) {
      ++out.segments;
      break;
    }
  }
  if (out.segments >= kMaxImpactSegments) out.ok = false;
  out.after = before;
  out.after.u = vel(0);
  out.after.v = vel(1);
  out.after.w = vel(2);
  for (int s = 0; s < 2; ++s) {
    out.took_part[s] = out.pn[s] > 0;
    out.stuck[s] = out.took_part[s] && c[s].mode == Friction::kStick;
    out.reversed[s] = reversed[s];
    out.collapsed[s] = out.collapsed[s] && out.took_part[s];
  }
  return out;
}

double Kinetic(const Model& m, const State& q) {
  return 0.5 * (q.u * q.u + q.v * q.v + q.w * q.w / m.inv_I);
}

}  // namespace

const std::vector<std::pair<std::string, RestitutionLaw>>& RestitutionLawNames() {
  static const std::vector<std::pair<std::string, RestitutionLaw>> kNames = {
      {"capped", RestitutionLaw::kCappedNewton}, {"newton", RestitutionLaw::kNewton}};
  return kNames;
}

ImpactOutcome ResolveImpact(const Model& m, const State& before, std::array<bool, 2> touching,
                            std::array<bool, 2> forced) {
  ImpactOutcome out = ResolveNewton(m, before, touching, forced, 1.0);
  const double e0 = Kinetic(m, before);
  out.energy_gain = Kinetic(m, out.after) - e0;
  // Gains at the level of round-off in the energy itself are not Stronge's effect.
  if (!(out.energy_gain > kEnergyRoundoffRel * e0)) out.energy_gain = 0;
  if (m.restitution != RestitutionLaw::kCappedNewton || !(out.energy_gain > 0)) return out;
  // Newton's kinematic restitution with friction can return more energy than it took when
  // slip stops or reverses in the restitution phase (Stronge 1990). Lower every target by
  // the same factor, found by bisection, until the impact no longer creates energy; the
  // plastic end (lambda = 0) never does: all normal and friction work is then dissipative.
  double lo = 0, hi = 1;
  ImpactOutcome best = ResolveNewton(m, before, touching, forced, 0.0);
  for (int i = 0; i < 60 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    ImpactOutcome trial = ResolveNewton(m, before, touching, forced, mid);
    if (Kinetic(m, trial.after) <= e0) {
      lo = mid;
      best = trial;
    } else {
      hi = mid;
    }
  }
  best.energy_gain = out.energy_gain;  // what plain Newton would have created
  best.restitution_scale = lo;
  return best;
}

}  // namespace dimer::sim
