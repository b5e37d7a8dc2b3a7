#include "tracking/plate/clipped_edge.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tracking/plate/plate_step.h"
#include "tracking/tolerances.h"

namespace dimer::tracking {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kBracketRows = kPlateBracketRows;

// Standard normal density.
double Density(double t) { return 0.3989422804014327 * std::exp(-0.5 * t * t); }

// The camera's blur across rows: a Gaussian of `sigma` px sampled on the pixel grid to 3 sigma
// (as cv::GaussianBlur applies it; sigma 0: none), normalised.
std::vector<double> PsfTaps(double sigma) {
  if (!(sigma > 0)) return {1.0};
  const int half = int(std::ceil(3 * sigma));
  std::vector<double> taps(2 * half + 1);
  double sum = 0;
  for (int t = -half; t <= half; ++t) {
    sum += taps[t + half] = std::exp(-0.5 * t * t / (sigma * sigma));
  }
  for (double& w : taps) w /= sum;
  return taps;
}

constexpr double kFarSigmas = 8.0;

// Expected value of a pixel whose true level is `mu`, read with Gaussian noise `sigma` and then
// clipped to [0, clip]: the noise pushes the mean of a dark pixel up, and of a clipped one down.
double ClippedMean(double mu, double sigma, double clip) {
  const double a = -mu / sigma, b = (clip - mu) / sigma;
  // Beyond 8 sigma of an end the clip's effect is below 1e-15 of sigma: no erf needed.
  if (b < -kFarSigmas) return clip;
  if (a > kFarSigmas) return 0.0;
  if (a < -kFarSigmas && b > kFarSigmas) return mu;
  const double pa = 0.5 * std::erfc(-a / std::sqrt(2.0));
  const double pb = 0.5 * std::erfc(-b / std::sqrt(2.0));
  return mu * (pb - pa) + sigma * (Density(a) - Density(b)) + clip * (1.0 - pb);
}

// d ClippedMean / d mu: the chance that the pixel is clipped at neither end.
double ClippedSlope(double mu, double sigma, double clip) {
  const double a = -mu / sigma, b = (clip - mu) / sigma;
  if (b < -kFarSigmas || a > kFarSigmas) return 0.0;
  if (a < -kFarSigmas && b > kFarSigmas) return 1.0;
  return 0.5 * (std::erf((clip - mu) / (sigma * std::sqrt(2.0))) +
                std::erf(mu / (sigma * std::sqrt(2.0))));
}

// The clipped edge's model (ClippedEdgeRowInProfile) at one trial row `y`: the step of true
// level that fits the profile best, and the fit's chi-square.
struct ClippedFit {
  double chi2 = std::numeric_limits<double>::infinity();
  double level = 0;
};

class ClippedEdgeModel {
 public:
  ClippedEdgeModel(const std::vector<double>& profile, int first_row, int k, double clip,
                   double pixel_sigma, double profile_sigma, double psf_sigma_px)
      : profile_(profile), first_row_(first_row), j0_(k - kBracketRows), j1_(k + kBracketRows),
        below_(profile[k + kBracketRows] > profile[k - kBracketRows]), clip_(clip),
        sigma_(pixel_sigma), profile_sigma_(profile_sigma), taps_(PsfTaps(psf_sigma_px)) {
    // The dark side's true level: its row's mean, unbent from the clip at 0 (bisection).
    const double m = below_ ? profile[j0_] : profile[j1_];
    double lo = -6 * sigma_, hi = clip_;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (ClippedMean(mid, sigma_, clip_) < m ? lo : hi) = mid;
    }
    dark_ = 0.5 * (lo + hi);
  }

