#include "tracking/sphere/sphere_locator.h"

#include <cmath>
#include <optional>
#include <utility>

#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

// Template method: whole-pixel search around a prediction (< 1 px per frame at 2000 frames/s)
// and around an acquisition's coarse match, px. The coarse match is the first sphere's
// appearance, and the second sphere's is framed differently (a sphere that never rests is
// framed on its lowest learning frames, above its centre: 3 px at 0.2 mm/px, 6 px at 0.1 mm/px),
// so the acquisition reaches Reach(kAcquireSearchPx, kAcquireSearchR, R) (tolerances.h): a
// fixed 4 px search misses at 0.1 mm/px, and following, which moves at most a pixel a frame,
// needs frames to catch up (povray.targets.fine_scale).
constexpr int kFollowSearchPx = 2;
constexpr int kAcquireSearchPx = 4;
constexpr double kAcquireSearchR = 0.16;

bool Distinct(const Eigen::Vector2d& other, const Eigen::Vector2d& self) {
  return other.allFinite() && (other - self).norm() > 0;
}

class SilhouetteLocator final : public SphereLocator {
 public:
  explicit SilhouetteLocator(Method method) : method_(method) {}

  SphereMeasurement Locate(const cv::Mat& frame, const SpherePrediction& p) const override {
    RefineContext ctx;
    ctx.polarity = p.polarity;
    ctx.plate_row = p.plate_row;
    // A sphere alone in view: its rod, toward the other out of view, is cut as a level one (the
    // mask cuts the corridor on both sides; a dimer on the plate tilts far less than the
    // corridor's half width at the sphere's rim, 0.3 R). Measured with it, the centroid of a
    // mirror-lit sphere alone lay up to 3 px toward the rod (DimerIdentity walks).
    ctx.rod_dir = Distinct(p.other, p.position) ? Eigen::Vector2d((p.other - p.position).normalized())
                                                : Eigen::Vector2d(1, 0);
    ctx.other = p.other;  // left out where the spheres touch (measure_sphere.h)
    ctx.precise_guess = p.precise;
    if (p.state_uncertainty) ctx.noise_sigma = p.noise_sigma;
    return MeasureSphere(frame, p.position, p.radius_px, ctx, method_);
  }

 private:
  Method method_;
};

class TemplateSphereLocator final : public SphereLocator {
 public:
  TemplateSphereLocator(std::shared_ptr<const std::array<Appearance, 2>> appearances, int which,
                        const EccStop& ecc, const FollowStop& follow)
      : appearances_(std::move(appearances)), which_(which), ecc_(ecc), follow_(follow),
        model_(PrepareFollow((*appearances_)[which_], follow.shifts_per_px)) {}

  // Following: the quick step from the prediction; where it fails (a prediction more than a
  // pixel off, at an impact), the whole-pixel search, the quick step from its peak and ECC
  // only if that fails too: ECC from the prediction costs as much for a 2,000-frame film's 51
  // such sphere-frames as all its quick steps (bench_track_e2e). With the quick step
  // off (FollowStop::max_iterations 0), ECC from the prediction, then after the search.
  // Acquisition: the search reaching as far as a coarse match can be off, then the quick step
  // from its peak.
  SphereMeasurement Locate(const cv::Mat& frame, const SpherePrediction& p) const override {
    if (!p.precise) {
      return At(frame, p, int(std::lround(Reach(kAcquireSearchPx, kAcquireSearchR, p.radius_px))));
    }
    if (const std::optional<Located> l =
            FollowOnlyQuickly(frame, (*appearances_)[which_], model_, p.position, Context(p),
                              follow_, 0, p.state_uncertainty)) {
      return Measured(*l, p);
    }
    if (follow_.max_iterations <= 0) {
      const SphereMeasurement m = At(frame, p, 0);
      if (m.found()) return m;
    }
    return At(frame, p, kFollowSearchPx);
  }

 private:
  static MaskContext Context(const SpherePrediction& p) {
    MaskContext ctx;
    ctx.plate_row = p.plate_row;
    ctx.plate_slope = p.plate_slope;
    if (Distinct(p.other, p.position)) {
      ctx.rod_dir = (p.other - p.position).normalized();
      ctx.other = p.other - p.position;
    }
    return ctx;
  }

  // The reference point of the appearance (the track's offset turns it into the centre
  // afterwards, track_sequence.cc), radius as known.
  static SphereMeasurement Measured(const Located& l, const SpherePrediction& p) {
    SphereMeasurement m;
    m.status = l.clipped ? SphereMeasurement::Status::kClipped
                         : (l.ok && l.score >= kMinTemplateScore ? SphereMeasurement::Status::kFound
                                                                 : SphereMeasurement::Status::kMissing);
    m.centre = l.position;
    m.radius_px = p.radius_px;
    m.score = l.refined;
    m.sigma_px = l.sigma;
    m.quality = std::isfinite(l.refined) ? l.refined : l.score;
    return m;
  }

  SphereMeasurement At(const cv::Mat& frame, const SpherePrediction& p, int search_px) const {
    return Measured(FollowAppearance(frame, (*appearances_)[which_], model_, p.position,
                                     Context(p), follow_, ecc_, search_px, p.state_uncertainty),
                    p);
  }

  std::shared_ptr<const std::array<Appearance, 2>> appearances_;
  int which_;
  EccStop ecc_;
  FollowStop follow_;
  FollowModel model_;  // the appearance prepared for the quick step
};

}  // namespace

std::unique_ptr<SphereLocator> MakeSilhouetteLocator(Method method) {
  return std::make_unique<SilhouetteLocator>(method);
}

std::unique_ptr<SphereLocator> MakeTemplateLocator(
    std::shared_ptr<const std::array<Appearance, 2>> appearances, int which, const EccStop& ecc,
    const FollowStop& follow) {
  return std::make_unique<TemplateSphereLocator>(std::move(appearances), which, ecc, follow);
}

}  // namespace dimer::tracking
