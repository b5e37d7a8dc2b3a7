#include "tracking/run_track.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <set>
#include <string>

#include "common/atomic_output.h"
#include "common/error.h"
#include "common/format.h"
#include "common/progress.h"
#include "common/stderr_capture.h"
#include "tracking/calibration.h"
#include "tracking/dimer_length_scale.h"
#include "tracking/dimer_presence.h"
#include "tracking/io/cine_time_stamps.h"
#include "tracking/io/frame_range.h"
#include "tracking/sphere/impact_vertex.h"
#include "tracking/track_file.h"
#include "tracking/track_report.h"

namespace dimer::tracking {
namespace {

// Stage "options": the command's options as the tracker takes them. The plate-contact offset
// of the template method needs the radius in pixels: from the scale when it is given, else the
// measured one (which then also sets the scale). The lens's calibration is read before any
// work: a bad file is said at once.
SequenceOptions SequenceOptionsOf(const TrackArgs& args) {
  SequenceOptions seq = args.sequence;
  seq.follower.method = args.method;
  if (args.m_per_px && std::isnan(seq.contact_radius_px)) {
    seq.contact_radius_px = 0.5 * args.diameter / *args.m_per_px;
  }
  seq.follower.polarity = Sign(args.polarity);
  if (args.plate_m_per_px && args.m_per_px) {
    seq.plate_motion_scale = *args.plate_m_per_px / *args.m_per_px;
  }
  if (!args.lens.empty()) {
    seq.lens = std::make_shared<const LensCalibration>(ReadLensCalibration(args.lens));
  }
  return seq;
}

// The frame rate: --fps when given (warning when a .cine header says another), else the one
// of the frames' own time stamps (warning when the header's differs by more than 1 %: a film
// saved with a decimation), else the header's, else kDefaultFps. A .cine whose header says 0
// and that has no time stamps needs --fps: 2000 would silently scale every velocity.
Recording ResolveFps(const RecordingInfo& info, TrackArgs* args, Diagnostics* diag) {
  Recording rec{"option", info};
  const bool header = info.known && info.fps > 0;
  const double stamped = FrameRateOfTimes(info.frame_times);
  if (args->fps) {
    rec.info.frame_times.clear();  // --fps wins: t is frame_index / fps
    if (header && *args->fps != info.fps) {
      diag->WarnInput("fps", Format("%s: --fps %.10g differs from the .cine header's %.10g "
                                    "frames/s; using --fps %.10g",
                                    args->input.c_str(), *args->fps, info.fps, *args->fps));
    }
  } else if (stamped > 0) {
    args->fps = stamped;
    rec.fps_from = "time_stamps";
    if (header && std::abs(stamped - info.fps) > 0.01 * info.fps) {
      diag->WarnInput("fps", Format("%s: the frames' time stamps give %.6g frames/s, the header "
                                    "says %.10g (saved with a decimation?); using the time stamps",
                                    args->input.c_str(), stamped, info.fps));
    }
  } else if (header) {
    args->fps = info.fps;
    rec.fps_from = "header";
    rec.info.frame_times.clear();
  } else if (info.known) {
    throw InputError(args->input + ": the .cine header's frame rate is 0 and the file has no "
                     "time stamps; give the rate with --fps");
  } else {
    args->fps = kDefaultFps;
    rec.fps_from = "default";
  }
  return rec;
}

// A camera set to flip its image vertically: the frames are read as stored (cine_source.h),
// which is how Phantom's software shows them; said, since gravity then points up the frame if
// the camera was not mounted upside down.
void WarnFlip(const TrackArgs& args, const Recording& rec, Diagnostics* diag) {
  if (!rec.info.flip_v) return;
  diag->WarnInput("cine_flip_v",
                  Format("%s: the camera was set to flip its image vertically (bFlipV); the "
                         "frames are read as stored, the plate must be at the bottom",
                         args.input.c_str()));
}

// Lossy compression moves edges and smooths the noise the offsets are measured against: on
// POV-Ray footage exported as H.264 the columns came out up to 3 px off while stating 0.2-0.4
// px (docs/BENCHMARKS.md, compressed_video.sh). Said before the work, and kept in the file.
void WarnLossyCodec(const TrackArgs& args, const Recording& rec, Diagnostics* diag) {
  if (rec.info.video_codec.empty() || LosslessVideoCodec(rec.info.video_codec)) return;
  diag->WarnInput("lossy_codec",
                  Format("%s: video codec '%s' is taken as lossy: compression moves the spheres' "
                         "edges by tenths of a pixel to pixels, beyond the offsets' stated "
                         "uncertainties; track the camera's own files (.cine) or lossless frames "
                         "where you can",
                         args.input.c_str(), rec.info.video_codec.c_str()));
}

// What opening the input found that may be off: the source's own warnings, a lossy codec, a
// flipped camera.
void WarnOfTheInput(const TrackArgs& args, const FrameSource& source, const Recording& rec,
                    Diagnostics* diag) {
  for (const std::string& w : source.warnings()) diag->WarnInput("frame_source", w);
  WarnLossyCodec(args, rec, diag);
  WarnFlip(args, rec, diag);
}

// Stage "scale from the dimer's length" (--ar without --m-per-px): the radius the film is
// tracked with comes from the dimer's length over its first frames (dimer_length_scale.h); the
// film's own length then sets the scale. Empty otherwise.
LengthScale RadiusFromDimerLength(const TrackArgs& args, SequenceOptions* seq, Diagnostics* diag) {
  if (!args.ar || args.m_per_px) return {};
  diag->Note("length_scale_start",
             Format("scale from the dimer's length (--ar %g): tracking its first %zu frames "
                    "until the radius settles",
                    *args.ar, kLengthScaleFrames));
  const LengthScale length_scale = TrackedDimerLengthScale(
      {args.input, args.frames, *args.ar, args.diameter, args.plate_m_per_px}, *seq, diag);
  if (!length_scale.ok) {
    throw InputError(args.input + ": cannot take the scale from the dimer's length (--ar): " +
                     length_scale.failure + "; pass --m-per-px");
  }
  seq->contact_radius_px = length_scale.radius_px;
  if (args.plate_m_per_px) {
    seq->plate_motion_scale = *args.plate_m_per_px / (0.5 * args.diameter / length_scale.radius_px);
  }
  return length_scale;
}

// Decoders (libpng, libjpeg, libtiff, OpenCV's codecs) may print their own messages on stderr.
// While frames are decoded they are captured and each distinct one becomes one input warning
// (common/stderr_capture.h); the progress goes to the real stderr, and so must whatever prints
// the diagnostics (app/track_messages.h).
SequenceResult TrackWithLibraryMessagesCaptured(const TrackArgs& args, const SequenceOptions& seq,
                                                FrameSource& source,
                                                Diagnostics* diagnostics) {
  std::mutex seen_mutex;
  std::set<std::string> seen;
  size_t repeats = 0;
  const bool live = StderrCapture::DiagnosticsIsTerminal();
  auto on_library_line = [&](const std::string& line) {
    std::lock_guard<std::mutex> lock(seen_mutex);
    if (!seen.insert(line).second) {
      ++repeats;
      return;
    }
    diagnostics->WarnInput("decoder_message", args.input + ": decoder message: " + line,
                           !args.quiet && live);
  };
  SequenceResult r;
  {
    StderrCapture capture(on_library_line);
    ProgressMeter progress("track", "frames", double(source.size()), !args.quiet,
                           StderrCapture::Diagnostics(), live);
    r = TrackSequence(
        source, seq,
        [&](size_t done) {
          progress.Update(double(done));
          if (args.on_progress) args.on_progress(done);
        },
        [&](const SkippedFrame& s) {
          diagnostics->WarnInput("frame_skipped", s.name + ": " + s.reason + "; skipped",
                                 !args.quiet && live);
        });
    progress.Finish(double(r.frames.size() + r.skipped.size()));
  }
  if (repeats > 0) {
    diagnostics->WarnInput("decoder_repeats",
                           Format("%s: %zu repeated decoder messages not shown",
                                  args.input.c_str(), repeats));
  }
  return r;
}

// Stage "a dimer is here" (dimer_presence.h): a film of something else is refused before anything
// is written.
void RequireADimer(const std::string& input, bool scale_given, const SequenceResult& r,
                   Diagnostics* diag) {
  const DimerPresence dimer = MeasureDimerPresence(r);
  if (!dimer.seen()) throw InputError(input + ": " + NoDimerMessage(dimer, scale_given));
  const std::string out_of_view = DimerOutOfViewNote(dimer);
  if (!out_of_view.empty()) diag->Note("dimer_out_of_view", input + ": " + out_of_view);
}

// The one-line summary every subcommand ends with (app/ prints it on stdout; -q silences
// progress only).
void Summarize(const TrackArgs& args, const SequenceResult& r, const Calibration& cal) {
  if (!args.on_summary) return;
  size_t both = 0, cut = 0;
  for (const auto& f : r.frames) {
    both += f.found[0] && f.found[1];
    cut += (f.found[0] && f.cut[0]) || (f.found[1] && f.cut[1]);
  }
  const std::string cut_text =
      cut ? Format(" (%zu with a sphere cut by the frame's edge)", cut) : std::string();
  args.on_summary(Format("%s: %zu frames tracked, %zu skipped, both spheres found in %zu%s, %s, "
                         "%.4g m/px%s",
                         (args.output_label.empty() ? args.output : args.output_label).c_str(),
                         r.frames.size(), r.skipped.size(), both, cut_text.c_str(),
                         ToString(r.method).c_str(), cal.m_per_px,
                         r.complete ? "" : " (interrupted: partial)"));
}

}  // namespace

void RunTrack(const TrackArgs& args) {
  args.Check();
  Diagnostics diag(args.on_diagnostic);
  SequenceOptions seq = SequenceOptionsOf(args);
  AtomicOutput out(args.output, args.force);  // refuses an existing output before any work
  auto source = SelectFrames(OpenFrameSource(args.input), ParseFrameRange(args.frames),
                             args.input);
  TrackArgs resolved = args;
  const Recording rec = ResolveFps(source->recording(), &resolved, &diag);
  // g in px per frame^2 is this times the radius in px (whichever the film is tracked with).
  seq.gravity_per_radius_px = 2.0 * kGravity / (args.diameter * *resolved.fps * *resolved.fps);
  WarnOfTheInput(args, *source, rec, &diag);
  const LengthScale length_scale = RadiusFromDimerLength(args, &seq, &diag);
  const SequenceResult r = TrackWithLibraryMessagesCaptured(resolved, seq, *source, &diag);
  if (r.frames.empty()) {
    if (!r.complete) throw Interrupted();
    throw InputError(args.input + ": no readable frame (all " +
                     std::to_string(r.skipped.size()) + " were skipped)");
  }
  if (r.complete) RequireADimer(args.input, args.m_per_px.has_value(), r, &diag);  // a partial film is kept whatever it shows
  ReportFilm(args, rec, r, &diag);
  const Calibration cal = Calibrate(args, r, length_scale);
  if (args.ar) ReportLengthScale(args, cal, &diag);
  WriteTrackFile(out.temp_path(), resolved, r, cal, rec);
  out.Commit();
  Summarize(args, r, cal);
  if (!r.complete) throw Interrupted();
}

}  // namespace dimer::tracking
