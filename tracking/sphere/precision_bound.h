#pragma once
// How precisely any unbiased estimator can place a learnt appearance in a frame: the
// Cramér-Rao bound of a translation of a known image in white noise, sd_axis = sigma /
// sqrt(sum over the used pixels of (dI/d axis)^2). The template method registers the learnt
// appearance by least squares (cv::findTransformECC), which reaches this bound when the
// appearance is exact and the noise white; its measured scatter set beside the bound says how
// much is the method's and how much the footage's (dim footage is bound above the 0.05 px
// target: see povray.precision).
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {

// Pixel noise of a frame, grey levels: the RMS / sqrt(2) of horizontal neighbour differences
// within 4 robust sigmas (edges are a small fraction of the pairs and are left out), over pairs
// clear of black and of the clip by 3 % of full scale. NaN with fewer than 1000 such pairs.
double FrameNoiseSigma(const cv::Mat& frame);

// Bound (col, row) in px on the standard deviation of the located position, from the
// appearance's gradient (central differences over mask pixels whose four neighbours are in the
// mask). The learnt appearance keeps some noise (the mean of the learning frames), whose
// gradient adds to the sum: the bound is then slightly low, never high. NaN for an invalid
// appearance or a flat one.
Eigen::Vector2d TranslationBound(const Appearance& a, double noise_sigma);

}  // namespace dimer::tracking