  // Fitted level at trial row y (the level unknown).
  ClippedFit At(double y) const {
    double share[2 * kBracketRows + 1];
    double smax = 0;
    for (int j = j0_; j <= j1_; ++j) smax = std::max(smax, share[j - j0_] = Share(j, y));
    if (smax <= 0) return {};
    // Start: the least step that brings the most lit row to its mean (or to the clip).
    double m_top = 0;
    for (int j = j0_; j <= j1_; ++j) {
      if (share[j - j0_] == smax) m_top = profile_[j];
    }
    double level = std::max(0.0, (std::min(m_top, clip_) - dark_) / smax);
    // Gauss-Newton on the step: the clipped rows pull it up only until they reach the clip.
    for (int it = 0; it < kPlateClipFitIterations; ++it) {
      double num = 0, den = 0;
      for (int j = j0_; j <= j1_; ++j) {
        const double mu = dark_ + level * share[j - j0_];
        const double g = ClippedSlope(mu, sigma_, clip_) * share[j - j0_];
        num += g * (profile_[j] - ClippedMean(mu, sigma_, clip_));
        den += g * g;
      }
      if (den <= 0) break;
      const double next = std::max(0.0, level + num / den);
      const bool done = std::abs(next - level) < 1e-6 * (1.0 + level);
      level = next;
      if (done) break;
    }
    ClippedFit fit;
    fit.level = level;
    fit.chi2 = 0;
    for (int j = j0_; j <= j1_; ++j) {
      const double mu = dark_ + level * share[j - j0_];
      const double r = (profile_[j] - ClippedMean(mu, sigma_, clip_)) / profile_sigma_;
      fit.chi2 += r * r;
    }
    return fit;
  }

  // Chi-square at trial row y with the clipped side's level (above the dark side) known.
  double Chi2(double y, double level) const {
    double chi2 = 0;
    for (int j = j0_; j <= j1_; ++j) {
      const double mu = dark_ + level * Share(j, y);
      const double r = (profile_[j] - ClippedMean(mu, sigma_, clip_)) / profile_sigma_;
      chi2 += r * r;
    }
    return chi2;
  }

  // Rows of the bracket whose mean is clear of the dark level and of the clip (kPartlyLit*).
  int PartlyLitRows() const {
    const double margin =
        std::max(kPartlyLitSigmas * profile_sigma_, kPartlyLitClipFraction * clip_);
    int n = 0;
    for (int j = j0_; j <= j1_; ++j) {
      n += profile_[j] >= dark_ + margin && profile_[j] <= clip_ - margin;
    }
    return n;
  }

  // The level that brings the clipped side to the clip: no level below it explains a clipped row.
  double LeastLevel() const { return clip_ - dark_; }

 private:
  // The clipped side's share of profile row j after the blur, for an edge at row y.
  double Share(int j, double y) const {
    const int half = int(taps_.size() / 2);
    double below = 0;  // pixel r spans [r - 1/2, r + 1/2]
    for (int t = -half; t <= half; ++t) {
      below += taps_[t + half] * std::clamp(first_row_ + j - t + 0.5 - y, 0.0, 1.0);
    }
    return below_ ? below : 1.0 - below;
  }

  const std::vector<double>& profile_;
  int first_row_, j0_, j1_;
  bool below_;
  double clip_, sigma_, profile_sigma_, dark_ = 0;
  std::vector<double> taps_;
};

// Golden-section minimum of f on [a, b], to a bracket narrower than `tolerance` (compare/
// plate_fit.cc runs a fixed number of steps instead); returns the bracket's middle.
template <typename F>
double GoldenMinimumToWidth(const F& f, double a, double b, double tolerance) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  while (b - a > tolerance) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    }
  }
  return 0.5 * (a + b);
}

