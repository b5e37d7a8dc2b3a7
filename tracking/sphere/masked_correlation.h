#pragma once
// The masked correlation coefficient of a template at every whole-pixel place of a small window,
// as cv::matchTemplate(image, templ, res, cv::TM_CCOEFF_NORMED, mask) defines it for a binary
// mask: at each place, Pearson's correlation of the template's and the image's pixels where the
// mask is set.
//
// Why not cv::matchTemplate: with a mask it correlates by Fourier transforms of the whole window
// several times over, whatever the number of places. The tracker's searches are a few pixels
// wide (9 x 9 places about a prediction): there the sums taken directly, row by row over the
// mask's own extent, cost a fraction of that (masked_correlation_test.cc holds the agreement,
// bench_track_e2e the time). Large searches (a whole frame) still go to cv::matchTemplate.
#include <opencv2/core.hpp>

namespace dimer::tracking {

// Places up to which MaskedCorrelation is the cheaper of the two (9 x 9 is the learning's and
// acquisition's search at R = 24 px; a search of 21 x 21 already is not).
inline constexpr int kDirectCorrelationMaxPlaces = 200;

// `res`: CV_32F, (image.rows - templ.rows + 1) x (image.cols - templ.cols + 1), each place's
// coefficient, NaN where the image's masked pixels are all alike (or the template's are).
// image and templ CV_32F, mask CV_8U of templ's size, image at least templ's size.
void MaskedCorrelation(const cv::Mat& image, const cv::Mat& templ, const cv::Mat& mask,
                       cv::Mat* res);

}  // namespace dimer::tracking
