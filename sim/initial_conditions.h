#pragma once
// Initial conditions (--init, --init-state), in the plate frame, with their start time.
//  - drift (the paper's release): the left sphere on the plate, the right end lifted by
//    lift * d, released at rest (lab) at plate phase release_phase (default 0.25: the plate is
//    momentarily still at its top, so "at rest" is the same in both frames).
//  - jump: a flat dimer leaving the plate on the bouncing-ball period-1 orbit (docs/MODEL.md check
//    1): impact at the phase where the plate velocity is V_p = gT(1-eps)/(2(1+eps)) with the
//    plate decelerating, take-off velocity gT/2 (lab). Needs Gamma >= pi(1-eps)/(1+eps).
//  - flutter: the left tip leaving the plate at the jump orbit's phase with tip velocities
//    chosen for flights of two periods (left) and about half a period (right), so the tips
//    alternate; whether it settles into flutter is reported, not assumed.
//  - rest: flat on the plate, at rest.
//  - init_state: the lab state (x, z, theta, u, v, omega) at t = 0.
#include <string>

#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim {

struct InitialCondition {
  double t0 = 0;  // s; plate phase at t0 is (omega_p t0 + phi0)
  State q;        // plate frame
};

// Throws InputError when the request cannot be met (e.g. jump below its Gamma threshold).
InitialCondition MakeInitialCondition(const Model& m, const SimOptions& o);

// Phase (rad, in [0, 2 pi)) of the period-1 bouncing-ball impact, or NaN if it does not exist.
double PeriodOneImpactPhase(const Model& m);

// When a run started by --init KIND (not --init-state) settled in another mode: one sentence
// naming the mode reached and the likely reason (docs/MODEL.md, "Modes and the drift speed",
// and the paper's ranges); "" when it reached the mode asked for. `periods` is the number of
// complete periods simulated.
std::string ModeNote(const SimOptions& o, const std::string& settled_mode, long periods);

}  // namespace dimer::sim
