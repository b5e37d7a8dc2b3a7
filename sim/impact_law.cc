#include "sim/impact_law.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/constants.h"
#include "sim/flat_contacts.h"

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
  // Slip history, for the outcome: did it slide, in which direction first, did it reverse.
  bool slid = false, reversed = false;
  double first_sigma = 0;

  void Slide(double direction) {
    mode = Friction::kSlide;
    sigma = direction;
    if (slid && first_sigma != sigma) reversed = true;
    if (!slid) first_sigma = sigma;
    slid = true;
  }
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
  if (n == 1) {
    // One active contact, in closed form: dN = 1, and dT = -sgn(U) mu_hat (sliding) or the
    // rate that keeps U constant, jt . (M^-1 jn + M^-1 jt dT) = 0 (sticking; jt M^-1 jt >= 1).
    const ContactRow& ci = c[idx[0]];
    const Vec3 rn = Response(m, ci.jn), rt = Response(m, ci.jt);
    const double dt = ci.mode == Friction::kSlide ? -ci.sigma * m.mu_hat
                                                  : -ci.jt.dot(rn) / ci.jt.dot(rt);
    Rates r;
    r.dn[idx[0]] = 1.0;
    r.dt[idx[0]] = dt;
    r.dvel = rn + rt * dt;
    r.ok = std::isfinite(dt);
    return r;
  }
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
  // Run-time size with fixed storage (no heap allocation per impact segment).
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4> as = a.topLeftCorner(dim, dim);
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 4, 1> x =
      as.completeOrthogonalDecomposition().solve(b.head(dim));
  Rates r;
  if (!x.allFinite() || (as * x - b.head(dim)).norm() > 1e-9) r.ok = false;
  if (n == 2 && c[idx[0]].mode == Friction::kStick && c[idx[1]].mode == Friction::kStick &&
      (c[idx[0]].jt - c[idx[1]].jt).norm() <= 1e-12 * c[idx[0]].jt.norm()) {
    ShareTangentialByNormal(x);  // flat, both sticking (flat_contacts.h)
  }
  for (int k = 0; k < n; ++k) {
    r.dn[idx[k]] = x(k);
    r.dt[idx[k]] = x(n + k);
    r.dvel += col_vec(k) * x(k) + col_vec(n + k) * x(n + k);
  }
  return r;
}

// Routh's integration of one impact (header), as a sequence of linear segments. Each segment
// is: (1) the active set (contacts at the lowest deficit); (2) admissible impulse rates;
// (3) the first event along the total normal impulse P, in closed form; (4) the advance.
class RouthImpact {
 public:
  RouthImpact(const Model& m, const State& before, std::array<bool, 2> touching,
              std::array<bool, 2> forced, double lambda);
  ImpactOutcome Run();

 private:
  double Deficit(int s) const { return c_[s].jn.dot(vel_) - c_[s].target; }
  double Slip(int s) const { return c_[s].jt.dot(vel_); }
  bool SelectActive(bool first);
  void Activate(int s);
  Rates AdmissibleRates();
  double NextEvent(const Rates& r, bool* ends) const;
  void Advance(const Rates& r, double dp);

  const Model& m_;
  const State before_;
  std::array<bool, 2> touching_, forced_;
  std::array<ContactRow, 2> c_;
  Vec3 vel_;
  ImpactOutcome out_;
  double zero_u_;
  double deficit_tol_;  // deficits equal to round-off
};

RouthImpact::RouthImpact(const Model& m, const State& before, std::array<bool, 2> touching,
                         std::array<bool, 2> forced, double lambda)
    : m_(m), before_(before), touching_(touching), forced_(forced),
      vel_(before.u, before.v, before.w), zero_u_(kSlipZeroRel * m.vel_scale),
      deficit_tol_(1e-13 * m.vel_scale) {
  for (int s = 0; s < 2; ++s) {
    const Arm r = ContactArm(m, before.th, s);
    c_[s].jt = Vec3(1.0, 0.0, -r.rz);
    c_[s].jn = Vec3(0.0, 1.0, r.rx);
    const double vb = c_[s].jn.dot(vel_);
    out_.v_before[s] = vb;
    const bool slow = std::abs(vb) < m.v_collapse;  // collapse: plastic
    c_[s].target = -(slow ? 0.0 : lambda * m.eps) * std::min(vb, 0.0);
    out_.collapsed[s] = touching[s] && slow && vb < 0;
  }
}

void RouthImpact::Activate(int s) {
  c_[s].active = true;
  const double u = Slip(s);
  if (std::abs(u) <= zero_u_) {
    c_[s].mode = Friction::kStick;
  } else {
    c_[s].Slide(u > 0 ? 1.0 : -1.0);
  }
}

