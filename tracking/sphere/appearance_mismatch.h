#pragma once
// Whether two spheres' learnt appearances are alike: the test the row transfer by registration
// rests on (appearance_model.h, TransferOffset).
//
// Why. A sphere that bounces while the other rests takes its row offset from the resting one's
// plate contact, carried over either by registering the two appearances (exact when the two
// spheres look alike, 0.11-0.17 px off where a one-sided light or a soft box lights them unlike)
// or through their outlines (immune to the lighting, but 0.4-0.6 px off where the outline is
// faint: POV-Ray ring_light at 0.7 of its levels). Their midpoint spent the registration's
// precision where it held. Whether it holds can be read from the pixels: once registered, two
// alike appearances differ by their noise only, unlike ones by more; the two transfers are
// weighed with that (CombineRowTransfers, appearance_model.h; see
// AppearanceOffset.RowTransfersAreWeighedByHowAlikeTheAppearancesAre).
//
// Measure: the mean squared difference of `to` shifted onto `from` (cv::findTransformECC's
// translation, RegisterTranslation) over the pixels both know (eroded by the interpolation's
// reach), divided by the mean of the two appearances' per-pixel noise variances. Each variance is
// the jackknife's over the groups of learning frames left out (LearntSphere::jackknife): the
// noise of that mean, the sensor's and the registration's jitter together. About 1 for
// appearances that differ by noise; NaN without jackknives.
#include <algorithm>
#include <cmath>

#include "tracking/sphere/learnt_sphere.h"

namespace dimer::tracking {

// The registered transfer's error where the appearances are unlike, px: at most
// kMismatchRowPx * sqrt(mismatch - 1). Measured against the truth: 0.04-0.085 px per unit of
// sqrt(mismatch - 1) on the POV-Ray films (mismatch 1.4-14; nearer 1, the resting sphere's own
// contact, +-0.03 px, is most of the error) and 0.04-0.054 on the synthetic ones (mismatch
// 3-41, tests/tracking/sphere/appearance_mismatch_test.cc); the envelope taken is above both. It adds
// to the registration's own uncertainty (TransferOffset) in quadrature.
inline constexpr double kMismatchRowPx = 0.1;
inline double RegisteredTransferModelErr(double mismatch) {
  return kMismatchRowPx * std::sqrt(std::max(0.0, mismatch - 1.0));
}

double AppearanceMismatch(const LearntSphere& from, const LearntSphere& to);

}  // namespace dimer::tracking
