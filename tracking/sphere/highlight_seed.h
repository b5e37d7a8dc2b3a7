#pragma once
// Rough sphere centres from the highlights alone, for footage where the silhouette methods find
// nothing (dark steel on a dark background, under-exposed, a ring light): the bright blobs above
// the plate, split into the two spheres' groups by one of two rules, the one whose seeds keep a
// dimer's length apart over the film (SeedFilm). learn_method.cc seeds the appearance
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

// The split the tracker used before SplitHighlights: at the widest gap between the blobs'
// columns (every blob kept), each side's mean position; false when fewer than two blobs or the
// gap is under a radius. A rod's glints between the spheres join one side (ring light: seeds
// 40 px off), but a sphere whose second highlight is too faint to weigh keeps its specks there
// (a cluttered backdrop's limb reflections: SplitHighlights puts such a seed at the bright limb).
bool SplitAtWidestGap(std::vector<HighlightBlob> blobs, double radius_px,
                      std::array<Eigen::Vector2d, 2>* centres);

// Seeds for a film's learning frames (`blobs`: each frame's FindHighlightBlobs). The dimer is
// rigid and a lamp's highlight sits at the same place on both spheres, so right seeds stand the
// same distance apart in every frame. Both splits are made on every frame; the film's is the one
// with more frames whose separation is within `tolerance_px` of its median frame's (`agrees`:
// those whose seeds the learning's search can register; the others have one seed off), then the
// smaller mean absolute deviation from it, the weighed split on a tie; a split seeding fewer
// than `min_frames` frames agrees nowhere. `seeded[i]`: frame i has seeds in `seeds[i]`.
struct HighlightSeeds {
  std::vector<std::array<Eigen::Vector2d, 2>> seeds;
  std::vector<bool> seeded;
  std::vector<bool> agrees;  // seeded, and within the tolerance of the median separation
  bool by_mass = true;  // SplitHighlights, else SplitAtWidestGap
  size_t agreeing = 0, other_agreeing = 0;    // the chosen and the other split's
  double spread_px = 0, other_spread_px = 0;  // the chosen and the other split's
};
HighlightSeeds SeedFilm(const std::vector<std::vector<HighlightBlob>>& blobs, double radius_px,
                        double tolerance_px, size_t min_frames);

// As whole divisors (blobs lighter than a tenth of the heaviest; pairs within a twentieth of the
// heaviest pair), compared by multiplying: a film's levels x 257 (8-bit data in 16 bits) give
// masses x 257 exactly and the same decisions, where a fraction's rounding could flip a tie.
constexpr int kMinMassDivisor = 10;
constexpr int kMassTieDivisor = 20;

// The frame's level step: the greatest common divisor of its levels (1 for most frames; 257 for
// 8-bit data widened to 16 bits, 64 for a 10-bit camera's levels shifted to the top).
double LevelStep(const cv::Mat& image);

}  // namespace dimer::tracking
