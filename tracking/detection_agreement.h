#pragma once
// The learnt appearance refereed by the sphere's own detections: over the learning frames, the
// positions the appearance registered at must move as the rough centres do (the existing
// methods' or the highlights' positions, learn_method.h), whatever constant offset lies between
// them. Something in view that does not move with the sphere (a ruler's or a backdrop's edge
// behind it) can hold the registrations where it is: on POV-Ray ruler_above_plate the hopping
// sphere's first learnt rows spread 0.27 px over the learning frames while its rough rows
// spread 2.36 px and it rose 11 px, and a track from them put it within a pixel of its resting
// row throughout. The dimer's length cannot tell (a sphere of a level dimer that rises 11 px
// changes the length by 0.44 px); this can. A sphere it rejects is learnt again without what
// stands still behind it (learn_method.h, RelearnHeldSpheres), and this referee judges the new
// appearance too; where it still disagrees, the track says so.
//
// Along each axis the rough positions are regressed on the learnt ones: a sphere followed by
// both gives a slope near 1, within what the rough methods' own motion bias allows (their
// rows follow a front-lit sphere's hop 1.3-1.6 times over: POV-Ray front_point and its
// seeds, defocus, mains_flicker), and a learnt position held still gives a large one.
#include <limits>

#include "tracking/sphere/learnt_sphere.h"

namespace dimer::tracking {

// The slope's band outside which the two disagree (1/kDetectionSlopeBand to kDetectionSlopeBand),
// and how many of its standard errors it must lie outside it: a rough position's noise can be
// pixels (POV-Ray coarse_scale: 7.8 px against 0.43 of learnt motion) and its slope's error is
// itself estimated, so a warning on a film where both follow the sphere stays rare (4 sigmas:
// POV-Ray ruler_above_plate's held rows lie 7.8 outside).
inline constexpr double kDetectionSlopeBand = 2.5;
inline constexpr double kDetectionSlopeSigmas = 4.0;

struct DetectionAgreement {
  bool agrees = true;  // also where too few frames or too little motion decide nothing
  int axis = 0;        // the axis furthest outside the band (0 column, 1 row)
  double slope = std::numeric_limits<double>::quiet_NaN();      // rough on learnt
  double slope_err = std::numeric_limits<double>::quiet_NaN();  // its standard error
  double learnt_sd = std::numeric_limits<double>::quiet_NaN();  // spread of the learnt, px
  double rough_sd = std::numeric_limits<double>::quiet_NaN();   // of the rough, px
  // The spread of (rough - learnt) about its mean, px: how far the two part from frame to frame
  // once their constant offset is removed. Where they disagree it enters the axis's stated
  // uncertainty (WidenForDisagreement).
  double residual_sd = std::numeric_limits<double>::quiet_NaN();
};

// From `s.rough` and `s.registered` (the same learning frames).
DetectionAgreement AgreementWithDetections(const LearntSphere& s);

// The stated uncertainty of a sphere's position on `a.axis`, `err`, widened where the learnt
// positions disagree with the detections: hypot(err, a.residual_sd). The tracker cannot tell
// which of the two is right, and the learnt positions may be held pixels off (on POV-Ray
// ruler_above_plate the first appearance's rows were 6.3 px off stating 0.56; with the
// residual, 2.0); where they agree, `err` unchanged.
double WidenForDisagreement(const DetectionAgreement& a, double err);

}  // namespace dimer::tracking
