#include "tracking/track_sequence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <future>
#include <optional>
#include <thread>

#include "common/error.h"
#include "common/interrupt.h"
#include "common/median.h"
#include "tracking/cut_spheres.h"
#include "tracking/length_relearn.h"
#include "tracking/method_trial.h"
#include "tracking/sphere/precision_bound.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
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
  // Frames at the chunk's start and end that missed a sphere, indices in `frames`: placed across
  // the seams with the neighbouring chunks (cut_spheres.h).
  std::vector<HeldFrame> head, tail;
};

// The follower's options with what the first readable frame fixed for every chunk.
FollowerOptions WithReference(FollowerOptions o, const Reference& ref) {
  o.polarity = ref.polarity;
  o.radius_px = ref.radius_px;
  return o;
}

std::string SizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// A frame as the tracker measures it: the sensor's stuck pixels replaced first (they are the
// sensor's, and undistortion would smear them), then the lens's distortion taken out.
cv::Mat CleanFrame(const cv::Mat& image, const DefectPixels& defects,
                   const LensUndistortion* lens) {
  cv::Mat repaired = RepairDefectPixels(image, defects);
  return lens ? lens->Apply(repaired) : repaired;
}

ChunkResult TrackChunk(const FrameSource& source, size_t start, size_t count,
                       std::vector<Frame> prefetched, const FollowerOptions& opts,
                       const Reference& ref, const DefectPixels& defects,
                       const LensUndistortion* lens) {
  ChunkResult out;
  FrameFollower tracker(WithReference(opts, ref));
  ChunkCuts cuts;  // frames held back for the spheres cut by the frame's edge
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
    cv::Mat clean = CleanFrame(f.image, defects, lens);
    out.frames.push_back(tracker.Process(clean, f.index));
    out.names.push_back(f.name);
    cuts.Add(tracker, std::move(clean), &out.frames);
  }
  out.head = std::move(cuts.head);
  out.tail = cuts.Tail(out.frames.size());
  return out;
}

