#include "tracking/method_trial.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "common/median.h"
#include "common/parallel_for.h"

namespace dimer::tracking {
namespace {

// A centre of scatter sigma has third differences of variance 20 sigma^2; 1.4826 times the
// median absolute value is their standard deviation for Gaussian noise, impacts left out.
constexpr double kThirdDifferenceVariance = 20.0;
constexpr double kMadToSigma = 1.4826;

// The noise of a coordinate from its third differences over runs of four frames where it is
// known (NaN: unknown); NaN with fewer than 8 such runs.
double NoiseFromThirdDifferences(const std::vector<double>& x) {
  std::vector<double> d;
  for (size_t i = 0; i + 3 < x.size(); ++i) {
    const double v = x[i + 3] - 3 * x[i + 2] + 3 * x[i + 1] - x[i];
    if (std::isfinite(v)) d.push_back(std::abs(v));
  }
  if (d.size() < 8) return std::numeric_limits<double>::quiet_NaN();
  return kMadToSigma * MedianOf(d) / std::sqrt(kThirdDifferenceVariance);
}

// Both candidates followed over `frames` and scored, `a` first, on up to `threads` threads (each
// on its own follower: the scores do not depend on the count).
std::vector<TrialScores> ScoreBoth(const std::vector<Frame>& frames, const FollowerOptions& a,
                                   const FollowerOptions& b, int threads) {
  const std::array<const FollowerOptions*, 2> options{&a, &b};
  std::vector<TrialScores> scores(2);
  ParallelFor(2, threads, [&](size_t i) {
    scores[i] = ScoreTrial(FollowFrames(frames, *options[i]), options[i]->method);
  });
  return scores;
}

std::string Describe(const TrialScores& s) {
  char text[160];
  std::snprintf(text, sizeof text, "%s %.3f px (smoothness %.3f, length %.3f; both in %zu of %zu)",
                ToString(s.method).c_str(), s.score, s.smooth_px, s.length_px, s.both_found,
                s.frames);
  return text;
}

}  // namespace

std::vector<FrameTrack> FollowFrames(const std::vector<Frame>& frames, const FollowerOptions& o) {
  FrameFollower follower(o);
  std::vector<FrameTrack> track;
  for (const Frame& f : frames) track.push_back(follower.Process(f.image, f.index));
  return track;
}

TrialScores ScoreTrial(const std::vector<FrameTrack>& track, Method method) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TrialScores s;
  s.method = method;
  s.frames = track.size();
  std::vector<double> length;
  std::array<std::array<std::vector<double>, 2>, 2> coord;  // [sphere][axis]
  for (const FrameTrack& f : track) {
    const bool both = f.found[0] && f.found[1];
    s.both_found += both;
    length.push_back(both ? (f.centre[1] - f.centre[0]).norm() : nan);
    for (int k = 0; k < 2; ++k) {
      for (int axis = 0; axis < 2; ++axis) coord[k][axis].push_back(f.found[k] ? f.centre[k](axis) : nan);
    }
  }
  double sum2 = 0;
  for (int k = 0; k < 2; ++k) {
    for (int axis = 0; axis < 2; ++axis) {
      const double n = NoiseFromThirdDifferences(coord[k][axis]);
      sum2 += n * n;
    }
  }
  s.smooth_px = std::sqrt(sum2 / 4);
  s.length_px = NoiseFromThirdDifferences(length);
  const bool competes = double(s.both_found) >= kTrialMinFoundFraction * double(s.frames) &&
                        std::isfinite(s.smooth_px) && std::isfinite(s.length_px);
  s.score = competes ? std::max(s.smooth_px, s.length_px / std::sqrt(2.0)) : nan;
  s.constancy = JudgeLengthConstancy(track);
  return s;
}

bool SilhouetteWinsTrial(const TrialScores& tmpl, const TrialScores& silhouette) {
  if (!std::isfinite(silhouette.score)) return false;
  return !std::isfinite(tmpl.score) || silhouette.score <= kTrialMargin * tmpl.score;
}

bool DiscFitWinsTrial(const TrialScores& centroid, const TrialScores& discfit) {
  if (!std::isfinite(discfit.score)) return false;
  return !std::isfinite(centroid.score) || discfit.score <= kDiscFitMargin * centroid.score;
}

MethodTrial TrySilhouetteMethods(const std::vector<Frame>& frames,
                                 const FollowerOptions& centroid_options, int threads) {
  FollowerOptions discfit = centroid_options;
  discfit.method = Method::kDiscFit;
  MethodTrial t;
  t.candidates = ScoreBoth(frames, centroid_options, discfit, threads);
  const bool discfit_better = DiscFitWinsTrial(t.candidates[0], t.candidates[1]);
  t.chosen = discfit_better ? Method::kDiscFit : Method::kCentroid;
  char margin[32];
  std::snprintf(margin, sizeof margin, "%g", kDiscFitMargin);
  t.reason = "; tried on " + std::to_string(frames.size()) + " consecutive frames, the noise the "
             "film shows: " + Describe(t.candidates[0]) + ", " + Describe(t.candidates[1]) +
             "; " +
             (discfit_better ? std::string("discfit, at most ") + margin +
                                   " of the centroid's noise, is run"
                             : std::string("the centroid is kept (discfit is run only at ") +
                                   margin + " of its noise or less)");
  return t;
}

MethodTrial TryMethods(const std::vector<Frame>& frames, const FollowerOptions& template_options,
                       int threads) {
  FollowerOptions silhouette = template_options;
  silhouette.method = Method::kCentroid;
  silhouette.appearance.reset();
  MethodTrial t;
  t.candidates = ScoreBoth(frames, template_options, silhouette, threads);
  const TrialScores& tmpl = t.candidates[0];
  const TrialScores& sil = t.candidates[1];
  const bool silhouette_better = SilhouetteWinsTrial(tmpl, sil);
  t.chosen = silhouette_better ? Method::kCentroid : Method::kTemplate;
  t.reason = "; tried on " + std::to_string(frames.size()) + " consecutive frames, the noise the "
             "film shows: " + Describe(tmpl) + ", " + Describe(sil) + "; " +
             (!silhouette_better ? "the template is kept (the centroid is run only at half its "
                                   "noise or less)"
              : std::isfinite(tmpl.score)
                  ? "the centroid, at most half the template's noise, is run"
                  : "the template found both spheres in too few of them to compete: the "
                    "centroid is run");
  return t;
}

}  // namespace dimer::tracking
