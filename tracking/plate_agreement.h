#pragma once
// The learnt appearance refereed by the plate the sphere stands on: over the frames where a
// sphere rests, its row must move with the plate's edge row (the slope of one on the other is
// the edge's scale to the contact line's, 1 where the edge is the contact line and within
// about 15 % of it where the camera sees an edge nearer or further than the dimer: plate_contact.h,
// FitPlateMotionScale). Something that stands still behind a resting sphere (a ruler's edge)
// can hold its learnt rows where it is: on POV-Ray ruler_above_plate the resting left sphere's
// rows moved 0.09 px per px of the plate's over the learning frames, and its tracked rows
// scattered 0.14 px about the truth. Its rough centres are too noisy to tell (the detections'
// referee, detection_agreement.h, saw 2.8 standard errors); the plate, found to 0.03 px, can.
// A sphere it rejects is learnt again without what stands still behind it
// (learn_method.cc, RelearnHeldByThePlate).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace dimer::tracking {

// The slope's band outside which the sphere does not move with the plate
// (1/kPlateSlopeBand to kPlateSlopeBand), and how many of its standard errors it must lie
// outside it: an edge seen 15 % nearer or further than the dimer is inside (PlateAgreement.
// AnEdgeSeenNearerOrFurtherThanTheDimerAgrees: 0.7-1.4); a held row (0.09 on the ruler) far
// outside, and so is one held by half: on the ruler's 20-frame film, once the hopping sphere's
// still background was cut with its margin (kStillBackgroundMarginPx), the resting sphere's
// followed rows moved 0.50 +- 0.004 px per px, and held so they scattered 0.135 px about the
// truth; with a band of 2 it was not learnt again (povray.detection_agreement).
inline constexpr double kPlateSlopeBand = 1.5;
inline constexpr double kPlateSlopeSigmas = 4.0;
// Fewer resting frames than this decide nothing.
inline constexpr size_t kMinPlateAgreementFrames = 8;

struct PlateAgreement {
  bool agrees = true;  // also where too few resting frames or too little plate motion decide
  double slope = std::numeric_limits<double>::quiet_NaN();      // row on edge row, resting
  double slope_err = std::numeric_limits<double>::quiet_NaN();  // its standard error
  size_t frames = 0;                                            // resting frames
  double edge_sd = 0;  // the plate edge's spread over them, px
};

// `edge` the plate's edge row under the sphere and `row` its row per frame (registered or
// followed; NaN: none), over the same frames; `resting` (may be null): 1 for each frame it
// rests in (FitRestingLine).
PlateAgreement AgreementWithPlate(const std::vector<double>& edge, const std::vector<double>& row,
                                  std::vector<uint8_t>* resting = nullptr);

// Whether `after` moves more nearly with the plate than `before`: its slope nearer 1 by more
// than twice their errors combined.
bool MovesMoreWithThePlate(const PlateAgreement& after, const PlateAgreement& before);

// The stated uncertainty of a sphere's rows, `err`, widened where a resting sphere's rows were
// held (learnt again, or rejected): by how far they part from moving with the plate over its
// excursion, |1 - slope| x edge_sd. Elsewhere `err` unchanged (an edge seen nearer or further
// than the dimer has a slope of its own: FitPlateMotionScale).
double WidenForPlate(const PlateAgreement& a, bool held, double err);

}  // namespace dimer::tracking
