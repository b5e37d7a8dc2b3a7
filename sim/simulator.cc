#include "sim/simulator.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/check.h"
#include "common/error.h"
#include "sim/constants.h"
#include "sim/contact_integrator.h"
#include "sim/flight.h"
#include "sim/reference_frames.h"
#include "sim/impact_law.h"
#include "sim/initial_conditions.h"
#include "sim/persistent_contact.h"
#include "sim/resting.h"

namespace dimer::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// An impact counts toward the mode statistics when it approaches faster than
// kSignificantImpactRel g/f (common/modes.h, shared with compare).

struct EventStorm : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The deepest penetration of a sphere that is not resting, at every state the run evaluates
// and keeps (samples, step ends, events). Past gap_tol (and round-off) an impact was missed:
// the first such state is kept for the error message, and the run stops there.
struct PenetrationWatch {
  double limit_m = 0;
  double* max_depth_m = nullptr;  // SimDiagnostics::max_penetration_m
  bool fault = false;  // the first state past the limit:
  double t = 0, depth_m = 0;
  int sphere = -1;
  State q;
  void See(const Model& m, double t_abs, const State& qs, std::array<bool, 2> resting) {
    for (int s = 0; s < 2; ++s) {
      if (resting[s]) continue;
      const double depth = -Gap(m, qs, s);
      *max_depth_m = std::max(*max_depth_m, depth);
      if (depth > limit_m && !fault) {
        fault = true;
        t = t_abs;
        depth_m = depth;
        sphere = s;
        q = qs;
      }
    }
  }
  std::string Message() const {
    std::ostringstream msg;
    msg.precision(17);
    msg << "simulator error: the " << (sphere == kLeft ? "left" : "right")
        << " sphere passed through the plate (" << depth_m << " m deep, tolerance " << limit_m
        << " m) at t = " << t << " s; plate-frame state x,z,theta,u,v,omega = " << q.x << ","
        << q.z << "," << q.th << "," << q.u << "," << q.v << "," << q.w;
    return msg.str();
  }
};

// Output samples k = 0 .. n-1 at exactly t_start + k / fps (absolute times, never accumulated;
// n = SimOptions::SampleCount(), defined once). The runner works in a local time that is
// re-based every period (see Runner), so Next() and Record() speak local time and `offset`
// converts.
class Sampler : public SampleSink {
 public:
  Sampler(const Model& m, double t0, long n, double fps, const double* offset, SimResult* res)
      : m_(&m), t0_(t0), fps_(fps), n_(n), offset_(offset), res_(res) {
    next_ = n > 0 ? t0 : kInf;
    // Every sample's place from the start: no copy as they grow, and fixed addresses for
    // RunControls::on_samples (the memory is the run's estimate, checked before it starts).
    res->t.reserve(static_cast<size_t>(n));
    res->lab.reserve(static_cast<size_t>(n));
  }
  double Next() const override { return next_ - *offset_; }
  void Record(double t_local, const State& q) override {
    if (watch_) watch_->See(*m_, next_, q, {false, false});  // resting spheres are at 0 exactly
    res_->t.push_back(next_);
    res_->lab.push_back(LabFromPlate(*m_, t_local, q));
    ++k_;
    next_ = k_ < n_ ? t0_ + k_ / fps_ : kInf;
  }
  long pending() const { return n_ - k_; }
  void Watch(PenetrationWatch* w) { watch_ = w; }

 private:
  const Model* m_;
  double t0_, fps_;
  long n_;
  const double* offset_;
  SimResult* res_;
  PenetrationWatch* watch_ = nullptr;
  long k_ = 0;
  double next_;
};

class Runner {
 public:
  Runner(const SimOptions& o, const RunControls& c)
      : o_(o), c_(c), m_(Model::FromOptions(o)), sampler_(m_, 0, 0, 0, &offset_, &res_) {}
  SimResult Run();

 private:
  void Settle(std::array<bool, 2> candidates, int force_slide_sphere = -1);
  std::array<bool, 2> RestingAmong(std::array<bool, 2> touching) const;
  void FlightStage(double t_lim);
  void ContactStage(double t_lim);
  void DoImpact(std::array<bool, 2> touching);
  void Log(EventKind kind, int sphere, const State& before, std::string detail = "");
  void StartPeriod();
  void FinishSamples();
  void TrackPenetration(const State& q, const ContactConfig& cfg);
  PenetrationWatch watch_;

  const SimOptions& o_;
  const RunControls& c_;
  Model m_;
  SimResult res_;
  Sampler sampler_;
  // Time: the plate's phase only needs t modulo T, and sin(omega t) loses digits as t grows
  // (at 10^6 periods, 1e-12 s of round-off is 1e-13 m of plate position). So the stages run on
  // a local time t_ that goes back by one period at every period boundary; absolute time is
  // offset_ + t_ (offset_ = k T), used only for output.
  double t_ = 0;
  double offset_ = 0;
  State q_;
  ContactConfig cfg_;
  double h_ = 0;  // contact step size carried between phases
  double period_end_ = 0;
  PeriodStats cur_;
};

