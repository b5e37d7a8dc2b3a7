#include "tracking/frame_follower.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/check.h"
#include "common/error.h"
#include "tracking/sphere/detector.h"
#include "tracking/sphere/precision_bound.h"
#include "tracking/plate/plate_edge.h"
#include "tracking/plate/plate_under_dimer.h"
#include "tracking/sphere/template_locator.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Before the radius is known, windows are sized from the distance-transform radius with this
// headroom (the silhouette of a mirror sphere can look smaller than the sphere).
constexpr double kProvisionalRadiusScale = 1.25;
// Acquisition by template: a second match is another sphere when at least this far away (in
// radii) and scoring at least kMinTemplateScore.
constexpr double kTemplateSeparationR = 1.5;
// A sphere cut by the frame's edge is measured where at least this fraction of its disc's
// followed pixels is in view (the "at least half in view", less the edge's guard).
constexpr double kCutMinInView = 0.3;
// ... and where its centre lies this close to the dimer's length from the other's: the rod is
// rigid (its length scatters by hundredths of a pixel), and a registration that slid along the
// cut is further off (DimerIdentity walks; povray.leaving_the_frame).
constexpr double kCutLengthTolerancePx = 0.5;
// The dimer's vector is carried over at most this many frames without both spheres.
constexpr int kCutMaxDimerAgeFrames = 4;
// Without it, the other sphere is looked for on the circle of the dimer's length tilted up to
// this much (34 degrees, beyond the tilts of the DimerIdentity walks and the POV-Ray films; one
// tilted further waits for a frame that shows both), where its centre is within this margin of
// being wholly in view or further out.
constexpr double kCutMaxTiltRad = 0.6;
constexpr double kCutWholeMarginPx = 6.0;

// How far `p` lies inside `frame`, px, to its nearest edge (pixel centres; negative: outside).
double InsideBy(const cv::Mat& frame, const Eigen::Vector2d& p) {
  return std::min(std::min(p.x() + 0.5, frame.cols - 0.5 - p.x()),
                  std::min(p.y() + 0.5, frame.rows - 0.5 - p.y()));
}

RefineContext Context(int polarity, double plate_row, const Eigen::Vector2d& self,
                      const Eigen::Vector2d* other) {
  RefineContext ctx;
  ctx.polarity = polarity;
  ctx.plate_row = plate_row;
  if (other && (*other - self).norm() > 0) ctx.rod_dir = (*other - self).normalized();
  if (other) ctx.other = *other;  // left out where the spheres touch (measure_sphere.h)
  return ctx;
}

// The sphere's radius, measured on an acquisition with a provisional window: a mirror sphere's
// rim fit measures the radius itself (the mean over both spheres when both are fitted: the
// radius error becomes a bias of every centre, and it is halved); otherwise the larger of the
// distance-transform radius and the first sphere's silhouette area.
double AcquisitionRadius(const cv::Mat& frame, const Detection& det,
                         const std::array<Eigen::Vector2d, 2>& coarse, int n, int polarity,
                         double plate_slope) {
  const double det_col = 0.5 * (frame.cols - 1);
  const double dt_r = *std::max_element(det.radii_px.begin(), det.radii_px.end());
  double rim_sum = 0, area_r = 0;
  int rims = 0;
  for (int k = 0; k < n; ++k) {
    RefineContext ctx = Context(polarity, det.plate_row + plate_slope * (coarse[k].x() - det_col),
                                coarse[k], n > 1 ? &coarse[1 - k] : nullptr);
    ctx.fit_radius = true;
    ctx.radius_start_px = dt_r;  // a filled silhouette's inscribed radius: close for a mirror
    const SphereMeasurement m = MeasureSphere(frame, coarse[k], kProvisionalRadiusScale * dt_r,
                                              ctx, Method::kCentroid);
    if (m.found() && m.rim_fit) {
      rim_sum += m.radius_px;
      ++rims;
    } else if (k == 0 && m.found()) {
      area_r = m.radius_px;
    }
    if (k == 0 && !(m.found() && m.rim_fit)) break;  // uniform: the first sphere's area
  }
  return rims > 0 ? rim_sum / rims : std::max(dt_r, area_r);
}

