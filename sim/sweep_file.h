#pragma once
// Sweep files (kind = sweep; docs/FORMATS.md, "Sweep files"): one row per grid point, in grid
// order, parallel 1-D datasets under /points/ (every swept parameter's value at the row) and
// /results/ (PointResult), the canonical spec as the root attribute `spec`. A shard's file holds
// its own rows; `dimerlab merge` joins shards into the file the unsharded run writes, byte for
// byte (with the same SOURCE_DATE_EPOCH): the file is a function of (spec, rows) alone.
#include <string>
#include <vector>

#include "sim/sweep_point.h"
#include "sim/sweep_spec.h"

namespace dimer::sim {

struct SweepFileContent {
  std::string spec;                // canonical spec text
  Shard shard;                     // 1/1 for a whole sweep
  long point_count = 0;            // points of the whole grid
  std::vector<PointResult> rows;   // ascending index
};

// Writes atomically (AtomicOutput; an existing file only with `force`). `rows` ascending by
// index. The parameter columns are recomputed from `spec`.
void WriteSweepFile(const std::string& path, bool force, const SweepSpec& spec,
                    const Shard& shard, const std::vector<PointResult>& rows);
// InputError naming the file when it is not a readable sweep file.
SweepFileContent ReadSweepFile(const std::string& path);

// Tab-separated text of the same rows for gnuplot and spreadsheets: a `#` line with the spec's
// identity, a `#` header naming each column with its unit, then one line per row.
void WriteSweepTsv(const std::string& path, bool force, const SweepSpec& spec,
                   const std::vector<PointResult>& rows);

}  // namespace dimer::sim