void Runner::Log(EventKind kind, int sphere, const State& before, std::string detail) {
  ++res_.diag.events;
  ++cur_.events;
  if (cur_.events > o_.max_events_per_period) {
    std::ostringstream s;
    s << "event storm: more than " << o_.max_events_per_period << " events in the period at t = "
      << offset_ + t_ << " s (last: " << ToString(kind) << "); see --max-events-per-period";
    throw EventStorm(s.str());
  }
  if (!c_.keep_events && !c_.on_event) return;
  EventRecord e{offset_ + t_, t_, kind, static_cast<int8_t>(sphere), std::move(detail), before,
                q_};
  if (c_.on_event) c_.on_event(e);
  if (c_.keep_events) res_.events.push_back(std::move(e));
}

std::array<bool, 2> Runner::RestingAmong(std::array<bool, 2> touching) const {
  std::array<bool, 2> out{};
  for (int s = 0; s < 2; ++s) {
    // Inelastic collapse, second half: a touching sphere that leaves slower than v_c (typically
    // lifted by the other sphere's impact) stays in persistent contact, so that two spheres
    // near the plate cannot pass ever smaller bounces back and forth without end.
    out[s] = touching[s] && std::abs(NormalV(ContactArm(m_, q_.th, s), q_)) < m_.v_collapse;
  }
  return out;
}

void Runner::Settle(std::array<bool, 2> candidates, int force_slide_sphere) {
  for (int iter = 0; iter < 4; ++iter) {
    // Normal constraints first (gaps and V of the candidates): the mass-metric projection also
    // moves U, and the stick/slide choice must see the slip that the contact will actually have.
    ContactConfig normal_only;
    normal_only.resting = candidates;
    normal_only.slide = {1, 1};
    ProjectOnContacts(m_, normal_only, &q_);
    ModeChoice mc = ChooseContactMode(m_, t_, q_, candidates);
    if (mc.painleve_sphere < 0) {
      const int s = force_slide_sphere;
      if (s >= 0 && mc.cfg.resting[s] && mc.cfg.slide[s] == 0) {
        // At the static cone's edge the stick test is decided by round-off: slide, as found.
        mc.cfg.slide[s] = mc.forces.f[s] > 0 ? -1 : 1;
      }
      cfg_ = mc.cfg;
      ProjectOnContacts(m_, cfg_, &q_);
      LayFlatOnTouchingSphere(m_, cfg_, &q_);
      return;
    }
    // Painleve: impact without collision at the sliding contact (impact_law.h).
    const State before = q_;
    std::array<bool, 2> forced{};
    forced[mc.painleve_sphere] = true;
    const ImpactOutcome io = ResolveImpact(m_, q_, candidates, forced);
    q_ = io.after;
    ++res_.diag.painleve;
    Log(EventKind::kPainleve, mc.painleve_sphere, before);
    candidates = RestingAmong(candidates);
  }
  cfg_ = ContactConfig{};
}

void Runner::TrackPenetration(const State& q, const ContactConfig& cfg) {
  watch_.See(m_, offset_ + t_, q, cfg.resting);
}

void Runner::FlightStage(double t_lim) {
  double dt_max = t_lim - t_;
  int hitter = -1;
  for (int s = 0; s < 2; ++s) {
    const ImpactSearch is = FindFlightImpact(m_, q_, t_, dt_max, s);
    res_.diag.flight_steps += is.steps;
    res_.diag.capped_searches += is.capped;
    if (is.found && is.dt <= dt_max) {
      hitter = s;
      dt_max = is.dt;
    }
  }
  const FlightPath path(m_, q_, t_);
  while (sampler_.Next() <= t_ + dt_max) {
    const double ts = sampler_.Next();
    sampler_.Record(ts, path.At(ts - t_));
  }
  q_ = path.At(dt_max);
  t_ = hitter >= 0 ? t_ + dt_max : t_lim;
  TrackPenetration(q_, cfg_);
  if (hitter < 0) return;
  std::array<bool, 2> touching{};
  for (int s = 0; s < 2; ++s) touching[s] = s == hitter || Gap(m_, q_, s) < kTouchTol_m;
  DoImpact(touching);
}

namespace {
std::string ImpactDetail(const ImpactOutcome& io) {
  std::string d;
  for (int s = 0; s < 2; ++s) {
    if (!io.took_part[s]) continue;
    if (!d.empty()) d += ' ';
    d += s == kLeft ? "L:" : "R:";
    d += io.reversed[s] ? "slip_reversal" : io.stuck[s] ? "slip_stick" : "continuous_slide";
  }
  return d;
}
}  // namespace

