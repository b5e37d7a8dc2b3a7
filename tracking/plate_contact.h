#pragma once
// Where the plate's top surface meets the spheres, when the edge the plate finder sees is not
// that line: a camera above the plate's plane sees the top surface as a band, from its far edge
// (the strongest step, dark backdrop above the lit plate, which plate_edge.h finds) down to its
// front edge; the dimer stands somewhere inside the band. On a polished plate the band shows
// each sphere's mirror image, and a sphere and its image are mirror images of one another about
// the plate's plane: in the picture, about the contact line's row (the camera's small elevation
// makes the image a sphere of the same size mirrored about that row, to far below a pixel).
//
// Measured once per sequence on the learning frames: near each sphere's bottom the picture is
// modelled as the sphere's disc resting on a row c and its mirrored disc below, both of the
// known radius, each pixel's covered fraction computed exactly across the row and on five
// sub-rows down it, and each row's grey levels a straight line in that fraction (its own levels
// inside and outside: the sphere is dark, its image bright, the backdrop changes at the far
// edge). (c, column) minimise the residual: the waist where the two discs meet. It depends on
// the two discs' shapes, not on what the sphere or the plate look like.
//
// Resting, not lifted: a fit that also let the sphere float (its bottom h above c, its image h
// below) put c 0.2-0.3 px low on the POV-Ray mirror plate. The image's top right at the contact
// is dim (what it mirrors there is the shadowed plate under the sphere), so the fit traded it
// for lift. A sphere in flight is then a poor fit; the median over the sphere-frames keeps the
// resting ones.
//
// A plate that shows no mirror image (matte, or its top unseen) gives no evidence below c; the
// fit is then kept out (kMinReflectionChi2), and the found edge is the plate row, as before.
#include <opencv2/core.hpp>

#include <limits>
#include <string>
#include <vector>

#include "tracking/appearance_model.h"

namespace dimer::tracking {

// The fit's window about the found edge: rows from kContactAbovePx above it to kContactBelowPx
// below; the contact line is searched from 1 px above to kContactSearchBelowPx below it.
inline constexpr int kContactAbovePx = 5;
inline constexpr int kContactBelowPx = 9;
inline constexpr double kContactSearchBelowPx = 7.0;
// How far the rough centre's column may be off, px.
inline constexpr double kContactColSearchPx = 2.0;
// The mirror image must lower the residual of the rows below the contact line by this much
// (chi-square, noise from the fit itself): a 5-sigma reflection.
inline constexpr double kMinReflectionChi2 = 25.0;
// The found edge is moved to the contact line only when they differ by at least this much and
// by kPlateShiftSigmas standard errors (the fits of a plate whose edge is the contact scatter
// about zero).
inline constexpr double kMinPlateShiftPx = 0.5;
inline constexpr double kPlateShiftSigmas = 5.0;
inline constexpr size_t kMinContactFits = 3;

struct MirroredContact {
  bool ok = false;
  double row = std::numeric_limits<double>::quiet_NaN();  // contact line, px (pixel centres)
  double col = std::numeric_limits<double>::quiet_NaN();   // sphere centre column, px
  double reflection_chi2 = 0;  // residual the mirror image explains below the line
};

// Fits the sphere + mirror image model near the sphere at column `col_guess` (within
// kContactColSearchPx) whose bottom is near the found plate edge `plate_row`.
MirroredContact FitMirroredContact(const cv::Mat& frame, double col_guess, double radius_px,
                                   double plate_row);

struct PlateShift {
  bool applied = false;
  double value = 0;   // px, added to every frame's found plate row
  double err = std::numeric_limits<double>::quiet_NaN();
  size_t fits = 0;    // sphere-frames with a mirror image it rests on
  std::string reason; // why applied or not, for stderr and the track file
};

// From the learning samples (their plate rows and rough centres): the median of
// contact line - found edge over the fits with a mirror image.
PlateShift EstimatePlateShift(const std::vector<LearningSample>& samples, double radius_px);

}  // namespace dimer::tracking