// The trial row minimising `cost` over the pixels next to the step k (the edge may sit up to a
// pixel and a half from it, on the clipped side): every `coarse` px, then golden-section search
// about the best to `tolerance` px. A grid alone is not enough: with the level known, a profile
// row averaged over hundreds of columns moves by tens of its noise sigmas per 0.01 px. `best`
// (if given): the cost there.
template <typename Cost>
double MinimiseOverRow(const Cost& cost, int first_row, int k, double coarse, double tolerance,
                       double* best = nullptr) {
  const double from = first_row + k - 1.5;
  const int n = int(std::lround(4.0 / coarse));
  double lowest = kInf, rough = kNaN;
  for (int i = 0; i <= n; ++i) {
    const double c = cost(from + i * coarse);
    if (c < lowest) {
      lowest = c;
      rough = from + i * coarse;
    }
  }
  if (!std::isfinite(rough)) return kNaN;
  const double mid = GoldenMinimumToWidth(cost, rough - coarse, rough + coarse, tolerance);
  // The grid point itself when the bracket's ends are no better (a kink at the clip).
  const double fmid = cost(mid);
  const bool grid = lowest < fmid;
  if (best) *best = grid ? lowest : fmid;
  return grid ? rough : mid;
}

// The step's index in `p`, or -1 when it cannot be bracketed.
int BracketedStep(const std::vector<double>& profile) {
  double size = 0;
  const int k = PlateStepIndex(profile, &size);
  return (k - kBracketRows < 0 || k + kBracketRows >= int(profile.size())) ? -1 : k;
}

// The model of `p`'s edge, with the sequence's noise `shared_sigma` where `p` could not measure
// its own (and shared_sigma is known).
ClippedEdgeModel ModelOf(const ClippedEdgeProfile& p, int k, double psf_sigma_px,
                         double shared_sigma) {
  const double sigma =
      p.noise_measured || !std::isfinite(shared_sigma) ? p.pixel_sigma : shared_sigma;
  return ClippedEdgeModel(p.profile, p.first_row, k, p.clip, sigma,
                          sigma / std::sqrt(double(std::max(1, p.columns))), psf_sigma_px);
}

// The median pixel noise of the frames that measured theirs; NaN if none did.
double SharedNoise(const std::vector<const ClippedEdgeProfile*>& frames) {
  std::vector<double> s;
  for (const ClippedEdgeProfile* p : frames) {
    if (p && p->valid() && p->noise_measured) s.push_back(p->pixel_sigma);
  }
  if (s.empty()) return kNaN;
  std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
  return s[s.size() / 2];
}

// The level search: a coarse grid in ln(level), then golden-section about its best point.
// With the level given, a frame's chi-square has one minimum over the rows, so the row's grid
// can be coarser than the free-level fit's (kPlateClipCoarsePx); within the level search the
// row needs less precision than for the final answer (the chi-square is flat about it).
constexpr double kLevelGridLow = 0.8, kLevelGridHigh = 64.0;  // x the least level
constexpr int kLevelGridPoints = 49;
constexpr double kLevelTolerance = 1e-7;  // in ln(level)
constexpr double kLevelRowCoarsePx = 0.1, kLevelRowTolerancePx = 1e-4;

}  // namespace

double ClippedEdgeRowInProfile(const std::vector<double>& profile, int first_row, double clip,
                               double pixel_sigma, double profile_sigma, double psf_sigma_px) {
  const int k = BracketedStep(profile);
  if (k < 0) return kNaN;
  const ClippedEdgeModel model(profile, first_row, k, clip, pixel_sigma, profile_sigma,
                               psf_sigma_px);
  // The most probable edge row with a scale-invariant prior on the unknown clipped level
  // (density 1 / level): minimise chi-square + 2 ln(level). Where two rows are lit the
  // chi-square decides and the prior hardly moves the row; where one is, the chi-square is flat
  // towards more light and the prior picks the least light that still reaches the clip; an
  // edge a pixel further on, lit in the row only by the blur's far tail with a level hundreds
  // of times the clip, pays 2 ln of that factor.
  const auto cost = [&](double y) {
    const ClippedFit fit = model.At(y);
    return fit.level > 0 ? fit.chi2 + 2.0 * std::log(fit.level) : kInf;
  };
  return MinimiseOverRow(cost, first_row, k, kPlateClipCoarsePx, kPlateClipTolerancePx);
}