void Runner::DoImpact(std::array<bool, 2> touching) {
  const State before = q_;
  const ImpactOutcome io = ResolveImpact(m_, q_, touching);
  res_.diag.impact_segments += io.segments;
  res_.diag.impact_failures += !io.ok;
  if (io.energy_gain > 0) {
    ++res_.diag.energy_capped;
    const double e0 = 0.5 * (before.u * before.u + before.v * before.v +
                             before.w * before.w / m_.inv_I);
    res_.diag.max_newton_gain = std::max(res_.diag.max_newton_gain, io.energy_gain / e0);
  }
  q_ = io.after;
  const int took = int(io.took_part[0]) + int(io.took_part[1]);
  for (int s = 0; s < 2; ++s) {
    if (io.took_part[s] && !io.collapsed[s] &&
        -io.v_before[s] > kSignificantImpactRel * m_.vel_scale) {
      ++cur_.impacts[s];
    }
  }
  // The detail string only for an event log kept or seen (benchmarks count only).
  const std::string detail =
      c_.keep_events || c_.on_event ? ImpactDetail(io) : std::string();
  if (took == 2) {
    Log(EventKind::kDoubleImpact, 2, before, detail);
  } else if (took == 1) {
    const int s = io.took_part[0] ? 0 : 1;
    Log(io.collapsed[s] ? EventKind::kCollapse : EventKind::kImpact, s, before, detail);
  }
  Settle(RestingAmong(touching));
}

void Runner::ContactStage(double t_lim) {
  if (c_.skip_rest && StaysPut(m_, cfg_, q_)) {
    // The rest state that provably stays put over the whole cycle (resting.h): q_ does not
    // change, so the stage ends at t_lim at once; the step-by-step path records the same.
    while (sampler_.Next() <= t_lim) sampler_.Record(sampler_.Next(), q_);
    for (int s = 0; s < 2; ++s) cur_.rest_time[s] += t_lim - t_;
    t_ = t_lim;
    ++res_.diag.rest_stages;
    return;
  }
  const ContactRun run = IntegrateContact(m_, cfg_, t_, q_, t_lim, &h_, &sampler_);
  res_.diag.contact_steps += run.steps;
  res_.diag.contact_rejected += run.rejected;
  res_.diag.step_underflows += !run.ok;
  for (int s = 0; s < 2; ++s) {
    if (cfg_.resting[s]) cur_.rest_time[s] += run.t - t_;
  }
  t_ = run.t;
  q_ = run.q;
  TrackPenetration(q_, cfg_);
  const int s = run.sphere;
  const State before = q_;
  switch (run.event) {
    case ContactEvent::kEnd:
      ProjectOnContacts(m_, cfg_, &q_);
      return;
    case ContactEvent::kImpact: {
      std::array<bool, 2> touching = cfg_.resting;
      touching[s] = true;
      DoImpact(touching);
      return;
    }
    case ContactEvent::kLiftoff: {
      std::array<bool, 2> cand = cfg_.resting;
      cand[s] = false;
      Settle(cand);
      Log(EventKind::kLiftoff, s, before);
      return;
    }
    case ContactEvent::kSlipStops: {
      q_.u = q_.w * ContactArm(m_, q_.th, s).rz;  // U_s = 0 exactly
      Settle(cfg_.resting);
      Log(cfg_.resting[s] && cfg_.slide[s] == 0 ? EventKind::kStick : EventKind::kSlip, s,
          before, cfg_.resting[s] && cfg_.slide[s] != 0 ? "reversal" : "");
      return;
    }
    case ContactEvent::kSlipStarts:
      Settle(cfg_.resting, s);
      Log(EventKind::kSlip, s, before);
      return;
    case ContactEvent::kPenetration:  // TrackPenetration above has seen it: the run stops
      return;
  }
}

void Runner::StartPeriod() {
  cur_ = PeriodStats{};
  // Along the plate (the plate frame's x), as the paper measures a drift and as compare reads a
  // track of a tilted plate; the lab's x on a level plate, to the bit (cos 0 = 1, sin 0 = 0).
  cur_.x_start = q_.x;
  period_end_ = res_.t_start + m_.period;  // local time: every period starts at t_start
}

// After the loop. A complete run may still owe its last sample: t_start + (n-1)/fps can exceed
// the end time reached by an ulp, which the stages never step past; it is the end state. A run
// that stopped early ends where it stopped: t_end is the last time reached, not the one asked.
void Runner::FinishSamples() {
  const double t_reached = offset_ + t_;
  if (res_.interrupted || !res_.error.empty()) {
    res_.t_end = t_reached;
    return;
  }
  const double rounding = 1e-9 * m_.period;
  while (sampler_.pending() > 0 && sampler_.Next() + offset_ <= t_reached + rounding) {
    sampler_.Record(t_, q_);
  }
}

