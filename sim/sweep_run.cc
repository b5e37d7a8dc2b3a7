#include "sim/sweep_run.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <map>
#include <mutex>
#include <thread>

#include "common/atomic_output.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/memory_limit.h"
#include "common/progress.h"
#include "sim/sweep_file.h"
#include "sim/sweep_journal.h"
#include "sim/sweep_point.h"
#include "sim/sweep_point_check.h"

namespace dimer::sim {

std::string JournalPath(const std::string& output) { return output + ".journal"; }

namespace {

// What a journal must match: the canonical spec and the shard.
std::string Identity(const SweepSpec& spec, const Shard& shard) {
  return spec.Canonical() + "shard = " + shard.ToString() + "\n";
}

int ThreadCount(int asked) {
  if (asked > 0) return asked;
  const unsigned hw = std::thread::hardware_concurrency();
  return hw > 0 ? static_cast<int>(hw) : 1;
}

}  // namespace

SweepRunStats RunSweep(const SweepRunArgs& args) {
  if (args.output.empty()) throw UsageError("sweep: -o/--output is required");
  if (args.threads < 0) {
    throw UsageError("--threads: " + std::to_string(args.threads) + ": expected >= 0 (0: all)");
  }
  args.spec.Check();
  // Every point runs transient + periods periods (one sample per period, no event log kept:
  // sweep_point.cc): the same estimate for each, held by each worker thread at once.
  const double per_point = args.spec.PointOptionsNoInit(0).EstimatedMemoryBytes(false);
  CheckRunMemory(ThreadCount(args.threads) * per_point,
                 "use fewer --transient/--periods or --threads");
  CheckCanWrite(args.output, args.force);
  if (!args.tsv.empty()) CheckCanWrite(args.tsv, args.force);

  const size_t total = args.spec.PointCount();
  std::vector<size_t> mine;
  for (size_t i = 0; i < total; ++i) {
    if (args.shard.Contains(i)) mine.push_back(i);
  }
  SweepJournal journal(JournalPath(args.output), Identity(args.spec, args.shard));
  std::map<int64_t, PointResult> done;
  for (const PointResult& p : journal.recovered()) {
    if (args.shard.Contains(static_cast<size_t>(p.index)) &&
        p.index < static_cast<int64_t>(total)) {
      // A record whose checksum holds is still checked as a result (sweep_point_check.h).
      const std::string problem = PointResultProblem(p, args.spec);
      if (problem.empty()) {
        done.emplace(p.index, p);
      } else {
        std::fprintf(stderr, "dimerlab: warning: %s: point %lld: %s; it is computed again\n",
                     JournalPath(args.output).c_str(), static_cast<long long>(p.index),
                     problem.c_str());
      }
    }
  }
  SweepRunStats stats;
  stats.shard_points = static_cast<long>(mine.size());
  stats.recovered = static_cast<long>(done.size());
  if (args.progress && (stats.recovered > 0 || journal.discarded_bytes() > 0)) {
    std::fprintf(stderr, "sweep: resuming from %s: %ld of %ld points already done",
                 JournalPath(args.output).c_str(), stats.recovered, stats.shard_points);
    if (journal.discarded_bytes() > 0) {
      std::fprintf(stderr, " (a torn last record of %ld bytes discarded)",
                   journal.discarded_bytes());
    }
    std::fprintf(stderr, "\n");
  }
  std::vector<size_t> todo;
  for (size_t i : mine) {
    if (!done.count(static_cast<int64_t>(i))) todo.push_back(i);
  }

  // The pool: workers take the next index, run it, and hand the result to the journal under
  // the lock; results are keyed by index, so the order of finishing does not matter.
  ProgressMeter meter("sweep", "points", static_cast<double>(todo.size()), args.progress);
  std::mutex mu;
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  const auto start = std::chrono::steady_clock::now();
  auto worker = [&] {
    for (;;) {
      if (stop || InterruptRequested()) return;
      const size_t k = next++;
      if (k >= todo.size()) return;
      const size_t i = todo[k];
      PointResult p;
      try {
        try {
          p = RunSweepPoint(args.spec, i, [&] { return stop.load() || InterruptRequested(); });
        } catch (const InputError& e) {
          // A start the simulator refuses at this point (e.g. --init jump below its Gamma
          // threshold) is this point's result, not the sweep's failure.
          p = PointResult{};
          p.index = static_cast<int64_t>(i);
          p.error = e.what();
        }
        if (p.index < 0) return;  // interrupted mid-point: not recorded
        std::lock_guard<std::mutex> lock(mu);
        journal.Append(p);
        ++stats.computed;
        stats.periods += static_cast<double>(args.spec.transient + args.spec.periods);
        meter.Update(static_cast<double>(stats.computed));
        if (args.verbose) {
          std::fprintf(stderr, "sweep: point %zu done\n", i);
          std::fflush(stderr);
        }
        done.emplace(p.index, std::move(p));
      } catch (...) {
        std::lock_guard<std::mutex> lock(mu);
        if (!failure) failure = std::current_exception();
        stop = true;
        return;
      }
    }
  };
  const int n_threads = std::max(1, std::min(ThreadCount(args.threads),
                                             static_cast<int>(todo.size())));
  if (!todo.empty()) {
    std::vector<std::thread> pool;
    for (int t = 1; t < n_threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  meter.Finish(static_cast<double>(stats.computed));
  if (failure) std::rethrow_exception(failure);
  if (done.size() < mine.size()) {
    if (args.progress) {
      std::fprintf(stderr, "sweep: %zu of %zu points saved in %s; rerun the same command to "
                   "resume\n", done.size(), mine.size(), JournalPath(args.output).c_str());
    }
    throw Interrupted();
  }
  std::vector<PointResult> rows;
  rows.reserve(done.size());
  for (auto& [index, p] : done) {
    if (!p.error.empty()) ++stats.failed;
    if (p.mode == "drift") ++stats.drift;
    rows.push_back(std::move(p));
  }
  WriteSweepFile(args.output, args.force, args.spec, args.shard, rows);
  if (!args.tsv.empty()) WriteSweepTsv(args.tsv, args.force, args.spec, rows);
  journal.Remove();
  return stats;
}

long RunMerge(const MergeArgs& args) {
  if (args.output.empty()) throw UsageError("merge: -o/--output is required");
  if (args.inputs.empty()) throw UsageError("merge: no input files");
  CheckCanWrite(args.output, args.force);
  if (!args.tsv.empty()) CheckCanWrite(args.tsv, args.force);
  std::string spec_text;
  long count = 0;
  std::map<int64_t, std::pair<PointResult, std::string>> rows;  // index -> row, its file
  for (const std::string& path : args.inputs) {
    SweepFileContent c = ReadSweepFile(path);
    if (spec_text.empty()) {
      spec_text = c.spec;
      count = c.point_count;
    } else if (c.spec != spec_text) {
      throw InputError(path + ": a different sweep spec from " + args.inputs[0] +
                       " (shards of one sweep must be run with the same options)");
    }
    for (PointResult& p : c.rows) {
      if (p.index < 0 || p.index >= count) {
        throw InputError(path + ": point index " + std::to_string(p.index) + " outside the grid");
      }
      auto [it, fresh] = rows.emplace(p.index, std::make_pair(p, path));
      if (!fresh) {
        throw InputError(path + ": point " + std::to_string(p.index) + " is also in " +
                         it->second.second + " (a shard given twice?)");
      }
    }
  }
  if (static_cast<long>(rows.size()) != count) {
    std::string missing;
    int shown = 0;
    for (long i = 0; i < count && shown < 5; ++i) {
      if (!rows.count(i)) {
        missing += (shown ? ", " : "") + std::to_string(i);
        ++shown;
      }
    }
    throw InputError("merge: " + std::to_string(count - static_cast<long>(rows.size())) + " of " +
                     std::to_string(count) + " points missing (first: " + missing +
                     "); is a shard file missing?");
  }
  const SweepSpec spec = ParseSweepSpec(spec_text, args.inputs[0] + " (spec attribute)");
  if (spec.Canonical() != spec_text) {
    throw InputError(args.inputs[0] + ": the spec attribute does not read back to itself");
  }
  std::vector<PointResult> all;
  for (auto& [i, row] : rows) all.push_back(std::move(row.first));
  WriteSweepFile(args.output, args.force, spec, Shard{}, all);
  if (!args.tsv.empty()) WriteSweepTsv(args.tsv, args.force, spec, all);
  return static_cast<long>(all.size());
}

}  // namespace dimer::sim