namespace {

// The row of an edge whose model is `model` (step k of a profile from first_row) at `level`.
double RowAtLevel(const ClippedEdgeModel& model, int first_row, int k, double level,
                  double* chi2) {
  return MinimiseOverRow([&](double y) { return model.Chi2(y, level); }, first_row, k,
                         kLevelRowCoarsePx, kPlateClipTolerancePx, chi2);
}

}  // namespace

double ClippedEdgeRowAtLevel(const ClippedEdgeProfile& p, double level, double psf_sigma_px,
                             double* chi2, double shared_sigma) {
  const int k = p.valid() ? BracketedStep(p.profile) : -1;
  if (k < 0 || !(level > 0)) return kNaN;
  return RowAtLevel(ModelOf(p, k, psf_sigma_px, shared_sigma), p.first_row, k, level, chi2);
}

namespace {

// The minimum of f over a grid x0 + i step (i = 0 .. n - 1), then golden section between the
// best point's neighbours.
template <typename F>
double GridThenGolden(const F& f, double x0, double step, int n, double tolerance) {
  int best_i = 0;
  double best = kInf;
  for (int i = 0; i < n; ++i) {
    const double v = f(x0 + i * step);
    if (v < best) {
      best = v;
      best_i = i;
    }
  }
  return GoldenMinimumToWidth(f, x0 + std::max(0, best_i - 1) * step,
                       x0 + std::min(n - 1, best_i + 1) * step, tolerance);
}

// The informative frames' models at one blur, and the summed chi-square at a level (each frame
// at its own best row).
struct LevelProblem {
  struct Frame {
    ClippedEdgeModel model;
    int first_row, k;
  };
  std::vector<Frame> frames;
  double least = 0;  // the least level any of them allows

  LevelProblem(const std::vector<const ClippedEdgeProfile*>& profiles, double psf_sigma_px,
               double shared_sigma) {
    for (const ClippedEdgeProfile* p : profiles) {
      const int k = BracketedStep(p->profile);
      frames.push_back({ModelOf(*p, k, psf_sigma_px, shared_sigma), p->first_row, k});
      least = std::max(least, frames.back().model.LeastLevel());
    }
  }

  double Total(double level) const {
    double sum = 0;
    for (const Frame& f : frames) {
      double best = kInf;
      MinimiseOverRow([&](double y) { return f.model.Chi2(y, level); }, f.first_row, f.k,
                      kLevelRowCoarsePx, kLevelRowTolerancePx, &best);
      sum += best;
    }
    return sum;
  }

  // The best level, in ln(level) over kLevelGridLow..kLevelGridHigh x the least level.
  double BestLevel(int grid_points, double tolerance) const {
    const double lo = std::log(kLevelGridLow * least), hi = std::log(kLevelGridHigh * least);
    const auto f = [&](double x) { return Total(std::exp(x)); };
    return std::exp(GridThenGolden(f, lo, (hi - lo) / (grid_points - 1), grid_points, tolerance));
  }
};

// Blur search: sigma over kBlurLowPx .. kBlurLowPx + (kBlurGridPoints - 1) kBlurStepPx, on at
// most kBlurFitFrames frames with a coarser level search per trial blur.
constexpr double kBlurLowPx = 0.2, kBlurStepPx = 0.1;
constexpr int kBlurGridPoints = 13;
constexpr double kBlurTolerancePx = 1e-3;
constexpr size_t kBlurFitFrames = 16;
constexpr int kBlurLevelGridPoints = 25;
constexpr double kBlurLevelTolerance = 3e-4;  // in ln(level)

// At most n of `profiles`, evenly spread.
std::vector<const ClippedEdgeProfile*> Spread(const std::vector<const ClippedEdgeProfile*>& p,
                                              size_t n) {
  n = std::min(n, p.size());
  std::vector<const ClippedEdgeProfile*> out;
  for (size_t u = 0; u < n; ++u) out.push_back(p[u * p.size() / n]);
  return out;
}

}  // namespace