// Identities of an acquisition's spheres (slot_of[i]: 0 left, 1 right): the nearest last
// position if any is known, else left = the smaller column. The film's names are settled later
// by the rigid dimer (dimer_identity.h).
std::array<int, 2> SlotsOf(const std::vector<SphereMeasurement>& found,
                           const std::array<bool, 2>& known,
                           const std::array<Eigen::Vector2d, 2>& last, int cols) {
  std::array<int, 2> slot_of{0, 1};
  if (found.size() == 2) {
    bool swap = found[1].centre.x() < found[0].centre.x();
    if (known[0] && known[1]) {
      const double keep = (found[0].centre - last[0]).norm() + (found[1].centre - last[1]).norm();
      const double cross = (found[0].centre - last[1]).norm() + (found[1].centre - last[0]).norm();
      swap = cross < keep;
    }
    if (swap) slot_of = {1, 0};
  } else if (found.size() == 1) {
    const Eigen::Vector2d c = found[0].centre;
    if (known[0] || known[1]) {
      const double d0 = known[0] ? (c - last[0]).norm() : INFINITY;
      const double d1 = known[1] ? (c - last[1]).norm() : INFINITY;
      slot_of[0] = d1 < d0 ? 1 : 0;
    } else {
      slot_of[0] = c.x() < 0.5 * cols ? 0 : 1;
    }
  }
  return slot_of;
}

}  // namespace

void FrameTrack::SwapSpheres() {
  std::swap(found[0], found[1]);
  std::swap(cut[0], cut[1]);
  std::swap(centre[0], centre[1]);
  std::swap(radius_px[0], radius_px[1]);
  std::swap(sigma_px[0], sigma_px[1]);
  std::swap(score[0], score[1]);
  std::swap(appearance[0], appearance[1]);
}

void FrameTrack::Drop(int k) {
  found[k] = false;
  cut[k] = false;
  centre[k] = Eigen::Vector2d(0, 0);
  score[k] = kNaN;
  sigma_px[k] = Eigen::Vector2d::Constant(kNaN);
}

std::vector<double> DimerLengthSeries(const std::vector<FrameTrack>& frames) {
  std::vector<double> length;
  length.reserve(frames.size());
  for (const FrameTrack& f : frames) {
    length.push_back(f.whole(0) && f.whole(1) ? (f.centre[1] - f.centre[0]).norm() : kNaN);
  }
  return length;
}

void FollowerOptions::Check() const {
  std::string bad;
  if (polarity < -1 || polarity > 1) bad += "polarity must be -1, 0 or +1; ";
  if (lone_search_every < 1) bad += "a lone sphere's whole-frame search must be every >= 1 frame; ";
  if (coarse_candidates < 0) bad += "the whole-frame search's coarse peaks must be >= 0; ";
  if (!std::isnan(radius_px) && !(radius_px >= 3)) bad += "sphere radius must be >= 3 px; ";
  if (!(psf_sigma_px >= 0 && psf_sigma_px <= 5)) bad += "PSF sigma must be 0..5 px; ";
  if (!(std::abs(plate_slope) <= kPlateMaxSlope)) bad += "plate slope must be within +-0.2; ";
  if (!bad.empty()) throw UsageError(bad.substr(0, bad.size() - 2));
}

FrameFollower::FrameFollower(const FollowerOptions& options)
    : options_(options), polarity_(options.polarity), radius_px_(options.radius_px) {
  options_.Check();
  for (int k = 0; k < 2; ++k) {
    locator_[k] = uses_template() ? MakeTemplateLocator(options_.appearance, k, options_.ecc,
                                                          options_.follow)
                                  : MakeSilhouetteLocator(options_.method);
  }
}

SpherePrediction FrameFollower::Prediction(const Eigen::Vector2d& at, const Eigen::Vector2d* other,
                                           const FrameTrack& frame, bool precise) const {
  SpherePrediction p;
  p.position = at;
  p.precise = precise;
  p.radius_px = radius_px_;
  p.polarity = polarity_;
  p.noise_sigma = noise_sigma_;
  p.state_uncertainty = options_.state_uncertainty;
  if (other) p.other = *other;
  p.plate_row = frame.PlateRowAt(at.x());
  p.plate_slope = options_.plate_slope;
  return p;
}

