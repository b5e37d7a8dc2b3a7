#include "tracking/track.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <deque>
#include <future>
#include <mutex>
#include <optional>
#include <set>
#include <thread>

#include "common/atomic_output.h"
#include "common/error.h"
#include "common/h5_file.h"
#include "common/interrupt.h"
#include "common/progress.h"
#include "common/stderr_capture.h"
#include "common/provenance.h"
#include "common/trajectory_io.h"
#include "tracking/dimer_length_scale.h"
#include "tracking/io/frame_range.h"
#include "tracking/sphere/impact_vertex.h"
#include "tracking/sphere/precision_bound.h"
#include "tracking/track_precision.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Found radii used for the diameter calibration (a median over this many is plenty).
constexpr size_t kCalibrationSamples = 2000;

// What every chunk must agree on, fixed from the first readable frame.
struct Reference {
  int width = 0, height = 0, polarity = 0;
  double radius_px = kNaN;
};

struct ChunkResult {
  std::vector<FrameTrack> frames;
  std::vector<std::string> names;
  std::vector<SkippedFrame> skipped;
  bool interrupted = false;
};

std::string SizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// A frame as the tracker measures it: the sensor's stuck pixels replaced first (they are the
// sensor's, and undistortion would smear them), then the lens's distortion taken out.
cv::Mat CleanFrame(const cv::Mat& image, const DefectPixels& defects,
                   const LensUndistortion* lens) {
  cv::Mat repaired = RepairDefectPixels(image, defects);
  return lens ? lens->Apply(repaired) : repaired;
}

ChunkResult TrackChunk(const FrameSource& source, size_t start, size_t count,
                       std::vector<Frame> prefetched, const TrackerOptions& opts,
                       const Reference& ref, const DefectPixels& defects,
                       const LensUndistortion* lens) {
  ChunkResult out;
  TrackerOptions o = opts;
  o.polarity = ref.polarity;
  o.radius_px = ref.radius_px;
  SequenceTracker tracker(o);
  const size_t n = prefetched.empty() ? count : prefetched.size();
  for (size_t j = 0; j < n; ++j) {
    if (InterruptRequested()) {
      out.interrupted = true;
      break;
    }
    Frame f = prefetched.empty() ? source.Read(start + j) : std::move(prefetched[j]);
    if (f.error.empty() && (f.image.cols != ref.width || f.image.rows != ref.height)) {
      f.error = "size " + SizeText(f.image.cols, f.image.rows) + " differs from the first frame's " +
                SizeText(ref.width, ref.height);
    }
    if (!f.error.empty()) {
      out.skipped.push_back({f.index, f.name, f.error});
      continue;
    }
    out.frames.push_back(tracker.Process(CleanFrame(f.image, defects, lens), f.index));
    out.names.push_back(f.name);
  }
  return out;
}

Reference MakeReference(const cv::Mat& image, const TrackerOptions& opts) {
  Reference ref;
  ref.width = image.cols;
  ref.height = image.rows;
  SequenceTracker probe(opts);
  probe.Process(image, 0);
  ref.polarity = probe.polarity();
  ref.radius_px = probe.radius_px();
  return ref;
}

// Swaps a chunk's identities when that continues the previous chunk's positions better.
void Stitch(const std::vector<FrameTrack>& done, std::vector<FrameTrack>* chunk) {
  auto both = [](const FrameTrack& t) { return t.found[0] && t.found[1]; };
  auto last = std::find_if(done.rbegin(), done.rend(), both);
  auto first = std::find_if(chunk->begin(), chunk->end(), both);
  if (last == done.rend() || first == chunk->end()) return;
  const double keep = (first->centre[0] - last->centre[0]).norm() +
                      (first->centre[1] - last->centre[1]).norm();
  const double cross = (first->centre[0] - last->centre[1]).norm() +
                       (first->centre[1] - last->centre[0]).norm();
  if (cross >= keep) return;
  for (FrameTrack& t : *chunk) {
    std::swap(t.found[0], t.found[1]);
    std::swap(t.centre[0], t.centre[1]);
    std::swap(t.radius_px[0], t.radius_px[1]);
  }
}

// An over-exposed plate: the clipped side's level shared by the frames, then every clipped
// frame's row fitted again at it (clipped_edge.h). The profiles are dropped afterwards.
PlateClip RefitClippedPlate(double psf_sigma_px, bool fit_blur, std::vector<FrameTrack>* frames) {
  PlateClip out;
  std::vector<const ClippedEdgeProfile*> profiles;
  std::vector<double> rows;
  for (const FrameTrack& f : *frames) {
    profiles.push_back(f.clipped_plate.get());
    rows.push_back(f.plate_row);
    out.frames += f.clipped_plate != nullptr;
  }
  if (out.frames > 0) {
    out.level = SharedClippedLevel(profiles, psf_sigma_px, kClippedLevelMaxFrames, fit_blur);
    out.refitted = RefitClippedRows(profiles, out.level, &rows);
  }
  for (size_t i = 0; i < frames->size(); ++i) {
    (*frames)[i].plate_row = rows[i];
    (*frames)[i].clipped_plate.reset();
  }
  return out;
}

}  // namespace

void SequenceOptions::Check() const {
  tracker.Check();
  if (threads < 0 || threads > 256) throw UsageError("--threads must be 0 (all cores) .. 256");
  if (chunk_frames < 1) throw UsageError("--chunk-frames must be >= 1");
  if (learn_passes < 0 || learn_passes > 20) throw UsageError("learning passes must be 0 .. 20");
  if (jackknife_groups < 0 || jackknife_groups > 64) {
    throw UsageError("jackknife groups must be 0 .. 64");
  }
  if (!(seed_agreement_px >= 0 && seed_agreement_px <= 64)) {
    throw UsageError("the seeds' agreement must be 0 (the default) .. 64 px");
  }
  if (camera_bits != 0 && (camera_bits < 8 || camera_bits > 16)) {
    throw UsageError("--bits must be 8 .. 16 (the camera's bits per pixel)");
  }
  if (!std::isnan(plate_motion_scale) &&
      !(plate_motion_scale > 0 && std::isfinite(plate_motion_scale))) {
    throw UsageError("the plate's motion scale must be > 0");
  }
}

namespace {

SequenceResult TrackSequenceOf(FrameSource& source, const SequenceOptions& options,
                               const std::function<void(size_t)>& on_progress,
                               const std::function<void(const SkippedFrame&)>& on_skip);

}  // namespace

SequenceResult TrackSequence(FrameSource& source, const SequenceOptions& options,
                             const std::function<void(size_t)>& on_progress,
                             const std::function<void(const SkippedFrame&)>& on_skip) {
  options.Check();
  // A 10- or 12-bit camera's 16-bit frames, scaled to the range the levels are fractions of
  // (level_scale.h); positions do not change with a gain.
  const LevelScale scale = ChooseLevelScale(source, options.camera_bits);
  SequenceResult result;
  if (scale.factor != 1) {
    const auto scaled = ScaledLevels(source, scale.factor);
    result = TrackSequenceOf(*scaled, options, on_progress, on_skip);
    result.level_scale = scale;
    result.level_scale.clipped_frames = scaled->clipped_frames();
    result.level_scale.first_clipped = scaled->first_clipped();
  } else {
    result = TrackSequenceOf(source, options, on_progress, on_skip);
    result.level_scale = scale;
  }
  return result;
}

