#pragma once
// Synthetic side-view frames with exact ground truth: two spheres, the rod between them, the
// plate and its top edge. Geometry is exact and anti-aliased (analytic disc coverage for the
// sphere silhouettes, supersampling for the rod and the mirror shading), so a tracker tested on
// these frames is judged against the true sub-pixel position, not against another estimate.
//
// Lighting (one string table, shared by the CLI, files and ToString):
//  - disc:    idealised bright uniform discs on a dark background; rod invisible. The designed
//             case for accuracy targets (a uniform disc has a known centroid).
//  - backlit: dark silhouettes (spheres, rod, plate) on a bright, slightly graded background.
//  - reflect: front lighting of polished steel. The sphere is a mirror reflecting a distant
//             environment (a dim room, the lit plate below, a dark backdrop behind, the camera
//             lens as a dark spot, and two lamps that make small saturated highlights), seen
//             orthographically: the pattern is fixed relative to the sphere centre, so any
//             tracker bias it causes is constant for a fixed camera and lamps. The plate's lit
//             top edge is the brightest thing in view.
// Noise: Gaussian read noise of `noise` grey levels (8-bit scale), drawn from an explicit
// Box-Muller transform of a std::mt19937_64 seeded per frame from (seed, frame index), so frames
// are identical across platforms, thread counts and rendering order.
#include <opencv2/core.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace dimer::tracking {

enum class Lighting { kDisc, kBacklit, kReflect };
std::string ToString(Lighting l);
// Throws InputError naming `option` and the accepted names for an unknown name.
Lighting ParseLighting(const std::string& name, const std::string& option = "--lighting");

// Thickness of the plate's lit top edge under reflect lighting, px. The plate-edge locator
// assumes an edge band of at least 4 px or a plain step (see plate_edge.h).
inline constexpr double kPlateEdgeBandPx = 4.0;

struct RenderOptions {
  int width = 512;                  // frame width, px
  int height = 256;                 // frame height, px
  Lighting lighting = Lighting::kReflect;
  double noise = 2.0;               // Gaussian sensor noise sigma, grey levels of 8-bit scale
  double gradient = 0.1;            // illumination change from left to right edge, fraction
  int bit_depth = 8;                // 8 or 16
  int supersample = 4;              // samples per pixel side for rod and mirror shading
  uint64_t seed = 1;                // noise seed

  // Reports every invalid field at once (InputError).
  void Check() const;
};

// The scene at one instant, in pixels (col, row of centres; rows grow downward).
struct SceneGeometry {
  Eigen::Vector2d left{0, 0}, right{0, 0};  // sphere centres, px
  double radius_px = 23.75;                 // sphere radius, px
  double rod_half_width_px = 3.75;          // rod radius, px (0: no rod)
  double plate_row = 200;                   // row of the plate's top surface, px
};

// Noise-free radiance of one instant, CV_32F in [0, 1+] (highlights may exceed 1 before
// clipping), without the illumination gradient.
cv::Mat RenderRadiance(const SceneGeometry& scene, const RenderOptions& options);

// One frame: the mean radiance over the exposure samples (motion blur; pass one sample for
// none), times the illumination gradient, plus noise, quantised to CV_8U or CV_16U.
cv::Mat RenderFrame(const std::vector<SceneGeometry>& exposure, const RenderOptions& options,
                    uint64_t frame_index);

}  // namespace dimer::tracking
