#pragma once
// The sim file (docs/FORMATS.md, kind = sim): the shared trajectory, /state, /events/*, every
// parameter as a root attribute, the settled mode and drift speed, and the run's diagnostics.
// Written atomically (common/atomic_output.h).
#include <string>

#include "common/provenance.h"
#include "sim/model.h"
#include "sim/simulator.h"

namespace dimer::sim {

// Every option, under the names of the CLI flags (dashes become underscores).
AttrList SimParameters(const SimOptions& o);

void WriteSimFile(const std::string& path, bool force, const SimOptions& o, const SimResult& r);

}  // namespace dimer::sim
