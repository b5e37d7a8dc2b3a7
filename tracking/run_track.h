#pragma once
// `dimerlab track FRAMES -o track.h5`: a film through the tracking pipeline (docs/DESIGN.md,
// "The tracking pipeline") into the track file of docs/FORMATS.md. RunTrack reads as its list
// of stages: the options typed (the lens's calibration read at once), the output claimed, the
// frames opened, the frame rate resolved, --ar's passes, the film tracked (track_sequence.h),
// reported (track_report.h), calibrated (calibration.h) and written (track_file.h).
#include "tracking/track_args.h"

namespace dimer::tracking {

// Runs the whole command; throws InputError for bad input, Interrupted after writing a valid
// partial file on Ctrl-C. Its notes and warnings go to args.on_diagnostic; the one-line
// summary to stdout.
void RunTrack(const TrackArgs& args);

}  // namespace dimer::tracking
