#include "tracking/learn_method.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tracking/detection_agreement.h"
#include "tracking/plate_agreement.h"
#include "tracking/plate_consensus.h"
#include "tracking/sphere/appearance_mismatch.h"
#include "tracking/sphere/clipped_highlights.h"
#include "tracking/sphere/highlight_seed.h"
#include "tracking/sphere/impact_vertex.h"
#include "tracking/sphere/measure_still_background.h"
#include "common/parallel_for.h"
#include "tracking/plate/plate_edge.h"

namespace dimer::tracking {
namespace {

// Fewer learning frames than this with both spheres (seeded), and nothing is learnt.
constexpr size_t kMinSeededFrames = 3;

// The learning frames tracked by the centroid, each acquired afresh (the learning frames are
// far apart): the probes for the choice of method, the samples to learn from, and which
// spheres show a clean silhouette.
struct Probes {
  std::vector<FrameTrack> tracks;
  std::vector<LearningSample> samples;
  std::vector<std::array<bool, 2>> clean;
};

Probes ProbeLearningFrames(const std::vector<Frame>& learning, const FollowerOptions& reference,
                           int threads) {
  Probes p;
  p.tracks.resize(learning.size());
  p.samples.resize(learning.size());
  p.clean.resize(learning.size());
  FollowerOptions o = reference;
  o.method = Method::kCentroid;
  o.appearance.reset();
  ParallelFor(learning.size(), threads, [&](size_t i) {
    const Frame& f = learning[i];
    FrameFollower t(o);
    const FrameTrack& probe = p.tracks[i] = t.Process(f.image, f.index);
    LearningSample& s = p.samples[i];
    s.image = f.image;
    s.plate_row = probe.plate_row;
    s.plate_col = probe.plate_col;
    s.plate_slope = probe.plate_slope;
    s.found = probe.found;
    s.centre = probe.centre;
    std::array<bool, 2>& c = p.clean[i];
    for (int k = 0; k < 2; ++k) {
      const double plate = s.PlateRowAt(s.centre[k].x());
      if (s.found[0] && s.found[1]) {
        c[k] = CleanSilhouette(f.image, s.centre[k], reference.radius_px, s.centre[1 - k], plate);
      } else if (s.found[k]) {
        c[k] = CleanSilhouette(f.image, s.centre[k], reference.radius_px, s.centre[k], plate);
      }
    }
  });
  return p;
}

// The learning frames' plate rows made one plate's (plate_consensus.h); returns what is added
// to the method's reason ("" where none was moved).
std::string OnePlateThroughTheFilm(double radius_px, std::vector<LearningSample>* samples) {
  const size_t moved = KeepOnePlate(radius_px, samples);
  if (moved == 0) return "";
  char clause[160];
  std::snprintf(clause, sizeof clause,
                "; in %zu learning frames another edge was taken for the plate, which was "
                "measured again near the others' row",
                moved);
  return clause;
}

// Rough centres from the highlights where the silhouette methods give both spheres in fewer
// than half the learning frames: at a lower gain front-lit steel shows parts of its outline
// in some frames, and a mean of those few (6 of 20 at 0.7 of front_point's levels) put the
// columns 0.18 px off; the highlights seed every frame there (see
// povray.lower_levels). The film's seeds are of one kind: a highlight
// stands off the centre by as much as 12 px (the one-sided light), farther than the learning's
// search, so silhouette and highlight seeds are not mixed. The highlights are taken where they
// agree in more frames than the silhouettes give pairs. Returns what is added to the method's
// reason ("" when the silhouettes are kept). With `always`, the highlights are taken wherever
// they agree in enough frames, whatever the silhouettes give (RelearnHeldSpheres).
std::string SeedFromHighlights(double radius_px, const LearnOptions& learn,
                               std::vector<LearningSample>* samples, bool always = false) {
  size_t seeded = 0, from_highlights = 0;
  for (const LearningSample& s : *samples) seeded += s.found[0] && s.found[1];
  if (!always && !(2 * seeded < samples->size() || seeded < kMinSeededFrames)) return "";
  std::vector<LearningSample> lines;
  std::vector<std::vector<HighlightBlob>> blobs;
  for (const LearningSample& s : *samples) {
    // Where the probe found no plate, the coarse row at the frame's centre column.
    LearningSample line = s;
    if (!std::isfinite(s.plate_row)) {
      line.plate_row = FindPlateRowCoarse(s.image, s.plate_slope);
      line.plate_col = 0.5 * (s.image.cols - 1);
    }
    // Above the plate everywhere: its highest point where it slopes.
    const double highest = std::min(line.PlateRowAt(0), line.PlateRowAt(s.image.cols - 1));
    lines.push_back(line);
    blobs.push_back(FindHighlightBlobs(s.image, highest, radius_px));
  }
  // A seed farther off than the learning's search is averaged in where it is; a frame whose
  // two seeds are not a dimer's length apart has one of them off (see
  // SeedFilm.FramesWhoseSeedsAreNotADimersLengthApartAreMarked), and is left out.
  const double agreement =
      learn.seed_agreement_px > 0 ? learn.seed_agreement_px : 2.0 * LearnSearchPx(radius_px);
  const HighlightSeeds seeds = SeedFilm(blobs, radius_px, agreement, kMinSeededFrames);
  if (always ? seeds.agreeing < kMinSeededFrames : seeds.agreeing <= seeded) return "";
  size_t left_out = 0;
  for (size_t i = 0; i < samples->size(); ++i) {
    LearningSample& s = (*samples)[i];
    if (!seeds.seeded[i] || !seeds.agrees[i]) {
      left_out += seeds.seeded[i];
      // Not learnt from: no silhouette pair among the highlight seeds. A single sphere
      // found stays for the plate's contact line (EstimatePlateShift).
      if (s.found[0] && s.found[1]) s.found = {false, false};
      continue;
    }
    s.centre = seeds.seeds[i];
    s.found = {true, true};
    s.plate_row = lines[i].plate_row;
    s.plate_col = lines[i].plate_col;
    ++from_highlights;
  }
  char spread[320];
  std::snprintf(spread, sizeof spread,
                " (%s: %zu a dimer's length apart within %.0f px, %zu by the %s; %zu left "
                "out; the silhouettes gave both spheres in %zu)",
                seeds.by_mass ? "weighed" : "split at the widest gap", seeds.agreeing,
                agreement, seeds.other_agreeing, seeds.by_mass ? "widest gap" : "weighed",
                left_out, seeded);
  return "; rough centres of " + std::to_string(from_highlights) +
         " learning frames from the highlights" + spread;
}

// A sphere whose learnt positions the referee finds not moving with its detections
// (detection_agreement.h) is held by something that stands still behind it: on POV-Ray
// ruler_above_plate the hopping sphere's rows stayed on the ruler's edges, 6 px off. Both are
// learnt again from rough centres on the highlights, which move with the spheres, with the
// pixels that stand still behind them left out (LearnOptions::still_background_spread); a held
// sphere takes the new appearance where the referee then passes it (povray.detection_agreement),
// and keeps the old one, its uncertainty widened, where not. Returns what is added to the
// method's reason; `taken[k]` says whether sphere k took it, and `from` holds the samples it was
// then learnt from.
std::string RelearnHeldSpheres(const std::vector<LearningSample>& samples, double radius_px,
                               bool recentre, bool fit_radius, const LearnOptions& learn,
                               std::array<LearntSphere, 2>* learnt, std::array<bool, 2>* taken,
                               std::vector<LearningSample>* from) {
  std::array<bool, 2> held{};
  for (int k = 0; k < 2; ++k) {
    held[k] = !AgreementWithDetections((*learnt)[k]).agrees || learn.relearn_held[size_t(k)];
  }
  if (!held[0] && !held[1]) return "";
  *from = samples;
  const std::string seeded = SeedFromHighlights(radius_px, learn, from, true);
  if (seeded.empty()) return "";
  LearnOptions still = learn;
  still.still_background_spread = kStillBackgroundSpread;
  bool radius_from_outline = false;
  const std::array<LearntSphere, 2> again =
      LearnAppearances(*from, radius_px, recentre, fit_radius, &radius_from_outline, still);
  std::string reason;
  for (int k = 0; k < 2; ++k) {
    if (!held[k] || !again[k].appearance.valid() || !AgreementWithDetections(again[k]).agrees) {
      continue;
    }
    (*learnt)[k] = again[k];
    (*taken)[k] = true;
    reason += std::string("; the ") + (k == 0 ? "left" : "right") +
              " sphere, held by something standing still behind it, learnt again from its "
              "highlights without that";
  }
  return reason.empty() ? "" : reason + seeded;
}

// The appearances `follow` followed on the learning frames, each acquired afresh (they are far
// apart), and each sphere's rows refereed by the plate under it (plate_agreement.h).
std::array<PlateAgreement, 2> FollowedWithThePlate(
    const std::vector<Frame>& learning, const FollowerOptions& reference,
    const std::array<Appearance, 2>& follow, int threads) {
  FollowerOptions o = reference;
  o.method = Method::kTemplate;
  o.appearance = std::make_shared<const std::array<Appearance, 2>>(follow);
  std::vector<FrameTrack> tracks(learning.size());
  ParallelFor(learning.size(), threads, [&](size_t i) {
    FrameFollower t(o);
    tracks[i] = t.Process(learning[i].image, learning[i].index);
  });
  std::array<PlateAgreement, 2> out;
  for (int k = 0; k < 2; ++k) {
    std::vector<double> edge, row;
    for (const FrameTrack& f : tracks) {
      const bool own = f.whole(k) && f.appearance[k] == k;
      edge.push_back(own ? f.PlateRowAt(f.centre[k].x()) : std::nan(""));
      row.push_back(own ? f.centre[k].y() : std::nan(""));
    }
    out[k] = AgreementWithPlate(edge, row);
  }
  return out;
}

// A sphere's registered rows on the learning frames refereed by the plate under it: what
// learning measured already, so a film pays nothing for it where it agrees. `on_plate`: 1 for
// each sample (indexed as `samples`) it rests in.
PlateAgreement RegisteredWithThePlate(const LearntSphere& s,
                                      const std::vector<LearningSample>& samples,
                                      std::vector<uint8_t>* on_plate) {
  std::vector<double> edge, row;
  for (size_t j = 0; j < s.samples.size() && j < s.registered.size(); ++j) {
    edge.push_back(samples[s.samples[j]].PlateRowAt(s.registered[j].x()));
    row.push_back(s.registered[j].y());
  }
  std::vector<uint8_t> resting(edge.size(), 0);
  const PlateAgreement a = AgreementWithPlate(edge, row, &resting);
  on_plate->assign(samples.size(), 0);
  for (size_t j = 0; j < edge.size(); ++j) (*on_plate)[s.samples[j]] = resting[j];
  return a;
}

// A sphere whose rows do not move with the plate it rests on (plate_agreement.h) is held by
// something that stands still behind it: on POV-Ray ruler_above_plate the resting left sphere's
// registered rows moved 0.07 +- 0.03 px per px of the plate's, and its followed ones 0.09 +-
// 0.01. It is learnt again from the same rough centres with the pixels that stand still behind
// it left out (LearnOptions::still_background_spread; its highlights, which RelearnHeldSpheres
// seeds from, put its rows 0.14 px off there) and its rows in the frames where it rests set by
// the plate (LearnOptions::rows_on_plate; registered instead, 0.55 +- 0.04 and rows scattering
// 0.056 px, measured before the cut's margin, kStillBackgroundMarginPx). Both appearances are
// followed on the learning frames, and it takes the new one where its rows move more nearly
// with the plate (povray.detection_agreement; on the ruler 0.83 +- 0.06, its rows' scatter about
// the truth 0.135 -> 0.025 px; the cut's spreads 5-20 gave 0.83-0.90 and 0.021-0.028 px, 3-4
// gave 0.72-0.73 and 0.11-0.12 px). Returns what is added to the method's reason.
// `relearnt_from`: the samples of the spheres RelearnHeldSpheres learnt again.
std::string RelearnHeldByThePlate(const std::vector<Frame>& learning,
                                  const FollowerOptions& reference,
                                  const std::vector<LearningSample>& samples,
                                  const std::vector<LearningSample>& relearnt_from, bool recentre,
                                  bool fit_radius, const LearnOptions& learn,
                                  SequenceMethod* m, std::array<Appearance, 2>* follow) {
  std::array<bool, 2> held{};
  std::array<std::vector<uint8_t>, 2> on_plate;
  for (int k = 0; k < 2; ++k) {
    m->plate_agreement[k] = RegisteredWithThePlate(
        m->learnt[k], m->relearnt[k] ? relearnt_from : samples, &on_plate[k]);
    held[k] = !m->plate_agreement[k].agrees && !m->relearnt[k];
  }
  if (!held[0] && !held[1]) return "";
  // Followed, the rows are told apart more finely than by their registration; a sphere they
  // pass is not held.
  const std::array<PlateAgreement, 2> followed =
      FollowedWithThePlate(learning, reference, *follow, learn.threads);
  for (int k = 0; k < 2; ++k) {
    if (!held[k]) continue;
    m->plate_agreement[k] = followed[k];
    held[k] = !followed[k].agrees;
  }
  if (!held[0] && !held[1]) return "";
  LearnOptions still = learn;
  still.still_background_spread = kStillBackgroundSpread;
  for (int k = 0; k < 2; ++k) {
    if (held[k]) still.rows_on_plate[size_t(k)] = on_plate[k];
  }
  bool radius_from_outline = false;
  const std::array<LearntSphere, 2> again =
      LearnAppearances(samples, reference.radius_px, recentre, fit_radius, &radius_from_outline,
                       still);
  std::string reason;
  for (int k = 0; k < 2; ++k) {
    if (!held[k] || !again[k].appearance.valid()) continue;
    const PlateAgreement& before = followed[k];
    char clause[200];
    std::snprintf(clause, sizeof clause,
                  "; the %s sphere's rows moved %.2f +- %.2f px per px of the plate's over %zu "
                  "resting learning frames",
                  k == 0 ? "left" : "right", before.slope, before.slope_err, before.frames);
    reason += clause;
    std::array<Appearance, 2> candidate = *follow;
    const ClipDecision clip = DecideClippedHighlights(again[k], samples, k, learn.threads);
    candidate[size_t(k)] = clip.appearance;
    const PlateAgreement after =
        FollowedWithThePlate(learning, reference, candidate, learn.threads)[size_t(k)];
    if (!MovesMoreWithThePlate(after, before)) {
      std::snprintf(clause, sizeof clause,
                    "; learnt again without what stands still behind it, %.2f +- %.2f: not "
                    "nearer, the first appearance kept",
                    after.slope, after.slope_err);
      reason += clause;
      continue;
    }
    m->learnt[k] = again[k];
    m->relearnt[k] = true;
    m->relearnt_by_plate[k] = true;
    m->plate_agreement[k] = after;
    (*follow)[size_t(k)] = clip.appearance;
    std::snprintf(clause, sizeof clause,
                  "; learnt again without what stands still behind it, %.2f +- %.2f", after.slope,
                  after.slope_err);
    reason += clause;
  }
  return reason;
}

// A sphere learnt without what stands still behind it is followed without it wherever it goes
// (still_background.h), measured on the learning frames by the centres it was learnt from.
void FollowWithoutStillBackground(const SequenceMethod& m,
                                  const std::vector<LearningSample>& learnt_from,
                                  std::array<Appearance, 2>* follow) {
  if (!m.relearnt[0] && !m.relearnt[1]) return;
  const std::shared_ptr<const StillBackground> still =
      MeasureStillBackground(learnt_from, (*follow)[0].radius_px);
  for (int k = 0; k < 2; ++k) {
    if (m.relearnt[k]) (*follow)[size_t(k)].still = still;
  }
}

// The row offset of the sphere that does not rest, carried over from sphere `ref`'s resting
// contact `from` by registering the two appearances and through their outlines, weighed by how
// alike the two appearances are (CombineRowTransfers; *mismatch: AppearanceMismatch).
OffsetEstimate RowFromTheOther(const SequenceMethod& m, int ref, const OffsetEstimate& from,
                               double* mismatch) {
  const LearntSphere& a = m.learnt[size_t(ref)];
  const LearntSphere& b = m.learnt[size_t(1 - ref)];
  *mismatch = AppearanceMismatch(a, b);
  return CombineRowTransfers(TransferOffset(a.appearance, b.appearance, from, 1),
                             TransferRowByOutline(a, b, from), *mismatch);
}

}  // namespace

std::vector<size_t> LearningIndices(size_t frames) {
  const size_t span = std::min(frames, kLearnSpanFrames);
  const size_t step = std::max<size_t>(1, span / kLearnFrames);
  std::vector<size_t> out;
  for (size_t i = 0; i < span && out.size() < kLearnFrames; i += step) out.push_back(i);
  return out;
}

SequenceMethod PrepareSequenceMethod(const std::vector<Frame>& learning,
                                     const FollowerOptions& reference, Method requested,
                                     bool radius_known, const LearnOptions& learn) {
  SequenceMethod m;
  Probes probes = ProbeLearningFrames(learning, reference, learn.threads);
  std::vector<LearningSample>& samples = probes.samples;
  const std::string replated = OnePlateThroughTheFilm(reference.radius_px, &samples);
  m.choice = ChooseMethod(probes.tracks, probes.clean, requested);
  m.choice.reason += replated;
  if (m.choice.method != Method::kTemplate) {
    m.plate_shift = EstimatePlateShift(samples, reference.radius_px, learn.threads);
    return m;
  }
  m.choice.reason += SeedFromHighlights(reference.radius_px, learn, &samples);
  // Before learning, which frames the templates on the plate contact: the learning frames'
  // plate rows are moved to the contact line where the plate's top is in view (rough centres of
  // highlights-only footage are seeded by now).
  m.plate_shift = EstimatePlateShift(samples, reference.radius_px, learn.threads);
  if (m.plate_shift.applied) {
    for (LearningSample& s : samples) s.plate_row += m.plate_shift.value;
  }
  m.learnt = LearnAppearances(samples, reference.radius_px, !m.choice.silhouettes,
                              !m.choice.silhouettes && !radius_known, &m.radius_from_outline,
                              learn);
  std::vector<LearningSample> relearnt_from;
  if (m.learnt[0].appearance.valid() && m.learnt[1].appearance.valid()) {
    m.choice.reason += RelearnHeldSpheres(samples, reference.radius_px, !m.choice.silhouettes,
                                          !m.choice.silhouettes && !radius_known, learn,
                                          &m.learnt, &m.relearnt, &relearnt_from);
  }
  if (!m.learnt[0].appearance.valid() || !m.learnt[1].appearance.valid()) {
    // Nothing to learn from (fewer than 3 learning frames with both spheres): the silhouette
    // methods are what is left.
    m.choice.method = Method::kCentroid;
    m.choice.reason += "; too few learning frames with both spheres to learn an appearance, "
                       "centroid instead";
    return m;
  }
  // The contact fit's discs have the sphere's radius: without the scale, the one used above was
  // the silhouette methods' (pixels short on steel), and the line came out 0.5 px low on the
  // POV-Ray mirror plate. Measured again with the outline's radius; the templates framed on the
  // first estimate keep their framing (the offsets are estimated later, on the final rows).
  if (m.radius_from_outline && m.plate_shift.fits >= kMinContactFits) {
    if (m.plate_shift.applied) {
      for (LearningSample& s : samples) s.plate_row -= m.plate_shift.value;
    }
    m.plate_shift = EstimatePlateShift(samples, m.learnt[0].appearance.radius_px, learn.threads);
  }
  // Following leaves a sphere's clipped highlights out where the learning frames show that they
  // lock its position to the pixel grid (clipped_highlights.h); the offsets are measured on the
  // learnt appearances, whose reference point is the same.
  std::array<Appearance, 2> follow;
  for (int k = 0; k < 2; ++k) {
    const ClipDecision clip = DecideClippedHighlights(
        m.learnt[k], m.relearnt[k] ? relearnt_from : samples, k, learn.threads);
    follow[size_t(k)] = clip.appearance;
    m.choice.reason += "; " + clip.reason;
  }
  // The rows refereed by the plate each sphere rests on (plate_agreement.h).
  m.choice.reason += RelearnHeldByThePlate(learning, reference, samples, relearnt_from,
                                           !m.choice.silhouettes,
                                           !m.choice.silhouettes && !radius_known, learn, &m,
                                           &follow);
  FollowWithoutStillBackground(m, relearnt_from.empty() ? samples : relearnt_from, &follow);
  m.appearance = std::make_shared<const std::array<Appearance, 2>>(follow);
  // The learnt positions refereed by the rough ones (detection_agreement.h).
  for (int k = 0; k < 2; ++k) {
    m.agreement[k] = AgreementWithDetections(m.learnt[k]);
    const DetectionAgreement& a = m.agreement[k];
    if (a.agrees) continue;
    char clause[240];
    std::snprintf(clause, sizeof clause,
                  "; the %s sphere's learnt %s moved %.2f px (sd) over the learning frames where "
                  "its rough centres moved %.2f px: not with the sphere",
                  k == 0 ? "left" : "right", a.axis == 0 ? "columns" : "rows", a.learnt_sd,
                  a.rough_sd);
    m.choice.reason += clause;
  }
  return m;
}

TemplateOffsets EstimateOffsets(const SequenceMethod& m, const std::vector<FrameTrack>& frames,
                                double contact_radius_px, double gravity_px) {
  // A sphere whose learnt positions did not move with its detections: its stated uncertainty
  // on that axis covers how far the two parted (detection_agreement.h).
  const auto widened = [&m](TemplateOffsets t) {
    for (int k = 0; k < 2; ++k) {
      OffsetEstimate& e = m.agreement[k].axis == 0 ? t.col[k] : t.row[k];
      e.err = WidenForDisagreement(m.agreement[k], e.err);
      // And a resting sphere's rows held by what stands still (plate_agreement.h).
      const PlateAgreement& p = m.plate_agreement[k];
      t.row[k].err = WidenForPlate(p, m.relearnt_by_plate[k] || !p.agrees, t.row[k].err);
    }
    return t;
  };
  TemplateOffsets o;
  // The tracker's noise whatever the motion (ContactRowOffset's noise_cap).
  const double length_noise = GapNoise(DimerLengthSeries(frames));
  for (int k = 0; k < 2; ++k) {
    if (m.choice.silhouettes) {
      o.col[k] = SilhouetteOffset(m.learnt[k], 0);
      o.row[k] = SilhouetteOffset(m.learnt[k], 1);
      continue;
    }
    std::vector<double> rows, plate;
    for (const FrameTrack& f : frames) {
      rows.push_back(f.whole(k) && f.appearance[k] == k ? f.centre[k].y() : std::nan(""));
      plate.push_back(f.PlateRowAt(f.centre[k].x()));  // (the plate under this sphere)
    }
    // On a sloping plate the centre stands R along the plate's normal: R sqrt(1 + slope^2)
    // above the plate's row at its column (0.23 px at 8 degrees and R = 23.75 px).
    const double slope = frames.empty() ? 0.0 : frames.front().plate_slope;
    o.row[k] =
        ContactRowOffset(rows, plate, contact_radius_px * std::hypot(1.0, slope), gravity_px,
                         length_noise);
  }
  if (m.choice.silhouettes) return widened(o);
  // The sphere that rests longer (more frames in its contact cluster) sets the contact; the
  // other one, if it rests much less (it bounces: the frames near its impacts are flight, up to
  // a few tenths of a pixel above contact, and bias its own estimate upward), gets that offset
  // carried over, by registering the two appearances and through their outlines, weighed by
  // how alike the two appearances are (CombineRowTransfers, appearance_mismatch.h). Not where
  // its impacts gave its own contact (plate_contact_impacts): that needs no likeness.
  const int ref = o.row[1].n > o.row[0].n ? 1 : 0, other = 1 - ref;
  const bool rests = o.row[ref].source == "plate_contact" && o.row[ref].n >= kMinRestingFrames;
  if (rests && o.row[other].source != "plate_contact_impacts" &&
      double(o.row[other].n) < kTransferBelowFraction * double(o.row[ref].n)) {
    const OffsetEstimate t = RowFromTheOther(m, ref, o.row[ref], &o.appearance_mismatch);
    if (t.source != "none") o.row[other] = t;
  } else if (rests && o.row[other].source == "plate_contact_impacts") {
    // Its impacts' contact is kept, its uncertainty reaching the resting sphere's carried over:
    // on the POV-Ray films of 100 frames the impacts put the bouncing sphere's rows 0.026-0.077
    // px high, stating 0.011-0.029 (up to 7 sigma), and the carried contact lay nearer the
    // truth on all nine (PovrayLongRuler.TheImpactsRowUncertaintyReachesTheRestingSpheres...).
    double mismatch = 0;
    const OffsetEstimate t = RowFromTheOther(m, ref, o.row[ref], &mismatch);
    if (t.source != "none") {
      o.row[other].err = std::hypot(o.row[other].err, o.row[other].value - t.value);
    }
  }
  // Columns from the outline, whose row is then known (where only one side of it shows).
  for (int k = 0; k < 2; ++k) {
    const double row = o.row[k].source == "none" ? std::nan("") : o.row[k].value;
    o.col[k] = LimbColumnOffset(m.learnt[k], row);
    if (o.col[k].source == "none") o.col[k] = ColumnWithoutTheUpperOutline(m.learnt[k]);
  }
  return widened(o);
}

void ApplyOffsets(const TemplateOffsets& o, std::vector<FrameTrack>* frames) {
  for (FrameTrack& f : *frames) {
    for (int k = 0; k < 2; ++k) {
      const int a = f.appearance[k];  // the offsets of the appearance it was measured with
      if (f.found[k]) f.centre[k] += Eigen::Vector2d(o.col[a].value, o.row[a].value);
    }
  }
}

}  // namespace dimer::tracking
