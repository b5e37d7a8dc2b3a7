#pragma once
// `--method auto`: which sub-pixel method suits this footage, decided once per sequence from the
// learning frames (appearance_model.h) as the existing methods measure them.
//
// The centroid (and discfit) are unbiased exactly when a sphere is a clean uniform silhouette
// (backlit, a bright background, matte discs): then they reach the noise limit and need no
// learning, so auto keeps them (the centroid here; which of the two runs, the film's first
// frames decide: method_trial.h, TrySilhouetteMethods). A sphere that is not uniform (polished
// steel under front light: highlights, reflections, a dim rim) goes to the rim fit in those
// methods, whose result depends on a rim contrast a given camera and lighting may not have
// (pixels of bias on ray-traced steel); auto then takes the template method, which assumes no
// appearance. Too few spheres found by the silhouette detector also means the footage is not
// silhouettes.
#include <array>
#include <string>
#include <vector>

#include "tracking/sphere/measure_sphere.h"
#include "tracking/frame_follower.h"

namespace dimer::tracking {

// Fraction of sphere measurements (two per learning frame) that must be clean silhouettes for
// auto to keep the centroid.
inline constexpr double kAutoUniformFraction = 0.9;
// A clean silhouette: the sphere's body (the annulus [0.4 R, 0.8 R]) and the ring just outside
// its edge are each uniform, and their levels differ by at least this many times the larger
// robust spread of the two. A sphere that is dark above and bright below (steel reflecting a lit
// plate) passes the refiner's level test from one side (the polarity follows the frame's
// median) but fails this one. The outer few pixels of the body are left out: a steel sphere in
// front of a glowing backdrop reflects it at grazing angles, a thin bright rim that does not
// bias a silhouette's centroid.
inline constexpr double kCleanContrastToSpread = 8.0;
inline constexpr double kBodyInnerR = 0.4, kBodyOuterR = 0.8;
// The outside ring: [R + 1.5, R + 3.5], px.
inline constexpr double kRingInnerPx = 1.5, kRingWidthPx = 2.0;

// Whether the sphere at `centre` (radius R) in `frame` is a clean silhouette; the rod (toward
// `other`) and the plate rows are left out of the rings.
bool CleanSilhouette(const cv::Mat& frame, const Eigen::Vector2d& centre, double radius_px,
                     const Eigen::Vector2d& other, double plate_row);

struct MethodChoice {
  Method method = Method::kCentroid;
  std::string reason;       // one line: the evidence, for stderr and the track file
  bool silhouettes = false; // clean uniform silhouettes (the centroid is unbiased on them)
};

// From the existing methods' measurements of the learning frames (`clean`: per probe and
// sphere, CleanSilhouette). `requested` is kAuto, or a method asked for explicitly (kept, with
// the evidence as the reason).
MethodChoice ChooseMethod(const std::vector<FrameTrack>& probes,
                          const std::vector<std::array<bool, 2>>& clean, Method requested);

}  // namespace dimer::tracking