bool FrameFollower::uses_template() const {
  return options_.method == Method::kTemplate && options_.appearance;
}

bool FrameFollower::places_cuts() const {
  return uses_template() || options_.cut_appearance;
}

const Appearance& FrameFollower::CutAppearance(int k) const {
  return uses_template() ? (*options_.appearance)[k] : (*options_.cut_appearance)[k];
}

Eigen::Vector2d FrameFollower::CutOffset(int k) const {
  return uses_template() ? Eigen::Vector2d(0, 0) : options_.cut_offset[k];
}

double FrameFollower::PlateRow(const cv::Mat& frame, double guess, double guess_col,
                                 const std::array<Eigen::Vector2d, 2>& centres, int n,
                                 std::shared_ptr<const ClippedEdgeProfile>* clipped,
                                 double* col) const {
  std::vector<std::pair<double, double>> excluded;
  const double r = (std::isnan(radius_px_) ? 0.0 : radius_px_) + kPlateSphereClearPx;
  for (int k = 0; k < n; ++k) excluded.emplace_back(centres[k].x() - r, centres[k].x() + r);
  *col = n == 2 ? 0.5 * (centres[0].x() + centres[1].x())
                : (n == 1 ? centres[0].x() : 0.5 * (frame.cols - 1));
  if (options_.plate_slope != 0) guess += options_.plate_slope * (*col - guess_col);
  ClippedEdgeProfile profile;
  const double row = RefinePlateRow(frame, guess, excluded, options_.psf_sigma_px, &profile,
                                    options_.plate_slope, *col);
  clipped->reset();
  if (profile.valid()) *clipped = std::make_shared<const ClippedEdgeProfile>(std::move(profile));
  return row;
}

bool FrameFollower::OutOfViewByTheDimer(const cv::Mat& frame, int j) const {
  if (!places_cuts() || !dimer_seen_) return false;
  const Eigen::Vector2d other = j == 0 ? Eigen::Vector2d(last_[0] + dimer_)
                                       : Eigen::Vector2d(last_[1] - dimer_);
  return InsideBy(frame, other) < radius_px_ + kCutWholeMarginPx;
}

bool FrameFollower::OtherCanBeOutOfView(const cv::Mat& frame, const FrameTrack& t) const {
  const double length = options_.dimer_length_px;
  if (t.found[0] == t.found[1] || !std::isfinite(length)) return false;
  const Eigen::Vector2d c = t.centre[t.found[0] ? 0 : 1];
  for (int side : {+1, -1}) {
    for (double theta = -kCutMaxTiltRad; theta <= kCutMaxTiltRad; theta += 0.05) {
      const Eigen::Vector2d p =
          c + side * length * Eigen::Vector2d(std::cos(theta), std::sin(theta));
      if (InsideBy(frame, p) < radius_px_) return true;
    }
  }
  return false;
}

void FrameFollower::PlanSearches(const cv::Mat& frame, const FrameTrack& t) {
  if (!t.acquired) {
    if (lone_frames_left_ > 0) --lone_frames_left_;
    if (empty_frames_left_ > 0) --empty_frames_left_;
    return;
  }
  // Two searches in a row without a candidate: the dimer is out of view (a drifting dimer leaves
  // it at the end of a long run), and each such search costs ~4 ms on 512x256 (a whole-frame
  // correlation and the silhouette detector's; bench_cut_spheres).
  const bool empty = acquired_candidates_ == 0 && !t.found[0] && !t.found[1];
  empty_searches_ = empty ? empty_searches_ + 1 : 0;
  empty_frames_left_ = empty_searches_ >= 2 ? options_.lone_search_every - 1 : 0;
  // Two searches in a row that found one sphere, where the dimer can reach out of view: one
  // alone may have missed a sphere in view (a 3-frame film of 160x96 px: docs.install).
  lone_searches_ = t.found[0] != t.found[1] ? lone_searches_ + 1 : 0;
  lone_frames_left_ = lone_searches_ >= 2 && OtherCanBeOutOfView(frame, t)
                          ? options_.lone_search_every - 1
                          : 0;
}

