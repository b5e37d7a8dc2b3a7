#pragma once
// What the tracker has to say about a film besides the track, as data: notes (what it chose and
// why, what it measured) and warnings (what may be off, and what would help). The library never
// prints them: each goes to the caller's sink as it is made, so that on a terminal they keep
// their order with the progress of a long run, and all stay in `entries()` for the caller (a
// test reads them there). app/ prints each as one line on stderr (FormatDiagnostic).
#include <functional>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace dimer::tracking {

enum class Severity {
  kNote,          // "dimerlab track: [TOPIC: ]MESSAGE"
  kWarning,       // "dimerlab track: [TOPIC: ]warning: MESSAGE"
  // About the input itself (a frame, a header, a codec), its message starting with the file:
  // "dimerlab track: warning: MESSAGE".
  kInputWarning,
};

struct Diagnostic {
  Severity severity = Severity::kNote;
  std::string code;     // what it is about, one stable word or two ("method", "offset_uncertain")
  std::string topic;    // the part of the film it concerns, printed before it ("plate"); or empty
  std::string message;  // one line, no prefix, no newline
  // Shown under --quiet. Notes never are; most warnings are, but those written out with the
  // template's offsets and the plate's contact line are part of the report -q silences.
  bool shown_when_quiet = false;
  // Said while the run's live progress line is drawn on a terminal (a frame skipped, a
  // decoder's message): a terminal shows it on a line of its own.
  bool during_progress = false;
};

// The line a terminal shows for `d` (no newline).
std::string FormatDiagnostic(const Diagnostic& d);

class Diagnostics {
 public:
  using Sink = std::function<void(const Diagnostic&)>;
  explicit Diagnostics(Sink sink = {}) : sink_(std::move(sink)) {}

  void Note(std::string code, std::string message, std::string topic = "") {
    Add({Severity::kNote, std::move(code), std::move(topic), std::move(message), false});
  }
  void Warn(std::string code, std::string message, std::string topic = "") {
    Add({Severity::kWarning, std::move(code), std::move(topic), std::move(message), true});
  }
  void WarnInput(std::string code, std::string message, bool during_progress = false) {
    Add({Severity::kInputWarning, std::move(code), "", std::move(message), true,
         during_progress});
  }
  // Thread-safe: decoders' messages arrive from the capture's reader thread (stderr_capture.h).
  void Add(Diagnostic d) {
    std::lock_guard<std::mutex> lock(mutex_);
    entries_.push_back(std::move(d));
    if (sink_) sink_(entries_.back());
  }
  // Read once the run has ended (no thread adds any more).
  const std::vector<Diagnostic>& entries() const { return entries_; }

 private:
  Sink sink_;
  std::mutex mutex_;
  std::vector<Diagnostic> entries_;
};

}  // namespace dimer::tracking
