#include "sim/event_rows.h"

#include "sim/reference_frames.h"

namespace dimer::sim {

void EventRows(const Model& m, const EventRecord& e, double* t, double* before, double* after) {
  *t = e.t;
  const Model::PlatePhase p = m.Phase(e.t_local);  // before and after share the instant
  LabStateRow(LabFromPlate(m, p, e.before), before);
  LabStateRow(LabFromPlate(m, p, e.after), after);
}

EventLogRows EventLogFills(const Model& m, const std::vector<EventRecord>* log) {
  auto column = [&m, log](int which) -> RowFill {
    return [&m, log, which](size_t first, size_t rows, double* out) {
      double row[1 + 2 * kLabStateColumns];
      const size_t width = which == 0 ? 1 : kLabStateColumns;
      const size_t at = which == 0 ? 0 : which == 1 ? 1 : 1 + kLabStateColumns;
      for (size_t i = first; i < first + rows; ++i, out += width) {
        EventRows(m, (*log)[i], row, row + 1, row + 1 + kLabStateColumns);
        for (size_t c = 0; c < width; ++c) out[c] = row[at + c];
      }
    };
  };
  return {column(0), column(1), column(2)};
}

EventRowsAhead::EventRowsAhead(ChunksAhead* ahead, const Model& m) : ahead_(ahead), m_(m) {
  ahead->AddAppendedRows("/events/t", 1);
  ahead->AddAppendedRows("/events/before", kLabStateColumns);
  ahead->AddAppendedRows("/events/after", kLabStateColumns);
}

void EventRowsAhead::See(const EventRecord& e) {
  double row[1 + 2 * kLabStateColumns];
  EventRows(m_, e, row, row + 1, row + 1 + kLabStateColumns);
  t_.push_back(row[0]);
  before_.insert(before_.end(), row + 1, row + 1 + kLabStateColumns);
  after_.insert(after_.end(), row + 1 + kLabStateColumns, row + 1 + 2 * kLabStateColumns);
}

void EventRowsAhead::Flush() {
  if (t_.empty()) return;
  ahead_->AppendRows("/events/t", t_.data(), t_.size());
  ahead_->AppendRows("/events/before", before_.data(), t_.size());
  ahead_->AppendRows("/events/after", after_.data(), t_.size());
  t_.clear();
  before_.clear();
  after_.clear();
}

}  // namespace dimer::sim