bool FrameFollower::Follow(const cv::Mat& frame, FrameTrack* out) {
  if (!std::isfinite(plate_row_)) return false;
  // One sphere followed: the other is searched for on the whole frame unless the dimer's last
  // vector puts it out of view or cut by the edge (then step 5 places it if it shows): a frame
  // with one sphere in view costs a following, not an acquisition.
  if (!locked_[0] && !locked_[1]) return false;
  if (!(locked_[0] && locked_[1]) && !OutOfViewByTheDimer(frame, locked_[0] ? 0 : 1) &&
      lone_frames_left_ == 0) {
    return false;
  }
  std::array<Eigen::Vector2d, 2> predicted{last_[0] + velocity_[0], last_[1] + velocity_[1]};
  for (int k = 0; k < 2; ++k) {
    if (!locked_[k]) predicted[k] = k == 1 ? Eigen::Vector2d(predicted[0] + dimer_)
                                           : Eigen::Vector2d(predicted[1] - dimer_);
  }
  out->plate_slope = options_.plate_slope;
  out->plate_row =
      PlateRow(frame, plate_row_, plate_col_, predicted, 2, &out->clipped_plate, &out->plate_col);
  if (!std::isfinite(out->plate_row)) return false;
  std::array<bool, 2> cut{!locked_[0], !locked_[1]};
  for (int k = 0; k < 2; ++k) {
    if (!locked_[k]) continue;
    // A constant-velocity prediction: < 1 px per frame at 2000 frames/s.
    // The other's place is unknown where the dimer was never seen in this chunk.
    const Eigen::Vector2d* other = locked_[1 - k] || dimer_seen_ ? &predicted[1 - k] : nullptr;
    const SphereMeasurement m =
        locator_[k]->Locate(frame, Prediction(predicted[k], other, *out, true));
    // A sphere cut by the frame's edge is placed by the dimer once the other is found.
    if (places_cuts() && m.status == SphereMeasurement::Status::kClipped) {
      cut[k] = true;
      continue;
    }
    // A learnt appearance that neither the quick step nor ECC could refine from the prediction
    // is a whole-pixel peak beside the sphere, not the sphere: on a still-plate film of separate
    // poses the lifted sphere, followed from the last pose, was matched so 7-11 px off
    // (povray.still_plate_poses). The whole frame is searched instead.
    if (uses_template() && !std::isfinite(m.score)) return false;
    if (!m.found()) return false;
    out->found[k] = true;
    out->centre[k] = m.centre;
    out->score[k] = m.score;
    out->radius_px[k] = m.radius_px;
    out->sigma_px[k] = m.sigma_px;
  }
  if (cut[0] && cut[1]) return false;
  MeasureCuts(frame, out);
  return true;
}

bool FrameFollower::PlaceCut(const cv::Mat& frame, int k, const Eigen::Vector2d& guess,
                             double length, FrameTrack* out) const {
  if (!places_cuts() || out->found[k]) return false;
  const bool pair = out->found[1 - k];
  MaskContext ctx;
  ctx.plate_row = out->PlateRowAt(guess.x());
  ctx.plate_slope = options_.plate_slope;
  if (pair && (out->centre[1 - k] - guess).norm() > 0) {
    ctx.rod_dir = (out->centre[1 - k] - guess).normalized();
    ctx.other = out->centre[1 - k] - guess;
  }
  Located l = LocateCutAppearance(frame, CutAppearance(k), guess - CutOffset(k), ctx,
                                  kCutMinInView, options_.ecc);
  if (!l.ok || !(l.score >= kMinTemplateScore)) return false;
  l.position += CutOffset(k);  // the method's centre
  if (pair && !(std::abs((l.position - out->centre[1 - k]).norm() - length) <=
                kCutLengthTolerancePx)) {
    return false;
  }
  out->found[k] = true;
  out->cut[k] = true;
  out->centre[k] = l.position;
  out->score[k] = l.refined;
  out->radius_px[k] = radius_px_;
  out->sigma_px[k] = CutSigma(frame, k, l, *out);
  // The dimer's length referees it: what its distance from the other misses the length by is
  // its error along the rod, and the stated uncertainty covers it (on 12-px spheres under
  // half in view the shift of the whole sphere cut alike stated a third of the error:
  // bench_cut_spheres).
  if (pair) {
    const double miss = (l.position - out->centre[1 - k]).norm() - length;
    out->sigma_px[k] = (out->sigma_px[k].cwiseProduct(out->sigma_px[k]).array() + miss * miss)
                           .sqrt()
                           .matrix();
  }
  out->appearance[k] = k;
  return true;
}

