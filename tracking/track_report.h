#pragma once
// What a tracked film says besides its track (diagnostics.h): the input (a colour camera, a
// camera's levels), the method and why, the plate (over-exposed, sloping, its contact line),
// what was cleaned (matches that were not the sphere, the lens, stuck pixels), the template's
// offsets, each sphere's precision, and what --ar's scale came to. The notes are made whatever
// --quiet says; the caller's sink leaves them out under it.
#include "tracking/calibration.h"
#include "tracking/diagnostics.h"
#include "tracking/track_args.h"
#include "tracking/track_file.h"
#include "tracking/track_sequence.h"

namespace dimer::tracking {

// Everything about the film tracked, in the order a reader meets it.
void ReportFilm(const TrackArgs& args, const Recording& rec, const SequenceResult& r,
                Diagnostics* diag);

// What --ar did: the scale and the radius it gave, or, beside --m-per-px, whether they agree.
void ReportLengthScale(const TrackArgs& args, const Calibration& cal, Diagnostics* diag);

}  // namespace dimer::tracking
