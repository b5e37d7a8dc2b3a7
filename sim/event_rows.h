#pragma once
// The sim file's numeric event datasets (/events/t, /events/before, /events/after: the time and
// the lab-frame states around each event), row by row: WriteSimFile makes them from the log,
// and RunSim hands them to the compressing threads as the run logs them
// (common/h5_chunks_ahead.h). One definition for both, so both give the same bytes
// (SimFile.RunSimGivesHdf5sBytes).
#include <vector>

#include "common/h5_chunks_ahead.h"
#include "sim/events.h"
#include "sim/model.h"
#include "sim/sample_rows.h"

namespace dimer::sim {

// Event e's rows: t (1 value), before and after (kLabStateColumns values each).
void EventRows(const Model& m, const EventRecord& e, double* t, double* before, double* after);

// The three datasets' rows from a finished log.
struct EventLogRows {
  RowFill t, before, after;
};
EventLogRows EventLogFills(const Model& m, const std::vector<EventRecord>* log);

// The three datasets for `ahead`, fed as the run goes: See every logged event
// (RunControls::on_event), Flush once a period (the rows go to `ahead` in one lock).
class EventRowsAhead {
 public:
  EventRowsAhead(ChunksAhead* ahead, const Model& m);
  void See(const EventRecord& e);
  void Flush();

 private:
  ChunksAhead* ahead_;
  const Model& m_;
  std::vector<double> t_, before_, after_;
};

}  // namespace dimer::sim