namespace {

SequenceResult TrackSequenceOf(FrameSource& source, const SequenceOptions& options,
                               const std::function<void(size_t)>& on_progress,
                               const std::function<void(const SkippedFrame&)>& on_skip) {
  const int threads = options.threads > 0 ? options.threads
                                          : int(std::max(1u, std::thread::hardware_concurrency()));
  SequenceResult result;
  Reference ref;
  bool have_ref = false;
  size_t next = 0;
  bool exhausted = false;
  TrackerOptions chunk_opts = options.tracker;
  SequenceMethod prepared;
  cv::Mat first_frame;  // the first readable frame, stuck pixels replaced: its noise
  std::optional<LensUndistortion> lens;  // made for the first readable frame's size
  const LensUndistortion* undistort = nullptr;  // &*lens once made, for CleanFrame
  const bool sequence_level = options.tracker.method == Method::kTemplate ||
                              options.tracker.method == Method::kAuto;
  std::deque<std::future<ChunkResult>> inflight;
  auto launch = [&]() {
    std::vector<Frame> buffer;
    size_t count = options.chunk_frames;
    if (!source.random_access()) {  // decode ahead on this thread
      Frame f;
      while (buffer.size() < options.chunk_frames && source.Next(&f)) buffer.push_back(f);
      count = buffer.size();
    } else {
      count = std::min(count, source.size() - next);
    }
    if (count == 0) {
      exhausted = true;
      return;
    }
    if (!have_ref) {  // the first readable frame fixes size, polarity and radius
      cv::Mat first;
      for (size_t j = 0; j < count && first.empty(); ++j) {
        Frame f = buffer.empty() ? source.Read(next + j) : buffer[j];
        if (f.error.empty()) first = f.image;
      }
      have_ref = !first.empty();
      if (have_ref) {
        // Frames spread over the first chunk: the sensor's stuck pixels (defect_pixels.h), then,
        // on the frames with those replaced, the plate edge's slope (plate_slope.h).
        std::vector<cv::Mat> probe;
        for (size_t j = 0; j < kSlopeFrames; ++j) {
          const size_t i = j * count / kSlopeFrames;
          if (j > 0 && i == (j - 1) * count / kSlopeFrames) continue;
          Frame f = buffer.empty() ? source.Read(next + i) : buffer[i];
          if (f.error.empty() && f.image.size() == first.size()) probe.push_back(f.image);
        }
        result.defects = FindDefectPixels(probe);
        if (options.lens) {
          lens.emplace(*options.lens, first.size());
          result.lens = options.lens;
          result.lens_max_shift_px = lens->max_shift_px();
          undistort = &*lens;
        }
        for (cv::Mat& p : probe) p = CleanFrame(p, result.defects, undistort);
        first_frame = CleanFrame(first, result.defects, undistort);
        ref = MakeReference(first_frame, options.tracker);
        result.plate_slope = EstimatePlateSlope(probe, ref.polarity);
        chunk_opts.plate_slope = result.plate_slope.value;
      }
      if (have_ref && sequence_level) {
        // Learning frames by index only (sequential sources: within the first chunk, which is
        // decoded ahead anyway); the method and appearances are fixed before any chunk runs.
        std::vector<Frame> learning;
        for (size_t i : LearningIndices(buffer.empty() ? source.size() : buffer.size())) {
          Frame f = buffer.empty() ? source.Read(i) : buffer[i];
          if (f.error.empty() && f.image.cols == ref.width && f.image.rows == ref.height) {
            f.image = CleanFrame(f.image, result.defects, undistort);
            learning.push_back(std::move(f));
          }
        }
        TrackerOptions reference = options.tracker;
        reference.polarity = ref.polarity;
        reference.plate_slope = chunk_opts.plate_slope;
        // The template is sized by the true radius when the scale is known (the silhouette
        // radius of a front-lit steel sphere can be pixels short).
        reference.radius_px = std::isfinite(options.contact_radius_px) ? options.contact_radius_px
                                                                       : ref.radius_px;
        prepared = PrepareSequenceMethod(learning, reference, options.tracker.method,
                                         std::isfinite(options.contact_radius_px),
                                         LearnOptions{options.learn_passes, threads,
                                                      chunk_opts.plate_slope,
                                                      options.jackknife_groups,
                                                      options.seed_agreement_px});
        chunk_opts.method = prepared.choice.method;
        chunk_opts.appearance = prepared.appearance;
        // The template's radius (the scale's, or its outline's) is every frame's radius, which
        // calibrates the scale when it is not given.
        if (prepared.appearance) {
          ref.radius_px = (*prepared.appearance)[0].radius_px;
          result.radius_source = std::isfinite(options.contact_radius_px) ? "scale"
                                 : prepared.radius_from_outline       ? "outline"
                                                                      : "silhouette";
        }
      }
    }
    inflight.push_back(std::async(std::launch::async, TrackChunk, std::cref(source), next, count,
                                  std::move(buffer), chunk_opts, ref, std::cref(result.defects),
                                  undistort));
    next += count;
    if (source.random_access() && next >= source.size()) exhausted = true;
  };
  while (true) {
    // Exactly `threads` chunks run at once (each on its own std::thread via std::async): more
    // would oversubscribe the cores; results do not depend on it (chunks are joined in order).
    while (!exhausted && !InterruptRequested() && int(inflight.size()) < threads) launch();
    if (inflight.empty()) break;
    ChunkResult chunk = inflight.front().get();
    inflight.pop_front();
    for (const auto& s : chunk.skipped) {
      if (on_skip) on_skip(s);
      result.skipped.push_back(s);
    }
    if (!result.complete) continue;  // after an interruption keep only whole prefixes
    Stitch(result.frames, &chunk.frames);
    result.frames.insert(result.frames.end(), chunk.frames.begin(), chunk.frames.end());
    result.names.insert(result.names.end(), chunk.names.begin(), chunk.names.end());
    if (chunk.interrupted) result.complete = false;
    if (on_progress) on_progress(result.frames.size() + result.skipped.size());
  }
  if (InterruptRequested()) result.complete = false;
  result.method = sequence_level ? prepared.choice.method : options.tracker.method;
  result.method_reason = prepared.choice.reason;
  // Before anything reads the found spheres (the plate's motion scale, the offsets).
  result.scores = DropOutlyingMatches(&result.frames);
  result.plate_clip = RefitClippedPlate(options.tracker.psf_sigma_px,
                                        options.tracker.fit_psf_sigma, &result.frames);
  result.plate_shift = prepared.plate_shift;
  const bool scale_given = std::isfinite(options.plate_motion_scale);
  if (prepared.plate_shift.applied || scale_given) {
    // The edge to the contact line: a constant at the learning frames' edge row (a polished
    // plate's mirror images), and the edge's motion scaled to the contact line's, by the ratio
    // of scales the user gave or else by a resting sphere (plate_contact.h).
    std::vector<double> edge;
    std::array<std::vector<double>, 2> rows;
    for (const FrameTrack& f : result.frames) {
      edge.push_back(f.plate_row);
      for (int k = 0; k < 2; ++k) rows[k].push_back(f.found[k] ? f.centre[k].y() : std::nan(""));
    }
    result.plate_scale =
        scale_given
            ? GivenPlateMotionScale(options.plate_motion_scale, edge, prepared.plate_shift)
            : FitPlateMotionScale(edge, rows, prepared.plate_shift);
    for (FrameTrack& f : result.frames) {
      f.plate_row = ContactRow(prepared.plate_shift, result.plate_scale, f.plate_row);
    }
  }
  if (chunk_opts.appearance) {
    result.appearance = *chunk_opts.appearance;
    result.frame_noise = FrameNoiseSigma(first_frame);
    for (int k = 0; k < 2; ++k) {
      result.precision_bound[k] = TranslationBound(result.appearance[k], result.frame_noise);
    }
    result.offsets = EstimateOffsets(prepared, result.frames, ref.radius_px,
                                     options.gravity_per_radius_px * ref.radius_px);
    ApplyOffsets(result.offsets, &result.frames);
  }
  result.precision = MeasurePrecision(result.frames, result.precision_bound);
  result.polarity = ref.polarity;
  result.width = ref.width;
  result.height = ref.height;
  return result;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

void TrackArgs::Check() const {
  std::string bad;
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad += (bad.empty() ? "" : "; ") + what;
  };
  need(!input.empty(), "input: a folder of frames, a TIFF, a .cine or a video is required");
  need(!output.empty(), "-o: the output track file is required");
  need(std::isnan(fps) || (fps > 0 && std::isfinite(fps)), "--fps must be > 0 frames/s");
  try {
    ParseFrameRange(frames);
  } catch (const InputError& e) {
    need(false, e.what());
  }
  need(std::isnan(m_per_px) || m_per_px > 0, "--m-per-px must be > 0 m/px");
  need(std::isnan(plate_m_per_px) || (plate_m_per_px > 0 && std::isfinite(plate_m_per_px)),
       "--plate-m-per-px must be > 0 m/px");
  // The ratio of the two scales is what moves the plate rows, and it is needed while tracking
  // (the template's plate-contact offsets read them), before a scale from --diameter exists.
  need(std::isnan(plate_m_per_px) || !std::isnan(m_per_px) || !std::isnan(ar),
       "--plate-m-per-px needs --m-per-px or --ar (the dimer plane's scale)");
  need(diameter > 0 && std::isfinite(diameter), "--diameter must be > 0 m");
  need(std::isnan(ar) || (ar >= kMinAspectRatio && std::isfinite(ar)),
       "--ar must be >= 2 (the dimer's length over a sphere's diameter; 2: spheres touching)");
  need(polarity == "auto" || polarity == "bright" || polarity == "dark",
       "--polarity '" + polarity + "': expected auto, bright or dark");
  try {
    ParseMethod(method);
  } catch (const InputError& e) {
    need(false, e.what());
  }
  if (!bad.empty()) throw UsageError(bad);
  sequence.Check();
}

namespace {

double Median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// Where the blur that placed a clipped plate edge came from.
std::string PsfSource(const TrackArgs& args, const PlateClip& clip) {
  if (clip.level.psf_fitted) return "fitted";
  return args.sequence.tracker.fit_psf_sigma ? "default" : "--psf-sigma";
}

// Pixels to metres. With a sloping plate edge (plate_slope.h) the axes turn with it: x along
// the plate, z along its normal, about the plate's mean row `row0` at the frame's centre column
// `col0`; with a level plate, x = col m_per_px and z = (row0 - row) m_per_px.
struct Calibration {
  double m_per_px = kNaN, row0 = kNaN;
  double col0 = 0, cos_a = 1, sin_a = 0;  // pivot column; the slope's angle
  // The track's median centre distance (offsets applied) and its frames: the scale with --ar
  // and no --m-per-px, a check with both.
  double length_px = kNaN;
  size_t length_frames = 0;
  LengthScale length_scale;  // the passes that chose the radius tracked with (--ar alone)
  Eigen::Vector2d ToMetres(const Eigen::Vector2d& px) const {
    const double dc = px.x() - col0, dr = px.y() - row0;
    return m_per_px * Eigen::Vector2d(col0 + dc * cos_a + dr * sin_a, dc * sin_a - dr * cos_a);
  }
};

Calibration Calibrate(const TrackArgs& args, const SequenceResult& r, const LengthScale& passes) {
  Calibration cal;
  cal.m_per_px = args.m_per_px;
  cal.row0 = args.row0;
  cal.length_scale = passes;
  if (!std::isnan(args.ar)) cal.length_px = MedianDimerLength(r.frames, &cal.length_frames);
  if (std::isnan(cal.m_per_px) && !std::isnan(args.ar)) {
    if (!std::isfinite(cal.length_px)) {
      throw InputError(args.input + ": cannot take the scale from the dimer's length (--ar): " +
                       std::to_string(cal.length_frames) + " frames show both spheres (" +
                       std::to_string(kLengthScaleMinFrames) + " needed); pass --m-per-px");
    }
    cal.m_per_px = ScaleFromDimerLength(cal.length_px, args.ar, args.diameter);
  } else if (std::isnan(cal.m_per_px)) {
    std::vector<double> radii;
    for (const auto& f : r.frames) {
      for (int k = 0; k < 2 && radii.size() < kCalibrationSamples; ++k) {
        if (f.found[k]) radii.push_back(f.radius_px[k]);
      }
    }
    const double radius = Median(radii);
    if (!std::isfinite(radius)) {
      throw InputError(args.input +
                       ": no sphere found, cannot calibrate; pass --m-per-px, or --ar with the "
                       "dimer's aspect ratio");
    }
    cal.m_per_px = args.diameter / (2.0 * radius);
  }
  const double slope = r.plate_slope.value;
  if (slope != 0) {
    cal.col0 = 0.5 * (r.width - 1);
    const double a = std::atan(slope);
    cal.cos_a = std::cos(a);
    cal.sin_a = std::sin(a);
  }
  if (std::isnan(cal.row0)) {
    std::vector<double> rows;
    for (const auto& f : r.frames) rows.push_back(f.PlateRowAt(cal.col0));
    cal.row0 = Median(rows);
    if (std::isnan(cal.row0)) cal.row0 = r.height - 0.5;  // no plate seen: bottom of the frame
  }
  return cal;
}

// Where the frame rate came from, and the recording's header values (a .cine's) when known.
struct Recording {
  std::string fps_from;  // option | header | default
  RecordingInfo info;
};

// TIME64 (seconds since 1970 and 2^-32 s fractions) as ISO 8601 UTC with nanoseconds.
std::string TriggerTimeText(int64_t seconds, int64_t fraction) {
  const std::time_t t = static_cast<std::time_t>(seconds);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char day[32];
  std::strftime(day, sizeof day, "%Y-%m-%dT%H:%M:%S", &tm);
  const long long ns = (static_cast<long long>(fraction) * 1000000000LL) >> 32;
  char out[64];
  std::snprintf(out, sizeof out, "%s.%09lldZ", day, ns);
  return out;
}

// How precisely each sphere was followed, beside the footage's bound (track_precision.h).
void WritePrecisionGroup(H5Writer& w, const SequenceResult& r) {
  std::vector<double> scatter, bound;
  std::vector<int64_t> followed, poor;
  for (int k = 0; k < 2; ++k) {
    const SpherePrecision& p = r.precision[k];
    scatter.insert(scatter.end(), {p.measured.x(), p.measured.y()});
    bound.insert(bound.end(), {p.bound.x(), p.bound.y()});
    followed.push_back(p.followed);
    poor.push_back(p.poor);
  }
  w.WriteDoubles("/precision/scatter", scatter, {2, 2}, "px", "col,row");
  w.SetAttr("/precision/scatter", "rows", "left,right");
  w.SetAttr("/precision/scatter", "description",
            "each sphere's centres' scatter from frame to frame: the median absolute second "
            "difference / 0.6745 / sqrt(6) (NaN: fewer than 3 consecutive found frames)");
  w.WriteDoubles("/precision/bound", bound, {2, 2}, "px", "col,row");
  w.SetAttr("/precision/bound", "rows", "left,right");
  w.SetAttr("/precision/bound", "description",
            "Cramer-Rao bound on placing each sphere's learnt appearance in the first frame's "
            "noise (template method; NaN otherwise)");
  w.SetAttr("/precision/bound", "frame_noise", r.frame_noise);
  w.SetAttr("/precision/bound", "frame_noise_units", "grey levels");
  w.WriteInt64("/precision/followed", followed, {2});
  w.SetAttr("/precision/followed", "codes", "0=not followed as the footage allows,1=followed");
  w.SetAttr("/precision/followed", "rows", "left,right");
  char text[160];
  std::snprintf(text, sizeof text,
                "whether each sphere was followed as the footage allows: not where its scatter "
                "is above %g times the bound and %g px",
                kNotFollowedFactor, kNotFollowedMinPx);
  w.SetAttr("/precision/followed", "description", text);
  w.WriteInt64("/precision/poor_footage", poor, {2});
  std::snprintf(text, sizeof text, "0=no,1=the bound is above %g px", kPoorFootageBoundPx);
  w.SetAttr("/precision/poor_footage", "codes", text);
  w.SetAttr("/precision/poor_footage", "rows", "left,right");
  w.SetAttr("/precision/poor_footage", "description",
            "whether the footage shows each sphere with too little contrast for sub-pixel work");
}

// The template method's learnt appearances and offsets (docs/FORMATS.md).
void WriteTemplateGroup(H5Writer& w, const SequenceResult& r) {
  std::vector<double> offset, err;
  std::vector<int64_t> frames;
  std::vector<std::string> sources;
  for (int k = 0; k < 2; ++k) {
    for (const OffsetEstimate* e : {&r.offsets.col[k], &r.offsets.row[k]}) {
      offset.push_back(e->value);
      err.push_back(e->err);
      frames.push_back(int64_t(e->n));
      sources.push_back(e->source);
    }
  }
  w.WriteDoubles("/template/offset", offset, {2, 2}, "px", "col,row");
  w.SetAttr("/template/offset", "rows", "left,right");
  w.SetAttr("/template/offset", "description",
            "offset from each learnt appearance's reference point to the sphere centre, added to "
            "every located position (already applied to /pixels)");
  // NaN (no row carried over) is written as such: the attribute is always there.
  w.SetAttr("/template/offset", "appearance_mismatch", r.offsets.appearance_mismatch);
  w.WriteDoubles("/template/offset_err", err, {2, 2}, "px", "col,row");
  w.SetAttr("/template/offset_err", "description", "standard uncertainty of /template/offset");
  w.WriteInt64("/template/offset_frames", frames, {2, 2});
  w.SetAttr("/template/offset_frames", "units", "1");
  w.SetAttr("/template/offset_frames", "columns", "col,row");
  w.SetAttr("/template/offset_frames", "description", "frames each offset rests on");
  w.WriteStrings("/template/offset_source", sources);
  w.SetAttr("/template/offset_source", "description",
            "left col, left row, right col, right row: silhouette, plate_contact, "
            "plate_contact_impacts, plate_contact_bounces, "
            "plate_contact_of_other(_outline|_both), limb, "
            "symmetry(_and_whole_outline) or none");
  for (int k = 0; k < 2; ++k) {
    const Appearance& a = r.appearance[k];
    std::vector<double> img(a.image.begin<float>(), a.image.end<float>());
    std::vector<uint8_t> mask(a.mask.begin<uint8_t>(), a.mask.end<uint8_t>());
    const std::string name = std::string("/template/") + (k == 0 ? "left" : "right");
    const size_t size = size_t(a.image.rows);
    std::string columns;  // each column's offset from the reference column, px
    for (int x = -a.half; x <= a.half; ++x) columns += (columns.empty() ? "" : ",") + std::to_string(x);
    w.WriteDoubles(name, img, {size, size}, "grey levels", columns);
    w.SetAttr(name, "description",
              "the learnt appearance, reference point at the centre pixel; frame grey levels");
    w.WriteUint8(name + "_mask", mask, {size, size});
    w.SetAttr(name + "_mask", "columns", columns);
    w.SetAttr(name + "_mask", "codes", "0=not part of the sphere's appearance (rod, plate, unseen),1=used");
    w.SetAttr(name + "_mask", "description", "which pixels of the learnt appearance are used");
  }
}

void WriteTrackFile(const std::string& path, const TrackArgs& args, const SequenceResult& r,
                    const Calibration& cal, const Recording& rec) {
  const size_t n = r.frames.size();
  Trajectory traj;
  traj.Reserve(n);
  std::vector<double> px[2], plate_row(n);
  std::vector<int64_t> index(n);
  std::vector<uint8_t> found(2 * n);
  for (size_t i = 0; i < n; ++i) {
    const FrameTrack& f = r.frames[i];
    Eigen::Vector2d tip[2];
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d c = f.found[k] ? f.centre[k] : Eigen::Vector2d(kNaN, kNaN);
      px[k].push_back(c.x());
      px[k].push_back(c.y());
      tip[k] = cal.ToMetres(c);
      found[2 * i + k] = f.found[k];
    }
    const Eigen::Vector2d axis = tip[1] - tip[0];
    // The plate under the dimer: midway between the spheres (where it was read if one is lost).
    const double plate_col = f.found[0] && f.found[1] ? 0.5 * (f.centre[0].x() + f.centre[1].x())
                                                      : f.plate_col;
    plate_row[i] = f.PlateRowAt(plate_col);
    traj.Append(double(f.index) / args.fps, tip[0], tip[1],
                cal.ToMetres({plate_col, plate_row[i]}).y(), std::atan2(axis.y(), axis.x()));
    index[i] = int64_t(f.index);
  }
  std::vector<std::string> skipped_names, skipped_reasons;
  for (const auto& s : r.skipped) {
    skipped_names.push_back(s.name);
    skipped_reasons.push_back(s.reason);
  }
  const bool clip_found = r.plate_clip.level.found();
  AttrList attrs = {{"source", args.input}, {"frames", args.frames.empty() ? "all" : args.frames},
                    {"method", ToString(r.method)}, {"method_requested", args.method},
                    {"method_reason", r.method_reason}, {"fps", args.fps},
                    {"fps_source", rec.fps_from},
                    {"plate_shift", r.plate_shift.applied ? r.plate_shift.value : 0.0},
                    {"plate_shift_err", r.plate_shift.applied ? r.plate_shift.err : 0.0},
                    {"plate_shift_reason", r.plate_shift.reason},
                    {"plate_shift_edge_ref",
                     r.plate_shift.applied || r.plate_scale.given ? r.plate_scale.edge_ref : 0.0},
                    {"plate_motion_scale", r.plate_scale.scale},
                    {"plate_motion_scale_err", r.plate_scale.fitted ? r.plate_scale.err : 0.0},
                    {"plate_motion_scale_source",
                     std::string(r.plate_scale.given    ? "--plate-m-per-px"
                                 : r.plate_scale.fitted ? "fitted"
                                                        : "none")},
                    {"plate_m_per_px", std::isnan(args.plate_m_per_px) ? 0.0 : args.plate_m_per_px},
                    {"plate_clipped_frames", int64_t(r.plate_clip.frames)},
                    {"plate_clip_level", clip_found ? r.plate_clip.level.value : 0.0},
                    {"plate_clip_level_err", clip_found ? r.plate_clip.level.err : 0.0},
                    {"plate_clip_refitted", int64_t(r.plate_clip.refitted)},
                    {"plate_psf_sigma", clip_found ? r.plate_clip.level.psf_sigma
                                                   : args.sequence.tracker.psf_sigma_px},
                    {"plate_psf_sigma_source", PsfSource(args, r.plate_clip)},
                    {"plate_slope", r.plate_slope.value},
                    {"plate_slope_measured", r.plate_slope.measured},
                    {"plate_slope_err", r.plate_slope.err},
                    {"plate_slope_reason", r.plate_slope.reason},
                    {"stuck_pixels", int64_t(r.defects.at.size())},
                    {"stuck_pixels_frames", int64_t(r.defects.frames)},
                    {"stuck_pixels_reason", r.defects.reason},
                    {"matches_dropped_score_left", int64_t(r.scores.dropped[0])},
                    {"matches_dropped_score_right", int64_t(r.scores.dropped[1])},
                    {"matches_dropped_length_left", int64_t(r.scores.dropped_length[0])},
                    {"matches_dropped_length_right", int64_t(r.scores.dropped_length[1])},
                    {"dimer_length_px", r.scores.length_px}};
  AttrUnits units = {{"fps", "1/s"}, {"plate_shift", "px"}, {"plate_shift_err", "px"},
                     {"plate_shift_edge_ref", "px"}, {"plate_motion_scale", "1"},
                     {"plate_motion_scale_err", "1"}, {"plate_m_per_px", "m/px"},
                     {"plate_clipped_frames", "1"},
                     {"plate_clip_level", "grey levels"}, {"plate_clip_level_err", "grey levels"},
                     {"plate_clip_refitted", "1"}, {"plate_psf_sigma", "px"},
                     {"plate_slope", "px/px"}, {"plate_slope_measured", "px/px"},
                     {"plate_slope_err", "px/px"}, {"stuck_pixels", "1"},
                     {"stuck_pixels_frames", "1"}, {"matches_dropped_score_left", "1"},
                     {"matches_dropped_score_right", "1"}, {"matches_dropped_length_left", "1"},
                     {"matches_dropped_length_right", "1"}, {"dimer_length_px", "px"},
                     {"m_per_px", "m/px"}, {"row0", "px"}, {"col0", "px"}, {"ar", "1"},
                     {"ar_length_px", "px"}, {"ar_length_frames", "1"}, {"ar_radius_px", "px"},
                     {"ar_outline_radius_px", "px"},
                     {"ar_passes", "1"}, {"ar_converged", "1"},
                     {"diameter", "m"},
                     {"chunk_frames", "1"}, {"width", "px"}, {"height", "px"},
                     {"frames_tracked", "1"}, {"frames_skipped", "1"}};
  if (!rec.info.video_codec.empty()) {  // a video file's codec, as its container declares it
    attrs.push_back({"video_codec", rec.info.video_codec});
    attrs.push_back({"video_codec_lossless", int64_t{LosslessVideoCodec(rec.info.video_codec)}});
    units["video_codec_lossless"] = "1";
  }
  attrs.push_back({"lens", r.lens ? r.lens->path : std::string()});
  attrs.push_back({"lens_max_shift_px", r.lens_max_shift_px});
  units["lens_max_shift_px"] = "px";
  attrs.push_back({"level_scale", r.level_scale.factor});
  attrs.push_back({"level_scale_bits", int64_t(r.level_scale.bits)});
  attrs.push_back({"level_scale_clipped_frames", int64_t(r.level_scale.clipped_frames)});
  units["level_scale"] = "1";
  units["level_scale_bits"] = "bit";
  units["level_scale_clipped_frames"] = "1";
  if (rec.info.known) {  // the .cine header's values, exactly as stored
    attrs.push_back({"exposure_ns", rec.info.exposure_ns});
    attrs.push_back({"trigger_time", TriggerTimeText(rec.info.trigger_seconds,
                                                     rec.info.trigger_fraction)});
    attrs.push_back({"trigger_time_seconds", rec.info.trigger_seconds});
    attrs.push_back({"trigger_time_fraction", rec.info.trigger_fraction});
    attrs.push_back({"first_image_no", rec.info.first_image_no});
    attrs.push_back({"real_bpp", int64_t(rec.info.real_bpp)});
    attrs.push_back({"cine_colour", rec.info.colour});
    attrs.push_back({"cine_cfa", rec.info.cfa});
    attrs.push_back({"cine_mosaic_balance", rec.info.mosaic_balance});
    units["exposure_ns"] = "ns";
    units["trigger_time_seconds"] = "s";
    units["trigger_time_fraction"] = "2^-32 s";
    units["first_image_no"] = "1";
    units["real_bpp"] = "bit";
    units["cine_cfa"] = "1";
  }
  H5Writer w(path);
  const AttrList rest = {
      {"m_per_px", cal.m_per_px}, {"row0", cal.row0}, {"col0", cal.col0},
      {"diameter", args.diameter},
      {"polarity", std::string(r.polarity > 0 ? "bright" : "dark")},
      {"polarity_requested", args.polarity},
      {"m_per_px_given",
       int64_t(!std::isnan(args.m_per_px) ? 1 : !std::isnan(args.ar) ? 2 : 0)},
      {"ar", std::isnan(args.ar) ? 0.0 : args.ar},
      {"ar_length_px", std::isfinite(cal.length_px) ? cal.length_px : 0.0},
      {"ar_length_frames", int64_t(cal.length_frames)},
      {"ar_radius_px", cal.length_scale.ok ? cal.length_scale.radius_px : 0.0},
      {"ar_outline_radius_px", std::isfinite(cal.length_scale.outline_radius_px)
                                   ? cal.length_scale.outline_radius_px
                                   : 0.0},
      {"ar_passes", int64_t(cal.length_scale.passes.size())},
      {"ar_converged", int64_t(cal.length_scale.converged)},
      {"chunk_frames", int64_t(args.sequence.chunk_frames)},
      {"width", int64_t(r.width)}, {"height", int64_t(r.height)},
      {"frames_tracked", int64_t(n)}, {"frames_skipped", int64_t(r.skipped.size())},
      {"complete", int64_t(r.complete)}};
  attrs.insert(attrs.end(), rest.begin(), rest.end());
  WriteProvenance(w, "track", attrs, units,
                  {{"m_per_px_given", "0=calibrated from --diameter,1=given by --m-per-px,"
                                      "2=calibrated from --ar (the dimer's length)"},
                   {"complete", "0=interrupted (Ctrl-C): the frames tracked so far,1=complete"}});
  WriteTrajectory(w, traj);
  w.WriteDoubles("/pixels/left", px[0], {n, 2}, "px", "col,row");
  w.SetAttr("/pixels/left", "description",
            "sub-pixel centre of the left sphere: 0-based column and row of pixel centres, rows "
            "growing downward; NaN where not found");
  w.WriteDoubles("/pixels/right", px[1], {n, 2}, "px", "col,row");
  w.SetAttr("/pixels/right", "description",
            "sub-pixel centre of the right sphere: 0-based column and row of pixel centres, rows "
            "growing downward; NaN where not found");
  w.WriteDoubles("/pixels/plate_row", plate_row, {n}, "px");
  w.SetAttr("/pixels/plate_row", "description",
            "row of the plate's top surface under the dimer (at the column midway between the "
            "centres; the edge slopes by the root attribute plate_slope)");
  w.WriteInt64("/frame_index", index, {n});
  w.SetAttr("/frame_index", "units", "1");
  w.SetAttr("/frame_index", "description",
            "0-based index of the frame in the source's sorted frame list");
  w.WriteStrings("/frame_files", r.names);
  w.SetAttr("/frame_files", "description", "file name of each tracked frame (FILE#PAGE in a stack)");
  w.WriteUint8("/found", found, {n, 2});
  w.SetAttr("/found", "columns", "left,right");
  w.SetAttr("/found", "codes", "0=not found (its tips and pixels are NaN),1=found");
  w.SetAttr("/found", "description", "whether each sphere was found in the frame");
  if (r.method == Method::kTemplate) WriteTemplateGroup(w, r);
  WritePrecisionGroup(w, r);
  std::vector<int64_t> stuck;
  for (const cv::Point& p : r.defects.at) stuck.insert(stuck.end(), {p.x, p.y});
  w.WriteInt64("/stuck_pixels", stuck, {r.defects.at.size(), 2});
  w.SetAttr("/stuck_pixels", "columns", "col,row");
  w.SetAttr("/stuck_pixels", "units", "px");
  w.SetAttr("/stuck_pixels", "description",
            "the sensor's stuck (hot or dead) pixels, found on the frames spread over the first "
            "chunk and replaced in every frame, before tracking, by the mean of their sound "
            "opposite neighbours");
  if (r.lens) {
    const LensCalibration& c = *r.lens;
    w.WriteDoubles("/lens/camera_matrix", std::vector<double>(c.camera.val, c.camera.val + 9),
                   {3, 3}, "px");
    w.SetAttr("/lens/camera_matrix", "description",
              "the lens calibration's camera matrix (fx 0 cx; 0 fy cy; 0 0 1), kept by the "
              "undistortion: every position in this file is in the undistorted frame");
    w.WriteDoubles("/lens/distortion", c.distortion, {c.distortion.size()}, "1");
    w.SetAttr("/lens/distortion", "description",
              "the lens's distortion coefficients in OpenCV's order (k1 k2 p1 p2 k3 ...), taken "
              "out of every frame before tracking");
  }
  w.WriteStrings("/skipped/files", skipped_names);
  w.SetAttr("/skipped/files", "description", "frames that could not be used");
  w.WriteStrings("/skipped/reasons", skipped_reasons);
  w.SetAttr("/skipped/reasons", "description", "why each skipped frame could not be used");
  w.Close();
}

// Decoders (libpng, libjpeg, libtiff, OpenCV's codecs) may print their own messages on stderr.
// While frames are decoded they are captured and each distinct one becomes one dimerlab warning
// (common/stderr_capture.h); our own progress and warnings go to the real stderr.
SequenceResult TrackWithLibraryMessagesCaptured(const TrackArgs& args, const SequenceOptions& seq,
                                                FrameSource& source) {
  std::mutex seen_mutex;
  std::set<std::string> seen;
  size_t repeats = 0;
  auto on_library_line = [&](const std::string& line) {
    std::lock_guard<std::mutex> lock(seen_mutex);
    if (!seen.insert(line).second) {
      ++repeats;
      return;
    }
    std::fprintf(StderrCapture::Diagnostics(), "dimerlab: warning: %s: decoder message: %s\n",
                 args.input.c_str(), line.c_str());
  };
  SequenceResult r;
  {
    StderrCapture capture(on_library_line);
    FILE* diag = StderrCapture::Diagnostics();
    const bool live = StderrCapture::DiagnosticsIsTerminal();
    ProgressMeter progress("track", "frames", double(source.size()), !args.quiet, diag, live);
    r = TrackSequence(
        source, seq,
        [&](size_t done) {
          progress.Update(double(done));
          if (args.on_progress) args.on_progress(done);
        },
        [&](const SkippedFrame& s) {
          std::fprintf(diag, "%sdimerlab: warning: %s: %s; skipped\n",
                       args.quiet || !live ? "" : "\n", s.name.c_str(), s.reason.c_str());
        });
    progress.Finish(double(r.frames.size() + r.skipped.size()));
  }
  if (repeats > 0) {
    std::fprintf(stderr, "dimerlab: warning: %s: %zu repeated decoder messages not shown\n",
                 args.input.c_str(), repeats);
  }
  return r;
}

// The frame rate: --fps when given (warning when a .cine header says another), else the
// header's, else kDefaultFps.
Recording ResolveFps(const RecordingInfo& info, TrackArgs* args) {
  Recording rec{"option", info};
  const bool header = info.known && info.fps > 0;
  if (std::isnan(args->fps)) {
    args->fps = header ? info.fps : kDefaultFps;
    rec.fps_from = header ? "header" : "default";
  } else if (header && args->fps != info.fps) {
    std::fprintf(stderr,
                 "dimerlab: warning: %s: --fps %.10g differs from the .cine header's %.10g "
                 "frames/s; using --fps %.10g\n",
                 args->input.c_str(), args->fps, info.fps, args->fps);
  }
  return rec;
}

// What --ar did: the scale and the radius it gave, or, beside --m-per-px, whether they agree.
// Each sphere's frame-to-frame scatter beside the footage's bound; a warning where the tracker
// did not follow a sphere as the footage allows (track_precision.h): its positions are then not
// what a sub-pixel tracker gives, whatever "found" says.
void ReportPrecision(const TrackArgs& args, const SequenceResult& r) {
  for (int k = 0; k < 2; ++k) {
    const SpherePrecision& p = r.precision[k];
    const char* side = k == 0 ? "left" : "right";
    if (!args.quiet && p.measured.allFinite()) {
      if (p.bound.allFinite()) {
        std::fprintf(stderr,
                     "dimerlab track: %s sphere: centres scatter %.3f / %.3f px (col / row) "
                     "from frame to frame; the footage allows %.3f / %.3f (noise %.2f grey "
                     "levels)\n",
                     side, p.measured.x(), p.measured.y(), p.bound.x(), p.bound.y(),
                     r.frame_noise);
      } else {
        std::fprintf(stderr,
                     "dimerlab track: %s sphere: centres scatter %.3f / %.3f px (col / row) "
                     "from frame to frame\n",
                     side, p.measured.x(), p.measured.y());
      }
    }
    if (p.poor) {
      std::fprintf(stderr,
                   "dimerlab track: warning: %s: the footage places the %s sphere to %.2f / "
                   "%.2f px (col / row) at best: too little contrast for sub-pixel work; its "
                   "offset to the centre, estimated on the same footage, may be off by more "
                   "than it states; more light or a larger image of the spheres helps\n",
                   args.input.c_str(), side, p.bound.x(), p.bound.y());
    }
    if (!p.followed) {
      std::fprintf(stderr,
                   "dimerlab track: warning: %s: the %s sphere's centres scatter %.2f / %.2f px "
                   "from frame to frame, more than %.0f times what the footage allows (%.3f / "
                   "%.3f px): it is not followed as a sub-pixel tracker should, and many "
                   "frames may be pixels off; more light, a larger image of the spheres or "
                   "--method centroid/discfit may help\n",
                   args.input.c_str(), side, p.measured.x(), p.measured.y(),
                   kNotFollowedFactor, p.bound.x(), p.bound.y());
    }
  }
}

void ReportLengthScale(const TrackArgs& args, const Calibration& cal) {
  if (std::isnan(args.m_per_px)) {
    const LengthScale& ls = cal.length_scale;
    if (!args.quiet) {
      std::fprintf(stderr,
                   "dimerlab track: scale %.6g m/px from the dimer's length %.3f px (median of %zu "
                   "frames, --ar %g, --diameter %g m); tracked with a sphere radius of %.3f px, "
                   "settled in %zu passes over the first frames\n",
                   cal.m_per_px, cal.length_px, cal.length_frames, args.ar, args.diameter,
                   ls.radius_px, ls.passes.size());
    }
    const double outline = ls.outline_radius_px;
    if (std::abs(ls.radius_px / outline - 1.0) > kOutlineRadiusCheck) {
      std::fprintf(stderr,
                   "dimerlab track: warning: the spheres' outline gives a radius of %.2f px, the "
                   "dimer's length with --ar %g one of %.2f px (%+.0f %%): check --ar (the length "
                   "over the diameter, not the centre distance over it)\n",
                   outline, args.ar, ls.radius_px, 100.0 * (ls.radius_px / outline - 1.0));
    }
    if (!ls.converged) {
      std::fprintf(stderr,
                   "dimerlab track: warning: the radius had not settled to %.2f px after %d "
                   "passes (last %.3f -> %.3f px); rows rest on it\n",
                   kLengthScaleTolPx, int(ls.passes.size()),
                   ls.passes.back().radius_px_used, ls.radius_px);
    }
    return;
  }
  if (!std::isfinite(cal.length_px)) return;
  // Both given: the tracked length says which A_r the scale and diameter imply.
  const double measured = cal.length_px * args.m_per_px / args.diameter + 1.0;
  if (std::abs(measured - args.ar) > kLengthCheckTolerance * (args.ar - 1.0)) {
    std::fprintf(stderr,
                 "dimerlab track: warning: with --m-per-px %g and --diameter %g m the tracked "
                 "length (%.3f px) gives A_r = %.4f, not --ar %g (A_r - 1 %+.1f %%): one of the "
                 "three is off\n",
                 args.m_per_px, args.diameter, cal.length_px, measured, args.ar,
                 100.0 * (measured - args.ar) / (args.ar - 1.0));
  }
}

}  // namespace