Reference MakeReference(const cv::Mat& image, const FollowerOptions& opts) {
  Reference ref;
  ref.width = image.cols;
  ref.height = image.rows;
  FrameFollower probe(opts);
  probe.Process(image, 0);
  ref.polarity = probe.polarity();
  ref.radius_px = probe.radius_px();
  return ref;
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

// A frame of the chunk being launched, by its index in the chunk (the decoded-ahead buffer of a
// sequential source, else read from the source).
using FrameAt = std::function<Frame(size_t)>;

// What the first readable frame fixes for every chunk, and what the chunks share by reference
// while they run (kept in place until the last one is joined).
struct Film {
  Reference ref;
  FollowerOptions chunk_opts;             // the tracker's options for every chunk
  SequenceMethod prepared;               // the method chosen (and learnt) for the film
  cv::Mat first_frame;                   // the first readable frame, stuck pixels replaced
  std::optional<LensUndistortion> lens;  // made for the first readable frame's size
  const LensUndistortion* undistort = nullptr;  // &*lens once made, for CleanFrame
};

// Stage "open": the first readable frame of `count` fixes size, polarity and radius. Frames
// spread over the chunk give the sensor's stuck pixels (defect_pixels.h) and then, on the frames
// with those replaced, the plate edge's slope (plate_slope.h). False: no readable frame there.
bool OpenFilm(const FrameAt& frame_at, size_t count, const SequenceOptions& options, Film* film,
              SequenceResult* result) {
  cv::Mat first;
  for (size_t j = 0; j < count && first.empty(); ++j) {
    Frame f = frame_at(j);
    if (f.error.empty()) first = f.image;
  }
  if (first.empty()) return false;
  std::vector<cv::Mat> probe;
  for (size_t j = 0; j < kSlopeFrames; ++j) {
    const size_t i = j * count / kSlopeFrames;
    if (j > 0 && i == (j - 1) * count / kSlopeFrames) continue;
    Frame f = frame_at(i);
    if (f.error.empty() && f.image.size() == first.size()) probe.push_back(f.image);
  }
  result->defects = FindDefectPixels(probe);
  if (options.lens) {
    film->lens.emplace(*options.lens, first.size());
    result->lens = options.lens;
    result->lens_max_shift_px = film->lens->max_shift_px();
    film->undistort = &*film->lens;
  }
  for (cv::Mat& p : probe) p = CleanFrame(p, result->defects, film->undistort);
  film->first_frame = CleanFrame(first, result->defects, film->undistort);
  film->ref = MakeReference(film->first_frame, options.follower);
  result->plate_slope = EstimatePlateSlope(probe, film->ref.polarity);
  film->chunk_opts.plate_slope = result->plate_slope.value;
  return true;
}

// The median distance of the two appearances' reference points over the learning frames that
// registered both, each moved by its `offset` (NaN: none).
double ReferenceLength(const std::array<LearntSphere, 2>& learnt,
                       const std::array<Eigen::Vector2d, 2>& offset = {Eigen::Vector2d(0, 0),
                                                                     Eigen::Vector2d(0, 0)}) {
  std::vector<double> d;
  for (size_t i = 0; i < learnt[0].samples.size() && i < learnt[0].registered.size(); ++i) {
    const auto& s1 = learnt[1].samples;
    const auto at = std::find(s1.begin(), s1.end(), learnt[0].samples[i]);
    const size_t j = size_t(at - s1.begin());
    if (at == s1.end() || j >= learnt[1].registered.size()) continue;
    d.push_back((learnt[1].registered[j] + offset[1] - learnt[0].registered[i] - offset[0]).norm());
  }
  return d.empty() ? kNaN : MedianOf(d);
}

// The film's first kTrialFrames frames (those that decode at the film's size), cleaned as
// every frame is: the run auto's trials follow (method_trial.h).
std::vector<Frame> TrialRun(const FrameAt& frame_at, size_t available, const Film& film,
                            const SequenceResult& result) {
  std::vector<Frame> run;
  for (size_t i = 0; i < std::min(available, kTrialFrames); ++i) {
    Frame f = frame_at(i);
    if (!f.error.empty() || f.image.cols != film.ref.width || f.image.rows != film.ref.height) {
      continue;
    }
    f.image = CleanFrame(f.image, result.defects, film.undistort);
    run.push_back(std::move(f));
  }
  return run;
}

// `auto`'s trial where the template was learnt (method_trial.h, TryMethods): the method with the
// lower noise is run.
void TakeTheTrial(const MethodTrial& trial, Film* film, SequenceResult* result) {
  film->prepared.choice.reason += trial.reason;
  result->method_trial = trial.candidates;
  if (trial.chosen != Method::kCentroid) return;
  film->prepared.choice.method = Method::kCentroid;
  film->chunk_opts.method = Method::kCentroid;
  // The learnt appearances still place a sphere cut by the frame's edge, moved to the centroid's
  // centre by their silhouette offsets (cut_spheres.h).
  FollowerOptions& c = film->chunk_opts;
  c.cut_appearance = c.appearance;
  for (int k = 0; k < 2; ++k) {
    const OffsetEstimate col = SilhouetteOffset(film->prepared.learnt[k], 0);
    const OffsetEstimate row = SilhouetteOffset(film->prepared.learnt[k], 1);
    c.cut_offset[k] = {col.value, row.value};
    c.cut_offset_err[k] = {col.err, row.err};
    if (!c.cut_offset[k].allFinite() || !c.cut_offset_err[k].allFinite()) c.cut_appearance.reset();
  }
  c.dimer_length_px = ReferenceLength(film->prepared.learnt, c.cut_offset);
  c.appearance.reset();
}

// `--method auto` on clean silhouettes: the centroid and discfit tried on the film's first
// consecutive frames (method_trial.h, TrySilhouetteMethods); discfit is run where it shows the
// lower noise by the trial's margin.
void TryTheDiscFit(const FrameAt& frame_at, size_t available, int threads, Film* film,
                   SequenceResult* result) {
  const MethodTrial trial =
      TrySilhouetteMethods(TrialRun(frame_at, available, *film, *result),
                           WithReference(film->chunk_opts, film->ref), threads);
  film->prepared.choice.reason += trial.reason;
  result->method_trial = trial.candidates;
  film->prepared.choice.method = trial.chosen;
  film->chunk_opts.method = trial.chosen;
}

// Without the scale the learning is framed by the first frame's radius, its silhouette's
// distance transform, which the spheres' outline measured over the learning frames can
// contradict by pixels: 26.0 px against the outline's 23.62 (truth 23.75) on the ruler's
// 100-frame film, whose spheres' blobs join the ruler's band. The template's frame (R + 4 px)
// and the plate's arbitration (a sphere's lowest point) move with it, and there most learning
// frames took the ruler's edge for the plate, both spheres' rows held 7-12 px off. Where the two
// differ by more than kRelearnRadiusFraction, the learning is made again at the outline's
// radius, held as a given scale's would be (povray.long_ruler, without the scale); kept where
// it learns the template again.
constexpr double kRelearnRadiusFraction = 0.05;

// True where it did: `reference`'s radius is then the outline's, held as a scale's.
bool LearnAtTheOutlinesRadius(const std::vector<Frame>& learning, FollowerOptions* reference,
                              Method requested, const LearnOptions& learn,
                              SequenceMethod* prepared) {
  if (!prepared->radius_from_outline || !prepared->appearance) return false;
  const double outline = (*prepared->appearance)[0].radius_px;
  const double first = reference->radius_px;
  if (!(std::abs(outline - first) > kRelearnRadiusFraction * outline)) return false;
  FollowerOptions at_outline = *reference;
  at_outline.radius_px = outline;
  SequenceMethod again = PrepareSequenceMethod(learning, at_outline, requested, true, learn);
  if (again.choice.method != Method::kTemplate || !again.appearance) return false;
  again.radius_from_outline = true;
  char clause[200];
  std::snprintf(clause, sizeof clause,
                "; learnt again at the outline's radius %.2f px (the first frame's silhouette "
                "gave %.2f px)",
                outline, first);
  again.choice.reason += clause;
  *prepared = std::move(again);
  *reference = at_outline;
  return true;
}

// Stage "choose method, learn" (template and auto): the learning frames, `learning_at(i)` for i
// in LearningIndices(available), by index only (sequential sources: within the first chunk,
// which is decoded ahead anyway); the method and appearances are fixed before any chunk runs.
void LearnFilm(const FrameAt& learning_at, size_t available, const SequenceOptions& options,
               int threads, Film* film, SequenceResult* result) {
  std::vector<Frame> learning;
  for (size_t i : LearningIndices(available)) {
    Frame f = learning_at(i);
    if (f.error.empty() && f.image.cols == film->ref.width && f.image.rows == film->ref.height) {
      f.image = CleanFrame(f.image, result->defects, film->undistort);
      learning.push_back(std::move(f));
    }
  }
  FollowerOptions reference = options.follower;
  reference.polarity = film->ref.polarity;
  reference.plate_slope = film->chunk_opts.plate_slope;
  // The template is sized by the true radius when the scale is known (the silhouette
  // radius of a front-lit steel sphere can be pixels short).
  reference.radius_px = std::isfinite(options.contact_radius_px) ? options.contact_radius_px
                                                                 : film->ref.radius_px;
  const LearnOptions learn{options.learn_passes, threads, film->chunk_opts.plate_slope,
                           options.jackknife_groups, options.seed_agreement_px};
  bool radius_known = std::isfinite(options.contact_radius_px);
  film->prepared = PrepareSequenceMethod(learning, reference, options.follower.method,
                                         radius_known, learn);
  if (!radius_known) {
    radius_known = LearnAtTheOutlinesRadius(learning, &reference, options.follower.method, learn,
                                            &film->prepared);
  }
  // The template's radius (the scale's, or its outline's) is every frame's radius, which
  // calibrates the scale when it is not given.
  if (film->prepared.appearance) {
    film->ref.radius_px = (*film->prepared.appearance)[0].radius_px;
    result->radius_source = std::isfinite(options.contact_radius_px) ? "scale"
                            : film->prepared.radius_from_outline     ? "outline"
                                                                     : "silhouette";
  }
  film->chunk_opts.method = film->prepared.choice.method;
  film->chunk_opts.appearance = film->prepared.appearance;
  film->chunk_opts.dimer_length_px = ReferenceLength(film->prepared.learnt);
  if (film->chunk_opts.method == Method::kTemplate) {
    // Stage "trial": the learnt appearances followed over the film's first consecutive frames,
    // refereed by the dimer's length (length_relearn.h) and, with auto, beside the silhouette
    // locator (method_trial.h); auto's trial measures the length, so that a film whose length
    // holds is followed there once.
    const std::vector<Frame> trial = TrialRun(learning_at, available, *film, *result);
    const bool try_methods = options.follower.method == Method::kAuto;
    auto try_them = [&] {
      return TryMethods(trial, WithReference(film->chunk_opts, film->ref), threads);
    };
    std::optional<MethodTrial> tried;
    if (try_methods) tried = try_them();
    film->prepared.choice.reason += RefereeTheLearningByTheLength(
        learning, trial, reference, WithReference(film->chunk_opts, film->ref),
        options.follower.method, radius_known, learn,
        tried ? &tried->candidates[0].constancy : nullptr, &film->prepared);
    if (film->prepared.appearance != film->chunk_opts.appearance) {
      film->chunk_opts.appearance = film->prepared.appearance;
      film->chunk_opts.dimer_length_px = ReferenceLength(film->prepared.learnt);
      if (try_methods) tried = try_them();
    }
    if (tried) TakeTheTrial(*tried, film, result);
  } else if (options.follower.method == Method::kAuto && film->prepared.choice.silhouettes &&
             film->chunk_opts.method == Method::kCentroid) {
    TryTheDiscFit(learning_at, available, threads, film, result);
  }
}

// Stage "contact line": on a polished plate (or with the plate edge's own scale given), the
// edge to the contact line: a constant at the learning frames' edge row (a polished plate's
// mirror images), and the edge's motion scaled to the contact line's, by the ratio of scales the
// user gave or else by a resting sphere (plate_contact.h).
void PlaceContactLine(const SequenceMethod& prepared, const SequenceOptions& options,
                      SequenceResult* result) {
  result->plate_shift = prepared.plate_shift;
  const bool scale_given = std::isfinite(options.plate_motion_scale);
  if (!prepared.plate_shift.applied && !scale_given) return;
  std::vector<double> edge;
  std::array<std::vector<double>, 2> rows;
  for (const FrameTrack& f : result->frames) {
    edge.push_back(f.plate_row);
    for (int k = 0; k < 2; ++k) rows[k].push_back(f.whole(k) ? f.centre[k].y() : std::nan(""));
  }
  result->plate_scale =
      scale_given ? GivenPlateMotionScale(options.plate_motion_scale, edge, prepared.plate_shift)
                  : FitPlateMotionScale(edge, rows, prepared.plate_shift);
  for (FrameTrack& f : result->frames) {
    f.plate_row = ContactRow(prepared.plate_shift, result->plate_scale, f.plate_row);
  }
}

// Stage "offsets" (template): the first frame's noise and each sphere's bound, then the offsets
// from each appearance's reference point to the sphere's centre, applied to every frame.
void PlaceOffsets(const Film& film, const SequenceOptions& options, SequenceResult* result) {
  if (!film.chunk_opts.appearance) return;
  result->appearance = *film.chunk_opts.appearance;
  result->frame_noise = FrameNoiseSigma(film.first_frame);
  for (int k = 0; k < 2; ++k) {
    result->precision_bound[k] = TranslationBound(result->appearance[k], result->frame_noise);
  }
  result->offsets = EstimateOffsets(film.prepared, result->frames, film.ref.radius_px,
                                    options.gravity_per_radius_px * film.ref.radius_px);
  ApplyOffsets(result->offsets, &result->frames);
}

// Stage "held rows": each sphere's rows against the plate under it and a free fall of
// `gravity_px` px per frame^2 (held_rows.h).
void JudgeHeldRows(double gravity_px, SequenceResult* result) {
  for (int k = 0; k < 2; ++k) {
    std::vector<double> rows, plate;
    for (const FrameTrack& f : result->frames) {
      rows.push_back(f.whole(k) ? f.centre[k].y() : std::nan(""));
      plate.push_back(f.PlateRowAt(f.centre[k].x()));
    }
    result->held_rows[k] = FindHeldRows(rows, plate, gravity_px);
  }
}

// The stages after the last chunk, in order.
void FinishFilm(const Film& film, const SequenceOptions& options, bool sequence_level,
                SequenceResult* result) {
  if (InterruptRequested()) result->complete = false;
  result->method = sequence_level ? film.prepared.choice.method : options.follower.method;
  result->method_reason = film.prepared.choice.reason;
  result->detection_agreement = film.prepared.agreement;
  result->relearnt = film.prepared.relearnt;
  result->plate_agreement = film.prepared.plate_agreement;
  result->relearnt_by_plate = film.prepared.relearnt_by_plate;
  result->relearnt_by_length = film.prepared.relearnt_by_length;
  // Before anything reads the found spheres (the plate's motion scale, the offsets): the chunks'
  // names made the film's, then the matches that are not a sphere dropped.
  result->dimer_names = NameSpheresByTheDimer(&result->frames);
  result->scores = DropOutlyingMatches(&result->frames);
  StateCutUncertainty(&result->frames);
  result->plate_clip = RefitClippedPlate(options.follower.psf_sigma_px,
                                         options.follower.fit_psf_sigma, &result->frames);
  PlaceContactLine(film.prepared, options, result);
  PlaceOffsets(film, options, result);
  result->precision = MeasurePrecision(result->frames, result->precision_bound);
  JudgeHeldRows(options.gravity_per_radius_px * film.ref.radius_px, result);
  result->length = JudgeLengthConstancy(result->frames);
  result->polarity = film.ref.polarity;
  result->width = film.ref.width;
  result->height = film.ref.height;
}

// What joining the chunks keeps between them.
struct Seams {
  std::optional<FrameFollower> follower;  // places cut spheres across the chunks' seams
  std::vector<HeldFrame> tail;            // the last chunk joined's (cut_spheres.h)
};

// Stage "join": a chunk's frames appended to the film's, and the spheres cut by the frame's edge
// that neither chunk could place, placed across the seam between them.
void JoinChunk(const Film& film, ChunkResult* chunk, Seams* seams, SequenceResult* result) {
  const size_t seam = result->frames.size();
  result->frames.insert(result->frames.end(), chunk->frames.begin(), chunk->frames.end());
  for (HeldFrame& h : chunk->head) h.index += seam;
  for (HeldFrame& h : chunk->tail) h.index += seam;
  if (seam > 0) {
    if (!seams->follower) seams->follower.emplace(WithReference(film.chunk_opts, film.ref));
    PlaceAcrossSeam(*seams->follower, seams->tail, chunk->head, &result->frames, seam);
  }
  seams->tail = std::move(chunk->tail);
  result->names.insert(result->names.end(), chunk->names.begin(), chunk->names.end());
  if (chunk->interrupted) result->complete = false;
}

// The frames of `source` as they are (levels already scaled): opened, learnt, followed in
// chunks of options.chunk_frames on `threads` workers, joined, finished.
SequenceResult TrackFramesAsGiven(FrameSource& source, const SequenceOptions& options,
                                  const std::function<void(size_t)>& on_progress,
                                  const std::function<void(const SkippedFrame&)>& on_skip) {
  const int threads = options.threads > 0 ? options.threads
                                          : int(std::max(1u, std::thread::hardware_concurrency()));
  SequenceResult result;
  Film film;
  film.chunk_opts = options.follower;
  bool have_ref = false;
  size_t next = 0;
  bool exhausted = false;
  const bool sequence_level = options.follower.method == Method::kTemplate ||
                              options.follower.method == Method::kAuto;
  std::deque<std::future<ChunkResult>> inflight;
  Seams seams;
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
    if (!have_ref) {
      const FrameAt in_chunk = [&](size_t j) {
        return buffer.empty() ? source.Read(next + j) : buffer[j];
      };
      have_ref = OpenFilm(in_chunk, count, options, &film, &result);
      if (have_ref && sequence_level) {
        const FrameAt learning_at = [&](size_t i) {
          return buffer.empty() ? source.Read(i) : buffer[i];
        };
        LearnFilm(learning_at, buffer.empty() ? source.size() : buffer.size(), options, threads,
                  &film, &result);
      }
    }
    inflight.push_back(std::async(std::launch::async, TrackChunk, std::cref(source), next, count,
                                  std::move(buffer), film.chunk_opts, film.ref,
                                  std::cref(result.defects), film.undistort));
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
    JoinChunk(film, &chunk, &seams, &result);
    if (on_progress) on_progress(result.frames.size() + result.skipped.size());
  }
  FinishFilm(film, options, sequence_level, &result);
  return result;
}

}  // namespace

void SequenceOptions::Check() const {
  follower.Check();
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

SequenceResult TrackSequence(FrameSource& source, const SequenceOptions& options,
                             const std::function<void(size_t)>& on_progress,
                             const std::function<void(const SkippedFrame&)>& on_skip) {
  options.Check();
  // Stage "levels": a 10- or 12-bit camera's 16-bit frames, scaled to the range the levels are
  // fractions of (level_scale.h); positions do not change with a gain.
  const LevelScale scale = ChooseLevelScale(source, options.camera_bits);
  SequenceResult result;
  if (scale.factor != 1) {
    const auto scaled = ScaledLevels(source, scale.factor);
    result = TrackFramesAsGiven(*scaled, options, on_progress, on_skip);
    result.level_scale = scale;
    result.level_scale.clipped_frames = scaled->clipped_frames();
    result.level_scale.first_clipped = scaled->first_clipped();
  } else {
    result = TrackFramesAsGiven(source, options, on_progress, on_skip);
    result.level_scale = scale;
  }
  return result;
}

}  // namespace dimer::tracking
