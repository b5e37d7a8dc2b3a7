#pragma once
// `--method auto` refereed by the dimer: where the appearance class points at the template (the
// spheres are not clean silhouettes), the silhouette locator is tried beside it on a run of
// consecutive frames and the film itself says which places the spheres better. Two things a
// film of this experiment always carries are checked, whatever the lighting:
//
//  - each centre moves smoothly between impacts (at 2000 frames/s a sphere in flight or at rest
//    follows a low-order curve over a few frames): the third difference of a coordinate is then
//    almost all noise, var = 20 sigma^2 for a centre of scatter sigma, and a median absolute
//    value over the run leaves the impacts out;
//  - the dimer's length is constant (a rigid rod): its third differences, the same way, show a
//    bias that changes with the pose (a rim fit at changing tilts), which smoothness alone
//    might pass.
//
// A method's score is the larger of the two per-centre figures (the length's divided by
// sqrt 2: it is the difference of two centres). The trial sees noise, not a constant bias: on
// POV-Ray matte steel the rim fit scored 0.8 of the template's noise with its rows 1 px off
// (povray.targets.matte), so the silhouette locator replaces the template only where it shows
// at most kTrialMargin of the template's noise (a template that fails to follow), or where the
// template cannot compete. Clean silhouettes
// keep the centroid without a trial: there it reaches the noise limit and the template does
// not do better on any case of the suite (docs/BENCHMARKS.md, bench_tracking_footage). On our
// renderer's backlit sequence (bench_tracking) the template's worst scatter about the truth is
// lower (0.0068 against 0.0085 px), but this trial, run there, ranks the centroid's noise lower
// (0.0043 against 0.0056 px; at R 11.9, 0.0047 against 0.0058): the film cannot tell them apart.
#include <string>
#include <vector>

#include "tracking/frame_follower.h"
#include "tracking/length_constancy.h"
#include "tracking/io/frame.h"

namespace dimer::tracking {

// Consecutive frames tried at the film's start (enough third differences for a median that
// holds over a few impacts; short beside the film) and the fraction of them in which a
// method must find both spheres to compete.
inline constexpr size_t kTrialFrames = 48;
inline constexpr double kTrialMinFoundFraction = 0.9;
inline constexpr double kTrialMargin = 0.5;

struct TrialScores {
  Method method = Method::kCentroid;
  size_t frames = 0;       // trial frames
  size_t both_found = 0;   // frames where the method found both spheres
  double smooth_px = 0;    // RMS over spheres and axes of each centre's noise from smoothness
  double length_px = 0;    // noise of the dimer's length from its constancy
  double score = 0;        // max(smooth_px, length_px / sqrt 2); NaN where it cannot compete
  // The dimer's length over the trial frames against its own noise (length_constancy.h): the
  // template's refers its learning (length_relearn.h).
  LengthConstancy constancy;
};

// `frames` (consecutive, cleaned) followed by one follower with options `o`, in order.
std::vector<FrameTrack> FollowFrames(const std::vector<Frame>& frames, const FollowerOptions& o);

// The noise figures of one method's track of consecutive frames.
TrialScores ScoreTrial(const std::vector<FrameTrack>& track, Method method);

// Whether the silhouette locator's scores `silhouette` replace the template's `tmpl` (the rule
// above).
bool SilhouetteWinsTrial(const TrialScores& tmpl, const TrialScores& silhouette);

// Clean silhouettes: the centroid, or discfit (a fit of the exact pixel-coverage disc, twice
// the centroid's CPU a frame: bench_tracking) where the film shows discfit's noise at most
// kDiscFitMargin of the centroid's. On our renderer's backlit films it scores 0.4-0.6 of the
// centroid's and scatters 0.0017-0.0041 px about the truth against 0.0047-0.0057; on POV-Ray's
// backlit steel both end with the rim fit and score alike, and the centroid is kept
// (docs/BENCHMARKS.md, auto_choice.sh).
inline constexpr double kDiscFitMargin = 0.9;

// Whether discfit's scores `discfit` replace the centroid's `centroid` (the rule above).
bool DiscFitWinsTrial(const TrialScores& centroid, const TrialScores& discfit);

struct MethodTrial {
  std::vector<TrialScores> candidates;  // the template first, then the silhouette locator
  Method chosen = Method::kTemplate;
  std::string reason;  // one clause for the method's reason
};

// Follows `frames` (consecutive, cleaned) with each candidate: `template_options` (the learnt
// appearances) and the same options with the silhouette locator, and chooses by
// SilhouetteWinsTrial. The two run on up to `threads` threads
// (the result does not depend on it).
MethodTrial TryMethods(const std::vector<Frame>& frames, const FollowerOptions& template_options,
                       int threads);

// The same between the silhouette locators: `centroid_options` and the same options with
// discfit, chosen by DiscFitWinsTrial (candidates: the centroid first).
MethodTrial TrySilhouetteMethods(const std::vector<Frame>& frames,
                                 const FollowerOptions& centroid_options, int threads);

}  // namespace dimer::tracking