Eigen::Vector2d FrameFollower::CutSigma(const cv::Mat& frame, int k, const Located& l,
                                        const FrameTrack& t) const {
  const int j = 1 - k;
  if (!t.found[j] || t.cut[j] || !l.sigma.allFinite()) return Eigen::Vector2d::Constant(kNaN);
  // The frame as the cut sphere sees it, moved to the whole one by whole pixels.
  const Eigen::Vector2d gk(std::round(l.position.x()), std::round(l.position.y()));
  const Eigen::Vector2d gj(std::round(t.centre[j].x()), std::round(t.centre[j].y()));
  const cv::Rect view(int(gj.x() - gk.x()), int(gj.y() - gk.y()), frame.cols, frame.rows);
  MaskContext ctx;
  ctx.plate_row = t.PlateRowAt(t.centre[j].x());
  ctx.plate_slope = options_.plate_slope;
  if ((l.position - t.centre[j]).norm() > 0) {
    ctx.rod_dir = (l.position - t.centre[j]).normalized();
    ctx.other = l.position - t.centre[j];
  }
  // The whole sphere's reference point where it was found (for the silhouette methods, its
  // centre less the appearance's offset: registered there, whole, it moves by what the
  // offset's scatter says).
  const Eigen::Vector2d at = t.centre[j] - CutOffset(j);
  const Located whole = LocateCutAppearance(frame, CutAppearance(j), at, ctx, kCutMinInView,
                                            options_.ecc);
  const Located w = LocateCutAppearance(frame, CutAppearance(j), at, ctx, kCutMinInView,
                                        options_.ecc, &view);
  if (!w.ok || !whole.ok) return Eigen::Vector2d::Constant(kNaN);
  const Eigen::Vector2d shift = w.position - whole.position;
  const Eigen::Vector2d off = uses_template() ? Eigen::Vector2d(0, 0) : options_.cut_offset_err[k];
  return (l.sigma.cwiseProduct(l.sigma) + shift.cwiseProduct(shift) + off.cwiseProduct(off))
      .cwiseSqrt();
}

bool FrameFollower::MeasureCut(const cv::Mat& frame, int k, const Eigen::Vector2d& dimer,
                               double length, FrameTrack* out) const {
  if (!out->found[1 - k]) return false;
  const Eigen::Vector2d guess = k == 1 ? Eigen::Vector2d(out->centre[0] + dimer)
                                       : Eigen::Vector2d(out->centre[1] - dimer);
  return PlaceCut(frame, k, guess, length, out);
}

void FrameFollower::SearchCutOnCircle(const cv::Mat& frame, FrameTrack* out) const {
  const double length = options_.dimer_length_px;
  if (!places_cuts() || out->found[0] == out->found[1] || !std::isfinite(length)) return;
  const int j = out->found[0] ? 0 : 1;  // the one found
  const Eigen::Vector2d c = out->centre[j];
  Located best;
  int best_side = 0;  // none
  for (int side : {+1, -1}) {  // +1: the one found is the left
    const int name = side > 0 ? 1 : 0;
    const Appearance& a = CutAppearance(name);
    // Candidates a pixel apart along the circle, tilted up to kCutMaxTiltRad either way.
    const double step = 1.0 / length;
    for (double theta = -kCutMaxTiltRad; theta <= kCutMaxTiltRad; theta += step) {
      const Eigen::Vector2d p = c + side * length * Eigen::Vector2d(std::cos(theta),
                                                                    std::sin(theta));
      if (p.y() > out->PlateRowAt(p.x()) - 0.5 * a.radius_px) continue;  // below the plate
      // Cut by the frame's edge (whole ones are acquired) and not mostly out of it.
      const double in = InsideBy(frame, p);
      if (in > a.radius_px + kCutWholeMarginPx || in < -0.2 * a.radius_px) continue;
      MaskContext ctx;
      ctx.plate_row = out->PlateRowAt(p.x());
      ctx.plate_slope = options_.plate_slope;
      ctx.rod_dir = (c - p).normalized();
      ctx.other = c - p;
      Located l = SearchCutAppearance(frame, a, p - CutOffset(name), ctx, kCutMinInView);
      l.position += CutOffset(name);
      if (l.ok && l.score > best.score) best = l, best_side = side;
    }
  }
  if (best_side == 0 || !(best.score >= kMinTemplateScore)) return;
  const int k = best_side > 0 ? 1 : 0;  // the cut sphere's name
  FrameTrack trial = *out;
  if (k == j) trial.SwapSpheres();  // the one found is the other
  trial.appearance[k] = k;
  const Eigen::Vector2d d = (best.position - c) * (k == 1 ? 1.0 : -1.0);  // right - left
  if (MeasureCut(frame, k, d, length, &trial)) *out = trial;
}

