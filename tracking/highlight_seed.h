#pragma once
// Rough sphere centres from the highlights alone, for footage where the silhouette methods find
// nothing (dark steel on a dark background, under-exposed, a ring light): the bright blobs above
// the plate, split into the two spheres' groups. template_sequence.cc seeds the appearance
// learning with them; learning re-centres on the plate contact (appearance_model.h), so a
// highlight's height above the centre does not matter, its column does.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <array>
#include <vector>

namespace dimer::tracking {

struct HighlightBlob {
  Eigen::Vector2d centre;  // (col, row) px, the blob's centroid
  double mass = 0;         // sum over its pixels of the level above the highlight level
};

// The highlights above `plate_row` (the plate's highest row): pixels standing well above the
// region's median and above the midpoint between it and the brightest pixel; blobs larger than
// a sphere (a white ruler, a lamp) are left out, with the level set again without them.
std::vector<HighlightBlob> FindHighlightBlobs(const cv::Mat& image, double plate_row,
                                              double radius_px);

// The two spheres' groups among `blobs`: blobs lighter than 1/kMinMassDivisor of the heaviest
// are dropped (glints on the rod, noise), then two disjoint runs of blobs in column order, each
// spanning at most a sphere's diameter, holding the most mass; of the pairs within
// 1/kMassTieDivisor of the heaviest, the one with the widest empty gap between the runs. Each
// group's rough centre is its blobs' mean position. False when there are not two runs, or the
// runs are less than a radius apart (one sphere's highlights, or the plate's).
bool SplitHighlights(std::vector<HighlightBlob> blobs, double radius_px,
                     std::array<Eigen::Vector2d, 2>* centres);

// As whole divisors (blobs lighter than a tenth of the heaviest; pairs within a twentieth of the
// heaviest pair), compared by multiplying: a film's levels x 257 (8-bit data in 16 bits) give
// masses x 257 exactly and the same decisions, where a fraction's rounding could flip a tie.
constexpr int kMinMassDivisor = 10;
constexpr int kMassTieDivisor = 20;

// The frame's level step: the greatest common divisor of its levels (1 for most frames; 257 for
// 8-bit data widened to 16 bits, 64 for a 10-bit camera's levels shifted to the top).
double LevelStep(const cv::Mat& image);

}  // namespace dimer::tracking
