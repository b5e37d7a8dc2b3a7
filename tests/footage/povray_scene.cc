#include "tests/footage/povray_scene.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include "common/error.h"

namespace dimer::footage {
namespace {

constexpr std::pair<Lighting, const char*> kLightingNames[] = {
    {Lighting::kFrontPoint, "front_point"},
    {Lighting::kFrontSoftbox, "front_softbox"},
    {Lighting::kBrightBackground, "bright_background"},
    {Lighting::kMatte, "matte"},
    {Lighting::kBacklit, "backlit"},
    {Lighting::kOneSidedGainRamp, "one_sided_gain_ramp"},
    {Lighting::kUnderexposed, "underexposed"},
    {Lighting::kOverexposed, "overexposed"},
    {Lighting::kMirrorPlate, "mirror_plate"},
    {Lighting::kRingLight, "ring_light"},
    {Lighting::kClutteredBackdrop, "cluttered_backdrop"},
    {Lighting::kRulerAbovePlate, "ruler_above_plate"},
};

constexpr double kMm = 1000.0;  // scene units per metre

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string Vec(double x, double y, double z) {
  return "<" + Num(x) + ", " + Num(y) + ", " + Num(z) + ">";
}

// One POV-Ray array of the sub-frame values picked by `get`.
template <class Get>
std::string Array(const char* name, const std::vector<Instant>& subframes, Get get) {
  std::string s = "#declare " + std::string(name) + " = array[" +
                  std::to_string(subframes.size()) + "] {";
  for (size_t k = 0; k < subframes.size(); ++k) s += (k ? ", " : " ") + Num(get(subframes[k]));
  return s + " };\n";
}

// Polished steel: a dim metallic mirror with a sharp specular highlight for each point light.
// The reflected environment (dark room, lit plate) and the highlights are all the sphere shows.
const char* kSteel =
    "texture { pigment { rgb 0.75 }\n"
    "  finish { ambient 0 emission 0 diffuse 0.03 specular 0.8 roughness 0.0006 metallic\n"
    "           reflection { 0.55 metallic } } }";
// Matte paint: Lambertian, no highlight, no reflection.
const char* kPaint =
    "texture { pigment { rgb 0.8 } finish { ambient 0 emission 0 diffuse 0.85 specular 0 } }";
// The plate: bead-blasted aluminium (diffuse grey, a faint broad sheen).
const char* kPlate =
    "texture { pigment { rgb 0.45 }\n"
    "  finish { ambient 0 emission 0 diffuse 0.7 specular 0.1 roughness 0.05 } }";
// A polished plate: mirrors the spheres below its top edge.
const char* kMirrorPlate =
    "texture { pigment { rgb 0.3 }\n"
    "  finish { ambient 0 emission 0 diffuse 0.25 specular 0.5 roughness 0.002\n"
    "           reflection { 0.6 } } }";

// Two point lamps in front, above and to either side of the camera, as in the reference footage.
const char* kFrontLamps =
    "light_source { <-250, 300, -550> rgb 0.9 }\n"
    "light_source { <300, 220, -600> rgb 0.8 }\n";

std::string Lights(Lighting l) {
  switch (l) {
    case Lighting::kFrontPoint:
    case Lighting::kMatte:
    case Lighting::kUnderexposed:
    case Lighting::kOverexposed:
    case Lighting::kMirrorPlate:
      return std::string(kFrontLamps) + "background { rgb 0 }\n";
    case Lighting::kFrontSoftbox:
      // A soft box 400 mm across, 500 mm from the dimer: an area light (5x5 lamps, adaptive,
      // no jitter: deterministic) and its glowing round diffuser facing the dimer, which the
      // steel mirrors as a bright patch instead of a point.
      return "#declare BoxAt = <-250, 250, -380>;\n"
             "light_source { BoxAt rgb 1.1 area_light <400, 0, 0>, <0, 400, 0>, 5, 5\n"
             "  adaptive 1 circular orient }\n"
             "disc { BoxAt, -BoxAt, 200\n"
             "  texture { pigment { rgb 1 } finish { ambient 0 diffuse 0 emission 0.9 } }\n"
             "  no_shadow }\n"
             "light_source { <300, 220, -600> rgb 0.5 }\n"
             "background { rgb 0 }\n";
    case Lighting::kBrightBackground:
      return std::string(kFrontLamps) +
             "plane { z, 150 texture { pigment { rgb 0.45 } finish { ambient 0 diffuse 1 } } }\n";
    case Lighting::kBacklit:
      // A glowing diffuser behind the dimer and no front light: silhouettes, with the steel
      // reflecting the diffuser as a thin bright rim just inside the outline.
      return "plane { z, 150 texture { pigment { rgb 1 } finish { ambient 0 diffuse 0 "
             "emission 0.85 } } }\n";
    case Lighting::kOneSidedGainRamp:
      return "light_source { <-500, 150, -300> rgb 1.3 }\nbackground { rgb 0 }\n";
    case Lighting::kClutteredBackdrop:
      // What stands around a dimer in a lab: a grey wall 150 mm behind it, lit by the same
      // lamps, with a white ruler across it above the dimer (black ticks every 5 mm, taller
      // every 10), its edges steps larger than the plate's; two steel bolt heads on the plate
      // beside the dimer; the steel's rims mirror the wall. A scene the
      // tracker was not tuned on, to find faults (see povray.targets.cluttered_backdrop).
      {
        std::string s = std::string(kFrontLamps) +
                        "plane { z, 150 texture { pigment { rgb 0.12 } finish { ambient 0 "
                        "diffuse 1 } } }\n"
                        "box { <-2000, 26, 148>, <2000, 40, 149.5>\n"
                        "  texture { pigment { rgb 0.9 } finish { ambient 0 diffuse 1 } } }\n";
        for (int mm = -150; mm <= 150; mm += 5) {
          const double top = mm % 10 == 0 ? 34 : 30;
          s += "box { " + Vec(mm - 0.3, 26, 147.5) + ", " + Vec(mm + 0.3, top, 148) +
               " texture { pigment { rgb 0.02 } finish { ambient 0 diffuse 1 } } }\n";
        }
        // Two steel bolt heads on the plate either side of the dimer (they ride with it).
        s += "cylinder { <-45, PZ[K], 0>, <-45, PZ[K] + 3, 0>, 4.5\n  " + std::string(kSteel) +
             " }\n";
        s += "cylinder { <52, PZ[K], 6>, <52, PZ[K] + 3, 6>, 4.5\n  " + std::string(kSteel) +
             " }\n";
        return s;
      }
    case Lighting::kRulerAbovePlate:
      // A white ruler on a stand 25 mm behind the dimer (5 mm behind the plate's back edge),
      // from 2.5 to 6 mm above the plate's mean top: in the frames a white band from 29 to 12
      // px above the plate's edge, behind the spheres' lower halves, its edges steps of twice
      // the plate's. Taken from the image alone the plate was the ruler's lower edge, 11 px
      // high; it is the edge the dimer stands on (povray.plate.ruler_above_plate;
      // sphere/detector.h).
      return std::string(kFrontLamps) + "background { rgb 0 }\n" +
             "box { <-2000, 2.5, 25>, <2000, 6, 26>\n"
             "  texture { pigment { rgb 0.9 } finish { ambient 0 diffuse 1 } } }\n";
    case Lighting::kRingLight: {
      // The lighting machine-vision setups use on axis: 16 LEDs on a ring 60 mm in radius
      // around the lens (10 mm in front of the pinhole, 0.7 m away), behind a glowing diffuser
      // ring that the steel mirrors near each sphere's centre. Not used to tune the tracker.
      std::string s;
      constexpr int kLeds = 16;
      for (int i = 0; i < kLeds; ++i) {
        const double a = 2.0 * M_PI * (i + 0.5) / kLeds;
        s += "light_source { " + Vec(60 * std::cos(a), 60 * std::sin(a), -690) + " rgb 0.09 }\n";
      }
      return s +
             "torus { 60, 6 rotate -90 * x translate <0, 0, -688>\n"
             "  texture { pigment { rgb 1 } finish { ambient 0 diffuse 0 emission 0.9 } }\n"
             "  no_shadow }\n"
             "background { rgb 0 }\n";
    }
  }
  return "";
}

}  // namespace

std::string ToString(Lighting l) {
  for (const auto& [value, name] : kLightingNames) {
    if (value == l) return name;
  }
  return "?";
}

Lighting ParseLighting(const std::string& name, const std::string& option) {
  std::string known;
  for (const auto& [value, n] : kLightingNames) {
    if (name == n) return value;
    known += (known.empty() ? "" : ", ") + std::string(n);
  }
  throw UsageError(option + " '" + name + "': expected one of " + known);
}

const std::vector<Lighting>& AllLightings() {
  static const std::vector<Lighting> all = [] {
    std::vector<Lighting> v;
    for (const auto& [value, name] : kLightingNames) v.push_back(value);
    return v;
  }();
  return all;
}

Instant FromPose(const DimerShape& shape, double x, double z, double theta, double plate_z) {
  const Eigen::Vector2d half = 0.5 * shape.CentreDistance() *
                               Eigen::Vector2d(std::cos(theta), std::sin(theta));
  Instant s;
  s.left = Eigen::Vector2d(x, z) - half;
  s.right = Eigen::Vector2d(x, z) + half;
  s.plate_z = plate_z;
  return s;
}

int Camera::RenderHeight() const {
  // Rows of an image centred on the optical axis that contains the output frame: 2 h + 1 when
  // the axis is in the lower part of the frame (crop the top rows), else mirrored.
  const double h = horizon_row >= 0.5 * (height - 1) ? horizon_row : height - 1 - horizon_row;
  return int(std::lround(2 * h + 1));
}

int Camera::RenderTop() const {
  return horizon_row >= 0.5 * (height - 1) ? 0 : RenderHeight() - height;
}

Eigen::Vector2d Camera::Project(double x, double y, double z) const {
  const double dx = x - centre_x, dy = y + distance, dz = z - elevation;
  const double f = FocalPx();
  // Offsets from the axis's pixel along the world's right (a) and up (b), then seen along the
  // rolled camera's right (cos, sin) and up (-sin, cos) axes; rows grow downward.
  const double a = f * dx / dy, b = f * dz / dy;
  const double roll = roll_deg * std::numbers::pi / 180.0, c = std::cos(roll), s = std::sin(roll);
  return {0.5 * (width - 1) + a * c + b * s, horizon_row + a * s - b * c};
}

double Camera::PlateRowAt(double plate_z, double col) const {
  // The plate's line in the dimer plane is straight in the image (a pinhole keeps lines): its
  // row at `col` from two of its points a metre apart either side of the axis.
  const Eigen::Vector2d p = Project(centre_x - 0.5, 0, plate_z);
  const Eigen::Vector2d q = Project(centre_x + 0.5, 0, plate_z);
  return p.y() + (q.y() - p.y()) * (col - p.x()) / (q.x() - p.x());
}

std::string Camera::PovCamera() const {
  // Screen of RenderHeight() x width pixels, one unit per pixel at distance f: the ray of pixel
  // (i, j) of the full image is direction + ((i + 0.5) / W - 0.5) right + (0.5 - (j + 0.5) / H) up.
  // A roll turns right and up about the direction (POV-Ray's x right, y up).
  const int hr = RenderHeight();
  const double roll = roll_deg * std::numbers::pi / 180.0, c = std::cos(roll), s = std::sin(roll);
  // (A level camera's statement is written as before the roll existed, so cached footage stays.)
  const std::string right = roll_deg == 0 ? Vec(width, 0, 0) : Vec(width * c, width * s, 0);
  const std::string up = roll_deg == 0 ? Vec(0, hr, 0) : Vec(-hr * s, hr * c, 0);
  return "camera { perspective\n  location " + Vec(0, kMm * elevation, -kMm * distance) +
         "\n  right " + right + "\n  up " + up +
         "\n  direction " + Vec(0, 0, FocalPx()) + "\n}\n";
}

std::string Camera::Check() const {
  std::string bad;
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad += (bad.empty() ? "" : "; ") + what;
  };
  need(width >= 16 && width <= 8192, "--width must be 16..8192 px");
  need(height >= 16 && height <= 8192, "--height must be 16..8192 px");
  need(m_per_px > 0 && std::isfinite(m_per_px), "--m-per-px must be > 0");
  need(distance > 0.05 && std::isfinite(distance), "--distance must be > 0.05 m");
  need(std::isfinite(elevation), "--elevation must be finite");
  need(std::isfinite(roll_deg) && std::abs(roll_deg) <= 10, "--roll-deg must be within +-10");
  need(!std::isinf(centre_x), "camera centre x must be finite (NaN: automatic)");
  need(std::isfinite(horizon_row) && horizon_row >= 0 && horizon_row <= height - 1 &&
           std::abs(2 * horizon_row - std::round(2 * horizon_row)) < 1e-9,
       "--horizon-row must be an integer or half-integer row inside the frame");
  return bad;
}