void FrameFollower::MeasureCuts(const cv::Mat& frame, FrameTrack* out) const {
  if (!places_cuts()) return;
  if (out->found[0] != out->found[1]) {
    if (!dimer_known_) {
      SearchCutOnCircle(frame, out);
      return;
    }
    // The dimer's vector in this frame: the last one moved on by its rate over the frames since.
    const Eigen::Vector2d d = dimer_ + double(dimer_age_ + 1) * dimer_rate_;
    MeasureCut(frame, out->found[0] ? 1 : 0, d, dimer_.norm(), out);
    return;
  }
  // Alone in view: a sphere followed into the last frame, from its own motion.
  for (int k = 0; k < 2; ++k) {
    if (!out->found[k] && !out->found[1 - k] && locked_[k]) {
      PlaceCut(frame, k, last_[k] + velocity_[k], kNaN, out);
    }
  }
}

bool FrameFollower::PlaceCutBeside(const cv::Mat& frame, const FrameTrack& adjacent,
                                   const FrameTrack* beyond, FrameTrack* t) const {
  for (int k = 0; k < 2; ++k) {
    if (!adjacent.found[k] || t->found[k]) continue;
    if (t->found[1 - k] && adjacent.found[1 - k]) {  // by the dimer's vector
      const Eigen::Vector2d d = adjacent.centre[1] - adjacent.centre[0];
      const Eigen::Vector2d rate = beyond && beyond->found[0] && beyond->found[1]
                                       ? Eigen::Vector2d(beyond->centre[1] - beyond->centre[0] - d)
                                       : Eigen::Vector2d(0, 0);
      MeasureCut(frame, k, d - rate, d.norm(), t);
    } else {  // by its own motion (and the dimer's length where the other is in *t)
      const Eigen::Vector2d v = beyond && beyond->found[k]
                                    ? Eigen::Vector2d(beyond->centre[k] - adjacent.centre[k])
                                    : Eigen::Vector2d(0, 0);
      PlaceCut(frame, k, adjacent.centre[k] - v,
               t->found[1 - k] ? options_.dimer_length_px : kNaN, t);
    }
  }
  return !(adjacent.found[0] && !t->found[0]) && !(adjacent.found[1] && !t->found[1]);
}

double FrameFollower::LowestReach(const FrameTrack& t, double col) const {
  double lowest = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 2; ++k) {
    if (!t.found[k]) continue;
    const double reach = AcquireReach((*options_.appearance)[size_t(t.appearance[k])]);
    const double row = t.centre[k].y() + reach + options_.plate_slope * (col - t.centre[k].x());
    if (!(row <= lowest)) lowest = row;
  }
  return lowest;
}

