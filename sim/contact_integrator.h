#pragma once
// Integration of persistent contact between events: adaptive Dormand-Prince RK5(4) on the full
// state with the contact forces of persistent_contact.h (mode fixed), projection back onto the
// contact constraints after each accepted step, and event location by Illinois iteration on a
// single RK step from the start of the step. Events:
//   - a resting sphere's normal force reaches 0 (lift-off);
//   - a sliding contact's slip reaches 0 (stick or reversal, decided by the caller);
//   - a sticking contact reaches the static cone |F_T| = mu_s N (slip starts);
//   - the other sphere's gap reaches 0 (impact while one sphere rests). Grazing inside a step is
//     caught by the minimum of the cubic Hermite interpolant of (h, h') at the step ends.
// The tolerance `contact_tol` is relative to R, g/f and their ratio; its effect on drift speed
// is measured in bench/bench_sim_accuracy.
#include "sim/model.h"
#include "sim/persistent_contact.h"
#include "sim/state.h"

namespace dimer::sim {

// kPenetration: a sphere not resting is found below -gap_tol at a step's end without having
// crossed it inside the step (it started the phase below it): the run stops there, since every
// impact after it would be missed; the simulator reports it as its own error.
enum class ContactEvent { kEnd, kImpact, kLiftoff, kSlipStops, kSlipStarts, kPenetration };

// Receives output samples: Next() is the next wanted sample time (+inf when none).
class SampleSink {
 public:
  virtual ~SampleSink() = default;
  virtual double Next() const = 0;
  virtual void Record(double t, const State& q) = 0;
};

struct ContactRun {
  double t = 0;
  State q;
  ContactEvent event = ContactEvent::kEnd;
  int sphere = -1;  // which sphere the event concerns
  long steps = 0, rejected = 0;
  bool ok = true;   // false: step size underflow
};

// Integrates from (t0, q0) in configuration cfg until the first event or t_end, recording every
// sample time in (t0, t_event]. `h` carries the step size between calls.
ContactRun IntegrateContact(const Model& m, const ContactConfig& cfg, double t0, const State& q0,
                            double t_end, double* h, SampleSink* sink);

}  // namespace dimer::sim