std::string SceneText(Lighting lighting, const DimerShape& shape, const Camera& camera,
                      const SceneOptions& scene, const std::vector<Instant>& subframes) {
  const double cx = camera.centre_x;
  std::string s =
      "// dimerlab test footage, lighting " + ToString(lighting) +
      " (tests/footage/povray_scene.cc). Millimetres; POV x = lab x - centre_x, y = lab z,\n"
      "// z = lab depth y. Rendered as an animation over the sub-frames (motion blur).\n"
      "#version 3.7;\n"
      "global_settings { assumed_gamma 1.0 max_trace_level 10 }\n" +
      camera.PovCamera();
  s += Array("LX", subframes, [&](const Instant& i) { return kMm * (i.left.x() - cx); });
  s += Array("LZ", subframes, [&](const Instant& i) { return kMm * i.left.y(); });
  s += Array("RX", subframes, [&](const Instant& i) { return kMm * (i.right.x() - cx); });
  s += Array("RZ", subframes, [&](const Instant& i) { return kMm * i.right.y(); });
  s += Array("PZ", subframes, [&](const Instant& i) { return kMm * i.plate_z; });
  s += "#declare K = min(frame_number, " + std::to_string(subframes.size() - 1) + ");\n";
  s += "#declare Left = <LX[K], LZ[K], 0>;\n#declare Right = <RX[K], RZ[K], 0>;\n";
  const std::string sphere_tex = lighting == Lighting::kMatte ? kPaint : kSteel;
  const double r = 0.5 * kMm * shape.diameter, rod = 0.5 * kMm * shape.rod_diameter;
  s += "sphere { Left, " + Num(r) + "\n  " + sphere_tex + " }\n";
  s += "sphere { Right, " + Num(r) + "\n  " + sphere_tex + " }\n";
  if (rod > 0) {
    // The rod joins the centres; only the part between the spheres shows.
    s += "#if (vlength(Right - Left) > " + Num(2 * r) + ")\n  cylinder { Left, Right, " +
         Num(rod) + "\n  " + kSteel + " }\n#end\n";
  }
  const double half_depth = 0.5 * kMm * scene.plate_depth;
  s += "box { <-2000, PZ[K] - " + Num(kMm * scene.plate_thickness) + ", " + Num(-half_depth) +
       ">, <2000, PZ[K], " + Num(half_depth) + ">\n  " +
       (lighting == Lighting::kMirrorPlate ? kMirrorPlate : kPlate) + " }\n";
  s += Lights(lighting);
  return s;
}

Camera DefaultCamera(Lighting lighting) {
  Camera c;
  if (lighting == Lighting::kMirrorPlate) {
    // Looking down on the polished plate from 5 mm above it, so that its top surface, and the
    // spheres mirrored in it, show; the plate stays near row 249.5.
    c.elevation = 0.005;
    c.horizon_row = 224.5;
  }
  return c;
}

SceneOptions DefaultSceneOptions(Lighting lighting) {
  SceneOptions s;
  if (lighting == Lighting::kMirrorPlate) s.plate_depth = 0.2;  // a wide polished table
  return s;
}

double LightingGain(Lighting lighting, double col, int width) {
  switch (lighting) {
    case Lighting::kOneSidedGainRamp:
      return 0.5 + col / std::max(1, width - 1);  // 0.5 at the left edge to 1.5 at the right
    case Lighting::kUnderexposed:
      return 0.25;
    case Lighting::kOverexposed:
      return 4.0;
    default:
      return 1.0;
  }
}

}  // namespace dimer::footage
