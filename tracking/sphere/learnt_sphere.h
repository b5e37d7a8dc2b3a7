#pragma once
// What learning leaves of one sphere (appearance_model.h, LearnAppearances): its appearance, the
// samples it was learnt from and where they registered, and the offset estimates measured on
// it. A type of its own so that the checks on learnt appearances (appearance_mismatch.h) need
// not include the learning.
#include <Eigen/Core>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "tracking/sphere/template_locator.h"

namespace dimer::tracking {

struct OffsetEstimate {
  double value = 0;                                        // px, reference -> centre
  double err = std::numeric_limits<double>::quiet_NaN();   // standard uncertainty, px
  size_t n = 0;                                            // frames it rests on
  std::string source;  // silhouette | plate_contact(_bounces|_of_other(_outline|_both)) | limb |
                       // whole_outline | symmetry(_and_whole_outline) | none
};

struct LearntSphere {
  Appearance appearance;
  std::vector<size_t> samples;               // learning samples used (both spheres found)
  std::vector<Eigen::Vector2d> rough;        // their rough centres
  std::vector<Eigen::Vector2d> registered;   // their reference positions after learning
  // Re-centred templates: the column of the whole outline (the plate's reflection kept, row
  // fitted) in the final appearance before that reflection was cut, relative to its reference;
  // source "none" where it could not be fitted. The cut appearance's faint upper outline can
  // give no edge at all (a 20-frame mean of under-exposed steel); this one is then the
  // symmetry estimate's cross-check (ColumnWithoutTheUpperOutline).
  OffsetEstimate whole_outline_col{0, std::numeric_limits<double>::quiet_NaN(), 0, "none"};
  // The appearance learnt again with each of kJackknifeGroups groups of its samples left out
  // (sample i in group i mod groups; the same positions and cut): what the samples' noise does
  // to a quantity measured on the appearance shows as that quantity's spread over these
  // (LimbColumnOffset). Empty for appearances not returned by LearnAppearances.
  std::vector<Appearance> jackknife;
  // The positions the appearance is the mean at (its last pass's, before `registered`) and the
  // row its plate reflection was cut from (-1: none): what LearnAppearances redoes for them.
  std::vector<Eigen::Vector2d> averaged;
  int cut_row = -1;
};

}  // namespace dimer::tracking
