#pragma once
// `dimerlab sim`: run one simulation and write its sim file; the CLI only parses into SimRunArgs.
#include <string>

#include "sim/model.h"

namespace dimer::sim {

struct SimRunArgs {
  SimOptions options;
  std::string output;     // sim.h5 path
  bool force = false;     // replace an existing output
  bool progress = true;   // periods/s and ETA on stderr
  int threads = 0;        // threads that compress the file (0: every core); same bytes for any
};

// Returns the process exit code (0 ok, 130 interrupted with a valid partial file). Throws
// InputError on bad input. Prints a one-paragraph summary on stdout.
int RunSim(const SimRunArgs& args);

// "x,z,theta,u,v,omega" -> six numbers; InputError naming --init-state otherwise.
std::array<double, 6> ParseInitState(const std::string& text);

}  // namespace dimer::sim