void FrameFollower::Acquire(const cv::Mat& frame, FrameTrack* out) {
  const Detection det = DetectSpheres(frame, polarity_, options_.plate_slope, radius_px_);
  AcquireAbove(frame, det, out);
  if (!uses_template()) return;
  // The plate is the edge the dimer stands on. The detector tells it from the spheres' blobs;
  // where a ruler's or a backdrop's edge cuts them, it can take that edge, and the search above
  // it then misses the spheres or finds them reaching below it (no sphere's reference point
  // comes nearer the plate than its reach, AcquireReach). The spheres are then searched for
  // above each candidate edge further down, nearest first, and the first under which both
  // stand (neither reaching below it) is the plate (ruler_above_plate's resting sphere, the
  // ruler's lower edge taken in chunks of 3 frames: povray.ruler_in_chunks).
  const double det_col = 0.5 * (frame.cols - 1);
  const double lowest = LowestReach(*out, det_col);
  const int found = int(out->found[0]) + int(out->found[1]);
  const bool through = lowest > det.plate_row + kPlateMeetPx;
  // A frame where the detector saw no sphere's blob either (the dimer out of view) is not
  // searched again: whole-frame searches are what such frames cost (bench_cut_spheres). Nor is
  // one where the search found as many spheres as the detector saw blobs: where it found fewer,
  // the part of a sphere above a wrong edge can have passed for it (the right's appearance
  // matched the hopping sphere's top above the ruler's lower edge at 0.54: povray.ruler_in_chunks).
  const bool fewer_than_blobs = found < int(det.centres.size());
  if ((found > 0 || det.centres.empty()) && !through && !fewer_than_blobs) return;
  const std::vector<PlateCandidate> candidates = PlateCandidates(frame, options_.plate_slope);
  const int first_candidates = acquired_candidates_;
  for (const PlateCandidate& c : candidates) {
    if (!(c.row > det.plate_row + kPlateMeetPx) || (through && c.row < lowest - kPlateMeetPx)) {
      continue;
    }
    Detection moved = det;
    moved.plate_row = c.row;
    FrameTrack again;
    again.index = out->index;
    AcquireAbove(frame, moved, &again);
    if (!again.found[0] || !again.found[1] ||
        LowestReach(again, det_col) > c.row + kPlateMeetPx) {
      continue;
    }
    for (const PlateCandidate& strongest : candidates) {
      if (strongest.strongest && strongest.row != c.row) again.strongest_edge_row = strongest.row;
    }
    *out = again;
    return;
  }
  acquired_candidates_ = first_candidates;  // the searches below found no dimer: as it was
}

void FrameFollower::AcquireAbove(const cv::Mat& frame, const Detection& detection,
                                 FrameTrack* out) {
  Detection det = detection;
  const size_t index = out->index;
  *out = FrameTrack{};
  out->index = index;
  out->acquired = true;
  out->strongest_edge_row = det.strongest_edge_row;
  // The coarse plate row is the edge's at the frame's centre column; the plate's lowest point
  // bounds the search for the spheres.
  const double det_col = 0.5 * (frame.cols - 1);
  const double plate_low = det.plate_row + std::abs(options_.plate_slope) * det_col;
  if (uses_template()) {
    // The learnt appearance finds the spheres whatever they look like (a silhouette detector
    // can miss a sphere that shows only its highlights).
    det.centres.clear();
    const double apart = kTemplateSeparationR * radius_px_;
    for (const Located& l : FindAppearance(frame, (*options_.appearance)[0], plate_low, apart,
                                           kMinTemplateScore, options_.coarse_candidates)) {
      det.centres.push_back(l.position);
    }
    // The two spheres need not look alike (something standing behind one of them, a lamp to
    // one side): where the left's appearance finds fewer than two, the right's looks for the
    // rest (ruler_above_plate's hopping sphere scores under kMinTemplateScore against its
    // resting partner's appearance in every frame: FrameFollower.FindsASphereUnlikeItsPartner).
    if (det.centres.size() < 2) {
      for (const Located& l : FindAppearance(frame, (*options_.appearance)[1], plate_low, apart,
                                             kMinTemplateScore, options_.coarse_candidates)) {
        const bool new_sphere = std::none_of(
            det.centres.begin(), det.centres.end(),
            [&](const Eigen::Vector2d& c) { return (c - l.position).norm() < apart; });
        if (new_sphere && det.centres.size() < 2) det.centres.push_back(l.position);
      }
    }
    det.radii_px.assign(det.centres.size(), radius_px_);
  }
  const int n = int(det.centres.size());
  acquired_candidates_ = n;
  std::array<Eigen::Vector2d, 2> coarse{};
  for (int k = 0; k < n; ++k) coarse[k] = det.centres[k];
  if (std::isnan(radius_px_) && n > 0) {
    radius_px_ = AcquisitionRadius(frame, det, coarse, n, polarity_, options_.plate_slope);
  }
  out->plate_slope = options_.plate_slope;
  out->plate_row = PlateRow(frame, det.plate_row, det_col, coarse, n, &out->clipped_plate,
                            &out->plate_col);
  std::vector<SphereMeasurement> found;
  for (int k = 0; k < n; ++k) {
    SphereMeasurement m;
    if (uses_template()) {  // coarse only: refined below with the identity's own appearance
      m.status = SphereMeasurement::Status::kFound;
      m.centre = coarse[k];
      m.radius_px = radius_px_;
    } else {  // the silhouette locator measures alike for either identity
      m = locator_[0]->Locate(frame,
                              Prediction(coarse[k], n > 1 ? &coarse[1 - k] : nullptr, *out, false));
    }
    if (m.found()) found.push_back(m);
  }
  const std::array<int, 2> slot_of = SlotsOf(found, known_, last_, frame.cols);
  if (uses_template()) {
    for (size_t i = 0; i < found.size(); ++i) {
      const Eigen::Vector2d* other = found.size() == 2 ? &found[1 - i].centre : nullptr;
      found[i] = locator_[slot_of[i]]->Locate(frame,
                                              Prediction(found[i].centre, other, *out, false));
    }
  }
  for (size_t i = 0; i < found.size(); ++i) {
    if (!found[i].found()) continue;
    out->found[slot_of[i]] = true;
    out->centre[slot_of[i]] = found[i].centre;
    out->score[slot_of[i]] = found[i].score;
    out->radius_px[slot_of[i]] = found[i].radius_px;
    out->sigma_px[slot_of[i]] = found[i].sigma_px;
  }
  MeasureCuts(frame, out);
}