// Touching contacts at the lowest deficit (and forced ones at the first segment). False when
// no deficit is negative: the impact is over.
bool RouthImpact::SelectActive(bool first) {
  double gmin = kInf;
  for (int s = 0; s < 2; ++s)
    if (touching_[s]) gmin = std::min(gmin, Deficit(s));
  const bool any_forced = first && (forced_[0] || forced_[1]);
  if (!(gmin < -deficit_tol_) && !any_forced) return false;
  for (int s = 0; s < 2; ++s) {
    const bool lowest = Deficit(s) <= gmin + deficit_tol_;
    const bool should = touching_[s] && (lowest || (first && forced_[s]));
    if (should && !c_[s].active) Activate(s);
    if (!should) c_[s].active = false;
  }
  return true;
}

// Adjust the active set and friction modes until the rates are admissible: no negative normal
// share, stick only inside the impact friction cone.
Rates RouthImpact::AdmissibleRates() {
  Rates r;
  for (int iter = 0; iter < 8; ++iter) {
    r = SolveRates(m_, c_);
    bool changed = false;
    for (int i = 0; i < 2 && !changed; ++i) {
      if (!c_[i].active) continue;
      if (c_[0].active && c_[1].active && r.dn[i] < 0) {
        c_[i].active = false;  // its deficit rises faster alone: it leaves the active set
        changed = true;
      } else if (c_[i].mode == Friction::kStick &&
                 std::abs(r.dt[i]) > m_.mu_hat_s * r.dn[i] * (1 + 1e-12)) {
        c_[i].Slide(r.dt[i] > 0 ? -1.0 : 1.0);  // slip develops against the needed friction
        changed = true;
      }
    }
    if (!changed) return r;
  }
  r.ok = false;
  return r;
}

// Increment of P to the next event: the lead deficit reaching zero (the end), another deficit
// catching up with it (joins), or a sliding contact's slip reaching zero.
double RouthImpact::NextEvent(const Rates& r, bool* ends) const {
  double dp = kInf;
  *ends = false;
  const int lead = c_[0].active ? 0 : 1;
  const double g_lead = Deficit(lead), gd_lead = c_[lead].jn.dot(r.dvel);
  if (gd_lead > 0 && g_lead < 0) {
    dp = -g_lead / gd_lead;
    *ends = true;
  }
  for (int s = 0; s < 2; ++s) {
    if (!touching_[s]) continue;
    if (!c_[s].active) {
      const double gd = c_[s].jn.dot(r.dvel);
      if (gd_lead > gd) {
        const double d = (Deficit(s) - g_lead) / (gd_lead - gd);
        if (d < dp) dp = std::max(d, 0.0), *ends = false;
      }
    } else if (c_[s].mode == Friction::kSlide) {
      const double u = Slip(s), ud = c_[s].jt.dot(r.dvel);
      // A slip that has just started from rest is at round-off size with either sign:
      // it cannot "stop" again before it has grown.
      if (u * ud < 0 && std::abs(u) > zero_u_ && -u / ud < dp) dp = -u / ud, *ends = false;
    }
  }
  return dp;
}

void RouthImpact::Advance(const Rates& r, double dp) {
  vel_ += r.dvel * dp;
  for (int s = 0; s < 2; ++s) {
    out_.pn[s] += r.dn[s] * dp;
    out_.pt[s] += r.dt[s] * dp;
  }
  // Slip that just stopped sticks from now on (checked against mu_hat_s at the next solve).
  for (int s = 0; s < 2; ++s) {
    if (c_[s].active && c_[s].mode == Friction::kSlide &&
        std::abs(Slip(s)) <= zero_u_ + 1e-12 * std::abs(c_[s].jt.dot(r.dvel) * dp)) {
      c_[s].mode = Friction::kStick;
    }
  }
}

ImpactOutcome RouthImpact::Run() {
  bool first = true;
  for (; out_.segments < kMaxImpactSegments; ++out_.segments) {
    if (!SelectActive(first)) break;
    first = false;
    const Rates r = AdmissibleRates();
    bool ends = false;
    const double dp = r.ok ? NextEvent(r, &ends) : kInf;
    if (!std::isfinite(dp)) {
      out_.ok = false;
      break;
    }
    Advance(r, dp);
    if (ends) {
      ++out_.segments;
      break;
    }
  }
  if (out_.segments >= kMaxImpactSegments) out_.ok = false;
  out_.after = before_;
  out_.after.u = vel_(0);
  out_.after.v = vel_(1);
  out_.after.w = vel_(2);
  for (int s = 0; s < 2; ++s) {
    out_.took_part[s] = out_.pn[s] > 0;
    out_.stuck[s] = out_.took_part[s] && c_[s].mode == Friction::kStick;
    out_.reversed[s] = c_[s].reversed;
    out_.collapsed[s] = out_.collapsed[s] && out_.took_part[s];
  }
  return out_;
}

// Newton's law with every restitution target scaled by `lambda` (1: the plain law).
ImpactOutcome ResolveNewton(const Model& m, const State& before, std::array<bool, 2> touching,
                            std::array<bool, 2> forced, double lambda) {
  return RouthImpact(m, before, touching, forced, lambda).Run();
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
