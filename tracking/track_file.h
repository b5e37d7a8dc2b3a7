#pragma once
// Stage "write": the track file of docs/FORMATS.md from a tracked film (track_sequence.h), its
// calibration (calibration.h) and the recording's own values (a .cine header's), as sim_file.h
// and compare_file.h write theirs.
#include <string>

#include "tracking/calibration.h"
#include "tracking/io/frame_source.h"
#include "tracking/track_args.h"
#include "tracking/track_sequence.h"

namespace dimer::tracking {

// Where the frame rate came from, and the recording's header values (a .cine's) when known.
struct Recording {
  std::string fps_from;  // option | time_stamps | header | default
  RecordingInfo info;
};

// Where the blur that placed a clipped plate edge came from: "fitted", "default" or
// "--psf-sigma".
std::string PsfSource(const TrackArgs& args, const PlateClip& clip);

// Writes the file at `path` (the caller's temporary name: common/atomic_output.h). `args.fps`
// is the frame rate resolved (run_track.h).
void WriteTrackFile(const std::string& path, const TrackArgs& args, const SequenceResult& r,
                    const Calibration& cal, const Recording& rec);

}  // namespace dimer::tracking