bool FrameFollower::MeasurePlateOnly(const cv::Mat& frame, FrameTrack* out) {
  if (!std::isfinite(plate_row_)) return false;
  out->plate_slope = options_.plate_slope;
  const std::array<Eigen::Vector2d, 2> no_sphere{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  out->plate_row = PlateRow(frame, plate_row_, plate_col_, no_sphere, 0, &out->clipped_plate,
                            &out->plate_col);
  return std::isfinite(out->plate_row);
}

void FrameFollower::Commit(const FrameTrack& t) {
  if (std::isfinite(t.plate_row)) {
    plate_row_ = t.plate_row;
    plate_col_ = t.plate_col;
  }
  if (t.found[0] && t.found[1]) {
    dimer_seen_ = true;
    const Eigen::Vector2d d = t.centre[1] - t.centre[0];
    dimer_rate_ = dimer_known_ && dimer_age_ == 0 ? Eigen::Vector2d(d - dimer_)
                                                  : Eigen::Vector2d(0, 0);
    dimer_ = d;
    dimer_known_ = true;
    dimer_age_ = 0;
  } else if (dimer_known_ && ++dimer_age_ > kCutMaxDimerAgeFrames) {
    dimer_known_ = false;
  }
  for (int k = 0; k < 2; ++k) {
    velocity_[k] = (t.found[k] && locked_[k]) ? Eigen::Vector2d(t.centre[k] - last_[k])
                                              : Eigen::Vector2d(0, 0);
    locked_[k] = t.found[k];
    if (t.found[k]) {
      last_[k] = t.centre[k];
      known_[k] = true;
    }
  }
}

FrameTrack FrameFollower::Process(const cv::Mat& frame, size_t index) {
  DIMER_CHECK(!frame.empty() && frame.channels() == 1,
              "the tracker measures grey frames (frame sources make them grey)");
  if (polarity_ == 0) polarity_ = DetectPolarity(frame);
  // Once per follower: a chunk's frames share the camera's noise.
  if (options_.state_uncertainty && !noise_measured_) {
    noise_sigma_ = FrameNoiseSigma(frame);
    noise_measured_ = true;
  }
  FrameTrack out;
  out.index = index;
  if (!Follow(frame, &out) && !(empty_frames_left_ > 0 && MeasurePlateOnly(frame, &out))) {
    Acquire(frame, &out);
  }
  Commit(out);
  PlanSearches(frame, out);
  return out;
}

}  // namespace dimer::tracking
