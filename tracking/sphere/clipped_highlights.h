#pragma once
// Whether following leaves a sphere's clipped highlights out, decided per film by a test the
// learning frames can make.
//
// Why. A lamp's reflection in a small steel sphere is a few pixels wide; where the camera clips
// it, the blob's shape changes (not only its place) as the sphere crosses a pixel, while the
// learnt appearance is their mean over many sub-pixel phases. Registered with those pixels, the
// position locks toward the pixel grid: 0.06-0.07 px peak to peak on a mirror-lit film at
// R = 11.9 px (bench_tracking's locking column). Left out, the locking went to 0.01-0.02 px;
// but where the clipped highlights carry most of the position (the POV-Ray over-exposed film,
// R = 23.75 px) leaving them out raised the scatter three-fold. Neither is right for every film.
//
// The test (Hausman's: one estimate efficient if unbiased, one unbiased but less efficient).
// Every learning sample is registered by the quick step (fast_follow.h) twice, with the
// appearance's mask whole and with the clipped zone left out: d = the difference of the two
// positions, and each states its standard deviation (RegistrationSigma; the quick step reaches
// it, SphereLocator.TemplateStatesItsScatterAndEccItsBound). Without locking the two differ by
// noise alone, E|d|^2 = sigma_out^2 - sigma_in^2 (the subset's extra noise, Delta). Locking
// that varies with the phase adds its square L^2 (less the zone-free estimate's own, taken as
// small). Leaving out is the better estimate when sigma_out^2 < sigma_in^2 + L^2, that is when
// E|d|^2 > 2 Delta: the ratio E|d|^2 / Delta is compared with kClipLeaveOutRatio.
//
// The clipped zone is fixed to the appearance, not taken from each frame: a zone that moved
// with the frame's own clipped pixels changed its shape with the phase too.
//
// The reference point. The learnt appearance's reference is where the whole appearance
// registers (the offsets to the centre, from its outline, rest on that); the part left out of
// it registers the same frames shifted by the mean of d. The followed appearance is shifted by
// that mean, so that positions keep the reference (the mean is 0.001-0.004 px on the project's
// mirror-lit renders at R = 11.9 px; ClippedHighlights.ShiftedContentRegistersByTheShift).
#include <opencv2/core.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "tracking/sphere/appearance_model.h"
#include "tracking/sphere/learnt_sphere.h"

namespace dimer::tracking {

// A pixel at or above this fraction of the frame's full scale is taken as clipped (a camera of
// fewer bits saturates just below the container's top: 4095 x 16 = 65520).
inline constexpr double kClipLevelFraction = 0.99;
// Leave the zone out when the samples' mean |d|^2 exceeds this many times their mean Delta.
// 2 would make the mean squared errors equal if the zone-free estimate did not lock; it has
// errors of its own, which the test counts against the whole appearance: on the POV-Ray
// over-exposed film the ratio was 2.2 and the zone-free rows scattered 2.3 times more
// (0.030 against 0.013 px). Where clipping locks, the ratio is 9-10 (ClippedHighlights.*), or
// Delta is negative: the clipped pixels fit worse than the noise (a mirror-lit film at
// R = 11.9 px, bench_tracking).
inline constexpr double kClipLeaveOutRatio = 4.0;
// Only clipped pixels within the sphere's radius and this margin of the reference point count:
// a clipped backdrop (a white ruler behind the spheres) is not the sphere's highlight.
inline constexpr double kClipZoneMarginPx = 2.0;
// The test needs this many samples registered both ways.
inline constexpr size_t kClipMinSamples = 8;
// Delta is averaged over every this-many-th sample: the two registrations' variances change
// little from one learning frame to the next, and stating them costs three quick steps each
// (the decision took ~20 ms of a 2,000-frame film's 0.48 s with every sample, bench_track_e2e).
inline constexpr size_t kClipSigmaEvery = 4;

struct ClipDecision {
  Appearance appearance;  // the one to follow: the learnt one, its mask cut where left out
  bool leave_out = false;
  int zone_px = 0;        // the appearance's pixels shaped by clipping (in its mask)
  size_t n = 0;           // samples registered both ways
  double mean_d2 = 0;     // mean |d|^2 over them, px^2
  double mean_delta = 0;  // mean Delta (sigma_out^2 - sigma_in^2 over both axes), px^2
  Eigen::Vector2d mean_d{0, 0};  // mean d, px: what the followed appearance is shifted by
  std::string reason;     // one clause for the track file's method reason
};

// The appearance's pixels within its radius and kClipZoneMarginPx of the reference point that a
// clipped frame pixel of any learning sample fell on (each sample's frame read at its registered
// position; the pixels either side of a fraction both).
cv::Mat ClippedZone(const LearntSphere& s, const std::vector<LearningSample>& samples);

// The appearance's image moved by `by` px (its mask kept, a fraction of a pixel): a frame then
// registers `by` lower against it.
Appearance ShiftContent(const Appearance& a, const Eigen::Vector2d& by);

// The decision for sphere `k` (0 left, 1 right), its samples registered on `threads` threads
// (each on its own: the result does not depend on the count).
ClipDecision DecideClippedHighlights(const LearntSphere& s,
                                     const std::vector<LearningSample>& samples, int k,
                                     int threads);

}  // namespace dimer::tracking