void RunTrack(const TrackArgs& args) {
  args.Check();
  SequenceOptions seq = args.sequence;
  seq.tracker.method = ParseMethod(args.method);
  // The plate-contact offset of the template method needs the radius in pixels: from the
  // scale when it is given, else the measured one (which then also sets the scale).
  if (!std::isnan(args.m_per_px) && std::isnan(seq.contact_radius_px)) {
    seq.contact_radius_px = 0.5 * args.diameter / args.m_per_px;
  }
  seq.tracker.polarity = args.polarity == "bright" ? 1 : args.polarity == "dark" ? -1 : 0;
  if (!std::isnan(args.plate_m_per_px)) {
    seq.plate_motion_scale = args.plate_m_per_px / args.m_per_px;
  }
  // Read before any work: a bad calibration file is said at once.
  if (!args.lens.empty()) {
    seq.lens = std::make_shared<const LensCalibration>(ReadLensCalibration(args.lens));
  }
  AtomicOutput out(args.output, args.force);  // refuses an existing output before any work
  auto source = SelectFrames(FrameSource::Open(args.input), ParseFrameRange(args.frames),
                             args.input);
  TrackArgs resolved = args;
  const Recording rec = ResolveFps(source->recording(), &resolved);
  // g in px per frame^2 is this times the radius in px (whichever the film is tracked with).
  seq.gravity_per_radius_px = 2.0 * kGravity / (args.diameter * resolved.fps * resolved.fps);
  // Lossy compression moves edges and smooths the noise the offsets are measured against: on
  // POV-Ray footage exported as H.264 the columns came out up to 3 px off while stating 0.2-0.4
  // px (docs/BENCHMARKS.md, "Compressed video"). Said before the work, and kept in the file.
  if (!rec.info.video_codec.empty() && !LosslessVideoCodec(rec.info.video_codec)) {
    std::fprintf(stderr,
                 "dimerlab: warning: %s: video codec '%s' is taken as lossy: compression moves the "
                 "spheres' edges by tenths of a pixel to pixels, beyond the offsets' stated "
                 "uncertainties; track the camera's own files (.cine) or lossless frames where you "
                 "can\n",
                 args.input.c_str(), rec.info.video_codec.c_str());
  }
  // --ar without --m-per-px: the radius the film is tracked with comes from the dimer's length
  // over its first frames (dimer_length_scale.h); the film's own length then sets the scale.
  LengthScale length_scale;
  if (!std::isnan(args.ar) && std::isnan(args.m_per_px)) {
    if (!args.quiet) {
      std::fprintf(stderr,
                   "dimerlab track: scale from the dimer's length (--ar %g): tracking its first "
                   "%zu frames until the radius settles\n",
                   args.ar, kLengthScaleFrames);
    }
    length_scale = TrackedDimerLengthScale(args, seq);
    if (!length_scale.ok) {
      throw InputError(args.input + ": cannot take the scale from the dimer's length (--ar): " +
                       length_scale.failure + "; pass --m-per-px");
    }
    seq.contact_radius_px = length_scale.radius_px;
    if (!std::isnan(args.plate_m_per_px)) {
      seq.plate_motion_scale =
          args.plate_m_per_px / (0.5 * args.diameter / length_scale.radius_px);
    }
  }
  const SequenceResult r = TrackWithLibraryMessagesCaptured(resolved, seq, *source);
  if (r.frames.empty()) {
    if (!r.complete) throw Interrupted();
    throw InputError(args.input + ": no readable frame (all " +
                     std::to_string(r.skipped.size()) + " were skipped)");
  }
  // A colour camera's film is tracked grey: said, as the file's cine_colour keeps it.
  if (rec.info.known && rec.info.colour != "grey" && !args.quiet) {
    std::fprintf(stderr, "dimerlab track: %s: %s, tracked in grey (%s)\n", args.input.c_str(),
                 rec.info.colour == "mosaic"
                     ? ("a colour sensor's raw Bayer mosaic (CFA " +
                        std::to_string(rec.info.cfa) + ")").c_str()
                     : "interpolated colour (BGR)",
                 rec.info.colour == "mosaic"
                     ? ("the four phases balanced to one grey, " + rec.info.mosaic_balance +
                        "; cells still coloured filtered to (R + 2G + B) / 4 over 3x3").c_str()
                     : "OpenCV's BGR to grey");
  }
  if (r.level_scale.warn) {
    std::fprintf(stderr, "dimerlab: warning: %s\n", r.level_scale.reason.c_str());
  } else if (!r.level_scale.reason.empty() && !args.quiet) {
    std::fprintf(stderr, "dimerlab track: levels: %s\n", r.level_scale.reason.c_str());
  }
  if (r.level_scale.clipped_frames > 0) {
    std::fprintf(stderr,
                 "dimerlab: warning: %zu %s (the first %s) had levels above the %d bits "
                 "taken for the camera and were clipped at the top by the scaling; give the "
                 "camera's bits with --bits (16: as stored)\n",
                 r.level_scale.clipped_frames,
                 r.level_scale.clipped_frames == 1 ? "frame" : "frames",
                 r.level_scale.first_clipped.c_str(), r.level_scale.bits);
  }
  // The choice and its evidence (also in the file); -q keeps stderr empty on success.
  if (!r.method_reason.empty() && !args.quiet) {
    std::fprintf(stderr, "dimerlab track: method %s -> %s (reason: %s)\n", args.method.c_str(),
                 ToString(r.method).c_str(), r.method_reason.c_str());
  }
  // An over-exposed plate: how its rows were found.
  if (r.plate_clip.frames > 0 && !args.quiet) {
    const PlateClip& c = r.plate_clip;
    if (c.level.found()) {
      std::fprintf(stderr,
                   "dimerlab track: plate: over-exposed in %zu frames; its level %.1f +- %.1f grey "
                   "levels above the backdrop and the camera's blur %.2f px (%s), from %zu "
                   "frames with two partly lit rows; %zu rows fitted at them\n",
                   c.frames, c.level.value, c.level.err, c.level.psf_sigma,
                   PsfSource(args, c).c_str(), c.level.used, c.refitted);
    } else {
      std::fprintf(stderr,
                   "dimerlab track: plate: warning: over-exposed in %zu frames, and %zu show two "
                   "partly lit rows (%zu needed to measure its level): a row may be up to the "
                   "covered part of a pixel toward the dark side\n",
                   c.frames, c.level.informative, kClippedLevelMinFrames);
    }
  }
  // Matches that were not the sphere (match_scores.h).
  const size_t by_score = r.scores.dropped[0] + r.scores.dropped[1];
  const size_t by_length = r.scores.dropped_length[0] + r.scores.dropped_length[1];
  if (by_score + by_length > 0 && !args.quiet) {
    std::fprintf(stderr,
                 "dimerlab track: %zu sphere matches dropped as not the sphere: %zu scoring far "
                 "below their sphere's median, %zu giving the dimer another length than its "
                 "%.2f px (a sphere at the frame's edge, or beside itself); those spheres are "
                 "not found there\n",
                 by_score + by_length, by_score, by_length, r.scores.length_px);
  }
  // The lens's distortion, taken out of every frame (lens_undistortion.h).
  if (r.lens && !args.quiet) {
    std::fprintf(stderr,
                 "dimerlab track: lens: every frame undistorted with %s (%zu coefficients, k1 "
                 "%.4g); it moves pixels by up to %.2f px in these frames\n",
                 r.lens->path.c_str(), r.lens->distortion.size(), r.lens->distortion[0],
                 r.lens_max_shift_px);
  }
  // Stuck pixels of the sensor, replaced before tracking (defect_pixels.h).
  if (!r.defects.at.empty() && !args.quiet) {
    std::fprintf(stderr,
                 "dimerlab track: %zu stuck pixels of the sensor (standing out from all their "
                 "neighbours in %zu frames or more of %zu) replaced in every frame by the mean of "
                 "their sound opposite neighbours (/stuck_pixels)\n",
                 r.defects.at.size(),
                 size_t(std::ceil(kDefectFrameFraction * double(r.defects.frames))),
                 r.defects.frames);
  } else if (!r.defects.reason.empty() && !args.quiet) {
    std::fprintf(stderr, "dimerlab track: note: %s\n", r.defects.reason.c_str());
  }
  // A camera not level (or a tilted plate): the rows are read under each sphere and the metres
  // run along the plate.
  if (r.plate_slope.applied && !args.quiet) {
    std::fprintf(stderr,
                 "dimerlab track: plate: the edge slopes by %.5f +- %.5f px per px (%s): the plate "
                 "is read under each sphere, and x runs along it, z along its normal\n",
                 r.plate_slope.value, r.plate_slope.err, r.plate_slope.reason.c_str());
  }
  // The plate's top in view: its row is the contact line found from the mirror images.
  if (r.plate_shift.applied && !args.quiet) {
    std::fprintf(stderr, "dimerlab track: plate: %s\n", r.plate_shift.reason.c_str());
  }
  if (r.plate_scale.given && !args.quiet) {
    std::fprintf(stderr,
                 "dimerlab track: plate: the edge's motion scaled by %.6g to the dimer's plane "
                 "(--plate-m-per-px %.6g / --m-per-px %.6g), about edge row %.3f\n",
                 r.plate_scale.scale, args.plate_m_per_px, args.m_per_px, r.plate_scale.edge_ref);
  } else if (r.plate_shift.applied && !args.quiet) {
    if (r.plate_scale.fitted) {
      std::fprintf(stderr,
                   "dimerlab track: plate: the contact line moves %.3f +- %.3f px per px of the "
                   "visible edge (the %s sphere resting, %zu frames)\n",
                   r.plate_scale.scale, r.plate_scale.err,
                   r.plate_scale.sphere == 0 ? "left" : "right", r.plate_scale.frames);
    } else {
      std::fprintf(stderr,
                   "dimerlab track: plate: warning: the edge's motion is taken as the contact "
                   "line's (fewer than %zu resting frames, or the plate moved under %.1f px in "
                   "them); the far edge of a deep plate moves less than the contact line\n",
                   kMinScaleFrames, kMinScaleSpreadPx);
    }
  }
  if (r.method == Method::kTemplate && !args.quiet) {
    for (int k = 0; k < 2; ++k) {
      const OffsetEstimate &c = r.offsets.col[k], &w = r.offsets.row[k];
      std::fprintf(stderr,
                   "dimerlab track: %s sphere: offset to the centre col %+.3f +- %.3f px (%s), "
                   "row %+.3f +- %.3f px (%s, %zu frames)\n",
                   k == 0 ? "left" : "right", c.value, c.err, c.source.c_str(), w.value, w.err,
                   w.source.c_str(), w.n);
    }
    // An offset is a constant shift of every frame's centre: it biases absolute positions (a
    // sphere's height above the plate, the tilt) but not velocities, slip or drift. Say so where
    // its uncertainty exceeds the 0.1 px the tracker aims at.
    constexpr double kOffsetWarnPx = 0.1;
    for (int k = 0; k < 2; ++k) {
      for (int axis = 0; axis < 2; ++axis) {
        const OffsetEstimate& e = axis == 0 ? r.offsets.col[k] : r.offsets.row[k];
        if (std::isnan(e.err)) {  // source "none": nothing on the footage gave it
          std::fprintf(stderr,
                       "dimerlab track: warning: the %s sphere's %s offset could not be "
                       "estimated (no outline, symmetry or plate contact to measure it on): its "
                       "absolute position is the learnt appearance's reference point, possibly "
                       "pixels off; its motion is not\n",
                       k == 0 ? "left" : "right", axis == 0 ? "column" : "row");
          continue;
        }
        if (!(e.err > kOffsetWarnPx)) continue;
        std::fprintf(stderr,
                     "dimerlab track: warning: the %s sphere's %s is uncertain by %.2f px (%s): "
                     "its absolute position may be off by as much; its motion is not\n",
                     k == 0 ? "left" : "right", axis == 0 ? "column" : "row", e.err,
                     e.source.c_str());
      }
    }
    // Rows rest on plate - R: a radius error is a row bias, so say where R came from.
    if (r.radius_source == "outline") {
      std::fprintf(stderr,
                   "dimerlab track: sphere radius %.2f px from the spheres' outline (no "
                   "--m-per-px); on mirror spheres it can be ~0.5 px short, which lowers every "
                   "row by as much and enlarges the scale by ~2 %%: pass --m-per-px when the "
                   "scale is known, or --ar with the dimer's aspect ratio\n",
                   r.appearance[0].radius_px);
    } else if (r.radius_source == "silhouette" && r.method == Method::kTemplate &&
               !r.method_reason.empty() && r.appearance[0].valid()) {
      std::fprintf(stderr,
                   "dimerlab track: warning: sphere radius %.2f px from the silhouette methods, "
                   "not the outline (the two spheres' outlines disagree); rows and the scale "
                   "rest on it: pass --m-per-px, or --ar with the dimer's aspect ratio\n",
                   r.appearance[0].radius_px);
    }
  }
  ReportPrecision(args, r);
  const Calibration cal = Calibrate(args, r, length_scale);
  if (!std::isnan(args.ar)) ReportLengthScale(args, cal);
  WriteTrackFile(out.temp_path(), resolved, r, cal, rec);
  out.Commit();
  // The one-line summary every subcommand ends with (stdout; -q silences progress only).
  size_t both = 0;
  for (const auto& f : r.frames) both += f.found[0] && f.found[1];
  std::printf("%s: %zu frames tracked, %zu skipped, both spheres found in %zu, %s, %.4g m/px%s\n",
              (args.output_label.empty() ? args.output : args.output_label).c_str(), r.frames.size(),
              r.skipped.size(), both, ToString(r.method).c_str(),
              cal.m_per_px, r.complete ? "" : " (interrupted: partial)");
  if (!r.complete) throw Interrupted();
}

}  // namespace dimer::tracking
