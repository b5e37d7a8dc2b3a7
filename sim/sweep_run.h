#pragma once
// `dimerlab sweep` and `dimerlab merge` (docs/FORMATS.md): run the points of a spec (or of one
// shard of it) on a pool of threads, each point in-process, results placed by grid index so the
// file does not depend on the thread count or the finishing order; journal every finished point
// (sweep_journal.h) so an interrupted sweep resumes; write the sweep file atomically at the end.
#include <string>
#include <vector>

#include "sim/sweep_spec.h"

namespace dimer::sim {

struct SweepRunArgs {
  SweepSpec spec;
  Shard shard;            // 1/1: the whole grid
  std::string output;     // sweep.h5; the journal is output + ".journal"
  std::string tsv;        // also a tab-separated table (empty: none)
  bool force = false;     // replace an existing output
  int threads = 0;        // 0: every core
  bool progress = true;   // points/s and ETA on stderr
  bool verbose = false;   // one stderr line per finished point ("sweep: point I done")
};

struct SweepRunStats {
  long shard_points = 0;  // points this run is responsible for
  long recovered = 0;     // found finished in the journal (not recomputed)
  long computed = 0;      // simulated by this run
  long failed = 0;        // points whose run stopped early (their error column says why)
  long drift = 0;         // points that ended in drift mode
  double seconds = 0;     // wall time of the computing part
  double periods = 0;     // simulated periods (transient + measured) of the computed points
};

// Throws UsageError/InputError for a bad spec or output, Interrupted on Ctrl-C (the journal
// keeps every finished point). Returns what was done.
SweepRunStats RunSweep(const SweepRunArgs& args);

// The journal of `output`.
std::string JournalPath(const std::string& output);

struct MergeArgs {
  std::vector<std::string> inputs;  // shard files of one sweep
  std::string output;
  std::string tsv;
  bool force = false;
};
// Checks that the inputs hold the same spec and every grid point exactly once, and writes the
// file the unsharded sweep writes. InputError naming the file for any mismatch. Returns rows.
long RunMerge(const MergeArgs& args);

}  // namespace dimer::sim
