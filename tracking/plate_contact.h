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

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tracking/sphere/appearance_model.h"

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
// The learning samples are probed first (about kProbeSamples of them, spread out); the rest are
// fitted only if the probe has kMinContactFits fits with a mirror image whose median is at least
// kProbeShiftFraction of kMinPlateShiftPx.
inline constexpr size_t kProbeSamples = 8;
inline constexpr double kProbeShiftFraction = 0.5;

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
  double value = 0;   // px, contact line - found edge, at the edge row `edge_ref`
  double err = std::numeric_limits<double>::quiet_NaN();
  double edge_ref = std::numeric_limits<double>::quiet_NaN();  // median edge row of the fits
  size_t fits = 0;    // sphere-frames with a mirror image it rests on
  std::string reason; // why applied or not, for stderr and the track file
};

// The far edge is further from the camera than the contact line, so it moves less with the
// plate: by D_contact / D_far (7/8 on the POV-Ray mirror plate, whose amplitude read off the
// edge was 12 % low). A sphere resting on the plate moves with the contact line itself, so the
// slope of its tracked row against the edge row, over the frames where it rests, is the scale
// from edge motion to contact-line motion. Resting frames: the lower envelope of edge - row
// (a sphere in flight is higher), kept by a straight-line fit and refitted. The sphere with more
// resting frames is used; fitted only with at least kMinScaleFrames of them and the edge
// spreading over kMinScaleSpreadPx (standard deviation), else scale 1.
inline constexpr size_t kMinScaleFrames = 10;
inline constexpr double kMinScaleSpreadPx = 0.2;
// A frame rests when its row is within this of the line (the tracker's scatter is ~0.03 px; a
// sphere that lifts by more than this is in flight).
inline constexpr double kRestBandPx = 0.15;

struct PlateMotionScale {
  bool fitted = false;
  // Given by the user instead (`track --plate-m-per-px`: the edge's own scale over the dimer
  // plane's); not fitted then.
  bool given = false;
  double scale = 1;   // contact-line motion per px of edge motion
  double err = std::numeric_limits<double>::quiet_NaN();
  double edge_ref = 0;  // the edge row the motion is scaled about (ContactRow)
  size_t frames = 0;  // resting frames it rests on
  int sphere = -1;    // 0 left, 1 right
};

// The plate edge a camera sees is seldom in the dimer's plane: a plate seen from the side shows
// its front edge, nearer the camera by half the plate's depth, and it moves more pixels per
// metre than the dimer does (by D_dimer / D_edge: 2.9 % on the POV-Ray film, 7 % for a 100 mm
// deep plate filmed from 0.7 m). Read with the dimer plane's scale, the plate's amplitude, and
// Gamma, come out that much high. A user who calibrates the edge's scale too
// (`--plate-m-per-px`) gives the ratio: contact-line px per edge px = plate m/px / dimer m/px.
// The edge is scaled about its median row (the plate's mean position: row0 is unchanged), or,
// where the mirror-image shift was measured, about the edge row it was measured at.
PlateMotionScale GivenPlateMotionScale(double scale, const std::vector<double>& edge,
                                       const PlateShift& shift);

// `edge` the found edge row per frame, `rows[k]` sphere k's tracked row per frame (NaN: none);
// scaled about `shift.edge_ref`.
PlateMotionScale FitPlateMotionScale(const std::vector<double>& edge,
                                     const std::array<std::vector<double>, 2>& rows,
                                     const PlateShift& shift);

// The straight line row = a + b edge through the frames where a sphere rests, `edge` the found
// edge row per frame and `row` the sphere's row (NaN: none): FitPlateMotionScale's fit, which
// the plate's referee of a learnt appearance uses too (plate_agreement.h).
struct RestingLine {
  double a = 0, b = 1;
  double b_err = std::numeric_limits<double>::quiet_NaN();
  double edge_sd = 0;  // the edge's spread over the resting frames, px
  size_t n = 0;        // resting frames
  size_t valid = 0;    // frames with both an edge and a row
};
// `resting` (may be null): 1 for each frame the line rests on.
RestingLine FitRestingLine(const std::vector<double>& edge, const std::vector<double>& row,
                           std::vector<uint8_t>* resting = nullptr);

// The contact line's row for a found edge row.
inline double ContactRow(const PlateShift& p, const PlateMotionScale& m, double edge) {
  return edge + (p.applied ? p.value : 0.0) + (m.scale - 1.0) * (edge - m.edge_ref);
}

// From the learning samples (their plate rows and rough centres): the median of
// contact line - found edge over the fits with a mirror image. The fits on `threads` workers
// (the same answer for any count).
PlateShift EstimatePlateShift(const std::vector<LearningSample>& samples, double radius_px,
                              int threads = 1);

}  // namespace dimer::tracking
