#pragma once
// The sim file (docs/FORMATS.md, kind = sim): the shared trajectory, /state, /events/*, every
// parameter as a root attribute, the settled mode and drift speed, and the run's diagnostics.
// Written atomically (common/atomic_output.h).
#include <string>

#include "common/h5_file.h"
#include "common/provenance.h"
#include "sim/model.h"
#include "sim/simulator.h"

namespace dimer::sim {

// Every option, under the names of the CLI flags (dashes become underscores).
AttrList SimParameters(const SimOptions& o);

// `storage` says how the chunks are compressed (threads, HDF5's pipeline or dimerlab's); the
// default is the one every dimerlab file uses, and the bytes do not depend on the threads.
void WriteSimFile(const std::string& path, bool force, const SimOptions& o, const SimResult& r,
                  const H5WriteOptions& storage = {});

}  // namespace dimer::sim