ClippedLevel SharedClippedLevel(const std::vector<const ClippedEdgeProfile*>& frames,
                                double psf_sigma_px, size_t max_frames, bool fit_blur) {
  ClippedLevel out;
  out.psf_sigma = psf_sigma_px;
  out.pixel_sigma = SharedNoise(frames);
  std::vector<const ClippedEdgeProfile*> informative;
  for (const ClippedEdgeProfile* p : frames) {
    if (!p || !p->valid()) continue;
    const int k = BracketedStep(p->profile);
    if (k >= 0 && ModelOf(*p, k, psf_sigma_px, out.pixel_sigma).PartlyLitRows() >= 2) {
      informative.push_back(p);
    }
  }
  out.informative = informative.size();
  if (informative.size() < kClippedLevelMinFrames) return out;
  // The blur: each trial blur's best level, its summed chi-square minimised over the blur.
  if (fit_blur && informative.size() >= kBlurFitMinFrames) {
    const auto few = Spread(informative, kBlurFitFrames);
    const auto at_blur = [&](double sigma) {
      const LevelProblem problem(few, sigma, out.pixel_sigma);
      return problem.Total(problem.BestLevel(kBlurLevelGridPoints, kBlurLevelTolerance));
    };
    out.psf_sigma =
        GridThenGolden(at_blur, kBlurLowPx, kBlurStepPx, kBlurGridPoints, kBlurTolerancePx);
    out.psf_fitted = true;
  }
  // The level, on at most max_frames frames (the cost is per frame and trial level).
  const LevelProblem problem(Spread(informative, std::max(max_frames, kClippedLevelMinFrames)),
                             out.psf_sigma, out.pixel_sigma);
  out.used = problem.frames.size();
  const double x = std::log(problem.BestLevel(kLevelGridPoints, kLevelTolerance));
  const auto f = [&](double t) { return problem.Total(std::exp(t)); };
  const double fx = f(x);
  out.value = std::exp(x);
  // Uncertainty: where the summed chi-square rises by 1 (by the reduced chi-square when the
  // model fits worse than the noise says), from its curvature in ln(level).
  const double h = 0.01;
  const double curvature = (f(x + h) - 2 * fx + f(x - h)) / (h * h);
  const double n = double(problem.frames.size());
  const double dof = n * (2 * kBracketRows + 1) - n - 1;
  const double scale = std::max(1.0, fx / std::max(1.0, dof));
  out.err = curvature > 0 ? out.value * std::sqrt(2.0 * scale / curvature) : kInf;
  return out;
}

size_t RefitClippedRows(const std::vector<const ClippedEdgeProfile*>& frames,
                        const ClippedLevel& level, std::vector<double>* rows) {
  if (!level.found()) return 0;
  size_t replaced = 0;
  for (size_t i = 0; i < frames.size() && i < rows->size(); ++i) {
    if (!frames[i] || !frames[i]->valid()) continue;
    const ClippedEdgeProfile& p = *frames[i];
    const int k = BracketedStep(p.profile);
    if (k < 0) continue;
    const ClippedEdgeModel model = ModelOf(p, k, level.psf_sigma, level.pixel_sigma);
    double shared = kInf;
    const double row = RowAtLevel(model, p.first_row, k, level.value, &shared);
    if (!std::isfinite(row)) continue;
    // Only a frame with two partly lit rows can show that its level is not the shared one (one
    // lit row fits any level at some row): its own fit, level free, with the same blur and noise.
    if (model.PartlyLitRows() >= 2) {
      double own = kInf;
      MinimiseOverRow([&](double y) { return model.At(y).chi2; }, p.first_row, k,
                      kPlateClipCoarsePx, kPlateClipTolerancePx, &own);
      if (shared > own + kSharedLevelMaxExtraChi2) continue;
    }
    (*rows)[i] = row - p.row_shift;
    ++replaced;
  }
  return replaced;
}

}  // namespace dimer::tracking
