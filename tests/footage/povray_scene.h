#pragma once
// The POV-Ray scene of one frame: a pinhole camera, the dimer (two spheres and the rod), the
// plate, and one of several lightings, written as scene-description text. This is test and
// bench infrastructure: footage from a renderer that shares no code with tracking/render.*, so
// the tracker is judged on a look our own renderer did not make.
//
// Coordinates. Lab frame as in docs/FORMATS.md (x to the right, z up, metres; the dimer moves in
// the plane y = 0, depth y grows away from the camera). POV-Ray's frame is left-handed with y up;
// the scene is written in millimetres with
//     pov = (1000 (x - camera.centre_x), 1000 z, 1000 y),
// so POV-Ray's +x is the image's right, +y up, +z away from the camera: its default orientation,
// nothing mirrored.
//
// Camera. A pinhole at (centre_x, -distance, elevation) in the lab, optical axis horizontal
// (along +y), focal length f = distance / m_per_px pixels, so the dimer plane is imaged at
// exactly m_per_px. The optical axis meets the image at column (width - 1) / 2 and row
// `horizon_row` (default 249.5: the plate low in the frame, room above for jumps). POV-Ray has no
// lens shift, so the scene is rendered `RenderHeight()` rows tall with the axis at its centre and
// only the top `height` rows are traced (+SR/+ER) and kept: the same pinhole with a shifted
// sensor. POV-Ray shoots the ray of pixel (i, j) through (i + 0.5, j + 0.5) of the screen
// (verified by a marker test), which is our convention of pixel centres at integer
// coordinates, so
//     col = (width - 1) / 2 + f X / Y,   row = horizon_row - f Z / Y
// with (X, Y, Z) the point relative to the pinhole. Camera::Project is this formula.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace dimer::footage {

enum class Lighting {
  kFrontPoint,        // polished steel, two point lights in front, dark background
  kFrontSoftbox,      // the same with an area light and its bright panel (soft box)
  kBrightBackground,  // polished steel in front of a lit white backdrop
  kMatte,             // matte painted spheres, front point lights, dark background
  kBacklit,           // dark silhouettes against a glowing backdrop, no front light
  kOneSidedGainRamp,  // front_point lit from the left only, sensor gain ramp left to right
  kUnderexposed,      // front_point at a quarter of the exposure
  kOverexposed,       // front_point at four times the exposure (highlights and plate clip)
  kMirrorPlate,       // front_point on a polished plate that mirrors the spheres
  kRingLight,         // polished steel lit by an LED ring around the lens, dark background
  kClutteredBackdrop, // front_point before a grey wall with a white ruler, bolts on the plate
  kRulerAbovePlate,   // front_point with a white ruler behind the dimer, just above the plate
};
std::string ToString(Lighting l);
// Throws UsageError naming the option and listing the accepted names.
Lighting ParseLighting(const std::string& name, const std::string& option = "--lighting");
const std::vector<Lighting>& AllLightings();

struct DimerShape {
  double diameter = 9.5e-3;      // sphere diameter, m
  double aspect_ratio = 3.9;     // A_r: centre distance = (A_r - 1) diameter
  double rod_diameter = 1.5e-3;  // m; 0: no rod
  double CentreDistance() const { return (aspect_ratio - 1.0) * diameter; }
};

// The scene at one instant, lab frame, metres.
struct Instant {
  Eigen::Vector2d left{0, 0}, right{0, 0};  // sphere centres (x, z)
  double plate_z = 0;                       // plate top surface
};

// An instant from the dimer's pose: centre of mass (x, z), axis angle theta (counter-clockwise
// from +x, left -> right), plate height.
Instant FromPose(const DimerShape& shape, double x, double z, double theta, double plate_z);

struct Camera {
  int width = 640, height = 320;  // output frame, px
  double m_per_px = 2.0e-4;       // scale at the dimer plane y = 0, m/px
  double distance = 0.7;          // pinhole to the dimer plane, m
  double elevation = 0.0;         // pinhole height above z = 0 (level with the plate top), m
  double centre_x = 0.0;          // lab x on the optical axis, m
  double horizon_row = 249.5;     // output row of the optical axis (integer or half-integer)
  // Rotation of the camera about its optical axis, degrees, counter-clockwise as seen from behind
  // it: a camera that is not quite level. The image turns clockwise about the axis's pixel, and
  // the plate's edge descends to the right by tan(roll) px per px.
  double roll_deg = 0.0;

  double FocalPx() const { return distance / m_per_px; }
  int RenderHeight() const;       // rows of the full (unshifted) POV-Ray image
  int RenderTop() const;          // its row that is the output's row 0
  // Pixel (col, row) of the lab point (x, y, z), metres; y = 0 is the dimer plane.
  Eigen::Vector2d Project(double x, double y, double z) const;
  Eigen::Vector2d Project(const Eigen::Vector2d& xz) const { return Project(xz.x(), 0, xz.y()); }
  // Row of the plate's top surface in the dimer plane for a plate at height plate_z, at the
  // optical axis's column; with a roll, at column `col` (the line through the plate's projection).
  double PlateRow(double plate_z) const { return Project(centre_x, 0, plate_z).y(); }
  double PlateRowAt(double plate_z, double col) const;
  // The POV-Ray camera statement matching Project().
  std::string PovCamera() const;
  std::string Check() const;      // "" or every invalid field
};

// Parameters of the scene that are not the camera, the dimer or the lighting.
struct SceneOptions {
  double plate_depth = 0.04;      // plate extent in y (toward and away from the camera), m
  double plate_thickness = 0.03;  // m
};

// Scene text of one frame: `subframes` instants (motion blur), the one rendered selected by
// POV-Ray's `frame_number` (0-based; the frame is rendered as an animation over them).
std::string SceneText(Lighting lighting, const DimerShape& shape, const Camera& camera,
                      const SceneOptions& scene, const std::vector<Instant>& subframes);

// The camera and scene of a lighting: level with the plate, a 40 mm deep plate; mirror_plate
// looks down from 5 mm above onto a 200 mm deep polished plate.
Camera DefaultCamera(Lighting lighting);
SceneOptions DefaultSceneOptions(Lighting lighting);

// Sensor gain of the lighting at column `col` (1 for most; the ramp, under- and over-exposure).
double LightingGain(Lighting lighting, double col, int width);

}  // namespace dimer::footage