SimResult Runner::Run() {
  const InitialCondition ic = MakeInitialCondition(m_, o_);
  res_.model = m_;
  t_ = ic.t0;
  q_ = ic.q;
  res_.t_start = t_;
  res_.t_end = t_ + o_.Duration();
  sampler_ = Sampler(m_, t_, o_.SampleCount(), o_.fps, &offset_, &res_);
  watch_.limit_m = m_.gap_tol + kPositionRoundoffRel * m_.R;
  watch_.max_depth_m = &res_.diag.max_penetration_m;
  sampler_.Watch(&watch_);
  h_ = 1e-3 * m_.period;
  StartPeriod();
  std::array<bool, 2> touching{};
  for (int s = 0; s < 2; ++s) touching[s] = Gap(m_, q_, s) < kTouchTol_m;
  Settle(RestingAmong(touching));
  const double total = o_.Duration() / m_.period;
  // Whole periods, then what remains of the duration (a count, so that rounding of k T can
  // neither add nor drop a period).
  const long whole = static_cast<long>(std::floor(total + 1e-9));
  const double remainder = std::max(0.0, o_.Duration() - whole * m_.period);
  auto running = [&] {
    const long done = static_cast<long>(res_.periods.size());
    return done < whole || (remainder > 1e-12 * m_.period && t_ < res_.t_start + remainder);
  };
  long stages_in_period = 0;
  while (running()) {
    const long done = static_cast<long>(res_.periods.size());
    const double t_lim = done < whole ? period_end_ : res_.t_start + remainder;
    if (++stages_in_period > 10 * o_.max_events_per_period + 1000) {
      // Stages that log no event (an impact that transfers nothing, a zero-length contact
      // phase) must still end: treat a period that never finishes like an event storm.
      std::ostringstream msg;
      msg << "no progress: " << stages_in_period << " stages in the period at t = "
          << offset_ + t_ << " s (resting " << cfg_.resting[0] << cfg_.resting[1] << ", z "
          << q_.z << ", theta " << q_.th << ", v " << q_.v << ", w " << q_.w << ")";
      res_.error = msg.str();
      break;
    }
    try {
      if (cfg_.Count() == 0) {
        FlightStage(t_lim);
      } else {
        ContactStage(t_lim);
      }
    } catch (const EventStorm& e) {
      res_.error = e.what();  // the run stops; what it computed so far is kept
      break;
    }
    if (watch_.fault) {  // a missed impact: every state after it would be wrong
      res_.error = watch_.Message();
      break;
    }
    if (t_ >= period_end_) {
      stages_in_period = 0;
      res_.periods.push_back(cur_);
      res_.diag.max_events_in_period = std::max(res_.diag.max_events_in_period, cur_.events);
      // Re-base: the same plate phase, one period earlier in local time.
      const long k = static_cast<long>(res_.periods.size());
      offset_ = k * m_.period;
      t_ = res_.t_start;
      StartPeriod();
      if (c_.on_samples) c_.on_samples(res_.t.data(), res_.lab.data(), res_.t.size());
      if (c_.progress) c_.progress(static_cast<double>(k), total);
      if (c_.should_stop && c_.should_stop()) {
        res_.interrupted = true;
        break;
      }
    }
  }
  // Mode over the project's settled window (common/modes.h).
  const State lab = LabFromPlate(m_, t_, q_);
  FinishSamples();  // the last sample and t_end (t_, q_ unchanged)
  std::array<int, 2> dir{};
  for (int s = 0; s < 2; ++s) {
    const double dx = TipLab(m_, lab, s).x() - TipLab(m_, lab, 1 - s).x();
    dir[s] = dx >= 0 ? 1 : -1;
  }
  const int n = static_cast<int>(res_.periods.size());
  const int w = SettledWindow(n);
  res_.mode = ClassifyPeriods(res_.periods, n - w, w, m_.period, q_.x, dir);
  return std::move(res_);
}

}  // namespace

SimResult RunSimulation(const SimOptions& options, const RunControls& controls) {
  const std::vector<std::string> errors = options.Check();
  if (!errors.empty()) {
    std::string msg = "invalid simulation parameters: ";
    for (size_t i = 0; i < errors.size(); ++i) msg += (i ? "; " : "") + errors[i];
    throw UsageError(msg);
  }
  DIMER_CHECK(options.diameter_m > 0 && std::isfinite(options.diameter_m) && options.ar > 1,
              "a simulation needs a dimer of positive size (SimOptions::Check passed it)");
  Runner runner(options, controls);
  return runner.Run();
}

}  // namespace dimer::sim
