#pragma once
// A footage case's TrackAccuracy measured once and read back by the other checks of the same
// case. Each POV-Ray case has four CTest checks (targets, plate, coverage, scatter), each its
// own process; tracking the same 20 frames four times cost ~45 s of the suite's wall time.
//
// The file holds every field exactly (hexadecimal floating point), the folder and method it was
// measured for, and is used only when it is newer than both the footage's truth.csv and the
// test program itself: a rebuilt tracker relinks the program, which invalidates every entry.
// Otherwise (missing, stale, another folder or method, unreadable) the accuracy is measured
// again and the file rewritten atomically (written aside, then renamed), so two checks started
// together never read half a file.
#include <string>

#include "tests/footage/track_accuracy.h"

namespace dimer::footage {

// MeasureTrackAccuracy(folder, method, threads) (scale given, the tracker's defaults, the lens's
// calibration file `lens` if not empty), through `cache_file`. `cache_file` empty: measured
// every time.
TrackAccuracy CachedTrackAccuracy(const std::string& folder, const std::string& method,
                                  int threads, const std::string& cache_file,
                                  const std::string& lens = "");

// The accuracy as text and back, every double exact; Parse returns false on any malformed or
// missing field (the cache is then ignored, never trusted in part).
std::string SerializeAccuracy(const TrackAccuracy& a);
bool ParseAccuracy(const std::string& text, TrackAccuracy* a);

}  // namespace dimer::footage
