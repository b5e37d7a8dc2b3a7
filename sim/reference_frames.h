#pragma once
// Lab <-> plate frame (model.h). Lab: x right, z up, z from the plate's mean surface.
// Plate frame: rotated by the tilt alpha and translated by the plate's displacement z_p(t)
// along its normal n = (-sin alpha, cos alpha); velocities are relative to the plate.
#include <Eigen/Core>

#include "sim/model.h"
#include "sim/state.h"

namespace dimer::sim {

State LabFromPlate(const Model& m, double t, const State& q);
// The same at the plate phase p = m.Phase(t), bit for bit: one sin/cos pair for several states
// at one time (an event's before and after).
State LabFromPlate(const Model& m, Model::PlatePhase p, const State& q);
State PlateFromLab(const Model& m, double t, const State& lab);
// Lab sphere centres (left, right) of a lab state.
Eigen::Vector2d TipLab(const Model& m, const State& lab, int sphere);
// Lab height of the plate surface below lab abscissa x.
double PlateSurfaceZ(const Model& m, double t, double x);

}  // namespace dimer::sim
