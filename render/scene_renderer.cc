#include "render/scene_renderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "common/error.h"
#include "common/disc_coverage.h"
#include "render/seeded_noise.h"

namespace dimer::tracking {
namespace {

// Radiance levels per lighting, as fractions of full scale.
struct Palette {
  double background, sphere, rod, plate_body, plate_edge;
  bool rod_visible, mirror;
};

Palette PaletteFor(Lighting l) {
  switch (l) {
    case Lighting::kDisc: return {0.12, 0.80, 0.12, 0.45, 0.45, false, false};
    case Lighting::kBacklit: return {0.85, 0.10, 0.10, 0.10, 0.10, true, false};
    case Lighting::kReflect: break;
  }
  return {0.05, 0.0, 0.22, 0.28, 0.95, true, true};
}

const std::pair<Lighting, const char*> kLightingNames[] = {
    {Lighting::kDisc, "disc"}, {Lighting::kBacklit, "backlit"}, {Lighting::kReflect, "reflect"}};

// Environment seen by the mirror sphere in reflection direction r (camera frame: x right, y up,
// z toward the camera). Values are radiances before the steel's reflectance.
double Environment(const Eigen::Vector3d& r) {
  static const Eigen::Vector3d kLamps[2] = {Eigen::Vector3d(-0.5, 0.6, 0.6).normalized(),
                                            Eigen::Vector3d(0.6, 0.35, 0.7).normalized()};
  constexpr double kLampRadiusRad = 0.12, kLampEdgeRad = 0.04, kLampRadiance = 3.0;
  constexpr double kLensRadiusRad = 0.15;
  for (const auto& lamp : kLamps) {
    const double angle = std::acos(std::clamp(r.dot(lamp), -1.0, 1.0));
    const double t = std::clamp((kLampRadiusRad + kLampEdgeRad - angle) / kLampEdgeRad, 0.0, 1.0);
    if (t > 0) return kLampRadiance * t + (1 - t) * 0.4;
  }
  if (std::acos(std::clamp(r.z(), -1.0, 1.0)) < kLensRadiusRad) return 0.06;  // camera lens
  if (r.y() < -0.25) return 0.75;  // the lit plate and table below
  if (r.z() < 0) return 0.16 + 0.05 * r.y();  // dim backdrop behind the dimer
  return 0.45 + 0.15 * r.y();  // the room on the camera side
}

// Radiance of the mirror sphere at offset (u, v) from its centre in units of R (v up).
double MirrorRadiance(double u, double v) {
  constexpr double kSteelReflectance = 0.6;
  const double nz = std::sqrt(std::max(0.0, 1.0 - u * u - v * v));
  const Eigen::Vector3d n(u, v, nz);
  const Eigen::Vector3d r = 2.0 * nz * n - Eigen::Vector3d::UnitZ();
  return kSteelReflectance * Environment(r);
}

void DrawPlate(cv::Mat& img, double plate_row, const Palette& p) {
  for (int row = 0; row < img.rows; ++row) {
    const double top = row - 0.5, bottom = row + 0.5;
    const double cover = std::clamp(bottom - plate_row, 0.0, 1.0);
    if (cover <= 0) continue;
    const double band = std::max(
        0.0, std::min(bottom, plate_row + kPlateEdgeBandPx) - std::max(top, plate_row));
    float* px = img.ptr<float>(row);
    const double lit = p.plate_edge * band + p.plate_body * (cover - band);
    for (int col = 0; col < img.cols; ++col) px[col] = px[col] * (1 - cover) + lit;
  }
}

void DrawRod(cv::Mat& img, const SceneGeometry& s, const Palette& p, int ss) {
  if (!p.rod_visible || s.rod_half_width_px <= 0) return;
  const Eigen::Vector2d axis = s.right - s.left;
  const double len = axis.norm();
  if (len <= 0) return;
  const Eigen::Vector2d a = axis / len;
  const double hw = s.rod_half_width_px;
  const int c0 = std::max(0, int(std::floor(std::min(s.left.x(), s.right.x()) - hw - 1)));
  const int c1 = std::min(img.cols - 1, int(std::ceil(std::max(s.left.x(), s.right.x()) + hw + 1)));
  const int r0 = std::max(0, int(std::floor(std::min(s.left.y(), s.right.y()) - hw - 1)));
  const int r1 = std::min(img.rows - 1, int(std::ceil(std::max(s.left.y(), s.right.y()) + hw + 1)));
  for (int row = r0; row <= r1; ++row) {
    float* px = img.ptr<float>(row);
    for (int col = c0; col <= c1; ++col) {
      int inside = 0;
      for (int i = 0; i < ss * ss; ++i) {
        const Eigen::Vector2d q(col - 0.5 + (i % ss + 0.5) / ss, row - 0.5 + (i / ss + 0.5) / ss);
        const Eigen::Vector2d d = q - s.left;
        const double along = d.dot(a), across = std::abs(d.x() * a.y() - d.y() * a.x());
        inside += (along >= 0 && along <= len && across <= hw);
      }
      const double cover = double(inside) / (ss * ss);
      px[col] = float(px[col] * (1 - cover) + p.rod * cover);
    }
  }
}

// Mean mirror radiance over the part of the pixel inside the disc (supersampled); falls back to
// the pixel centre's nearest disc point when no sample lands inside a barely covered pixel.
double MirrorPixel(int col, int row, const Eigen::Vector2d& c, double r, int ss) {
  double sum = 0;
  int n = 0;
  for (int i = 0; i < ss * ss; ++i) {
    const double u = (col - 0.5 + (i % ss + 0.5) / ss - c.x()) / r;
    const double v = -(row - 0.5 + (i / ss + 0.5) / ss - c.y()) / r;
    if (u * u + v * v > 1.0) continue;
    sum += MirrorRadiance(u, v);
    ++n;
  }
  if (n > 0) return sum / n;
  Eigen::Vector2d d((col - c.x()) / r, -(row - c.y()) / r);
  d /= std::max(1.0, d.norm());
  return MirrorRadiance(d.x(), d.y());
}

void DrawSphere(cv::Mat& img, const Eigen::Vector2d& c, double r, const Palette& p, int ss) {
  const int c0 = std::max(0, int(std::floor(c.x() - r - 1)));
  const int c1 = std::min(img.cols - 1, int(std::ceil(c.x() + r + 1)));
  const int r0 = std::max(0, int(std::floor(c.y() - r - 1)));
  const int r1 = std::min(img.rows - 1, int(std::ceil(c.y() + r + 1)));
  for (int row = r0; row <= r1; ++row) {
    float* px = img.ptr<float>(row);
    for (int col = c0; col <= c1; ++col) {
      const double cover = DiscPixelArea(col, row, c, r);
      if (cover <= 0) continue;
      const double level = p.mirror ? MirrorPixel(col, row, c, r, ss) : p.sphere;
      px[col] = float(px[col] * (1 - cover) + level * cover);
    }
  }
}


}  // namespace

std::string ToString(Lighting l) {
  for (const auto& [value, name] : kLightingNames) {
    if (value == l) return name;
  }
  return "?";
}

Lighting ParseLighting(const std::string& name, const std::string& option) {
  for (const auto& [value, n] : kLightingNames) {
    if (name == n) return value;
  }
  throw UsageError(option + " '" + name + "': expected one of disc, backlit, reflect");
}

void RenderOptions::Check() const {
  std::string bad;
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad += (bad.empty() ? "" : "; ") + what;
  };
  need(width >= 16 && width <= 16384, "--width " + std::to_string(width) + ": expected 16..16384");
  need(height >= 16 && height <= 16384,
       "--height " + std::to_string(height) + ": expected 16..16384");
  need(noise >= 0 && std::isfinite(noise), "--noise must be >= 0 grey levels");
  need(std::abs(gradient) < 1, "--gradient must be in (-1, 1)");
  need(bit_depth == 8 || bit_depth == 16,
       "--bit-depth " + std::to_string(bit_depth) + ": expected 8 or 16");
  need(supersample >= 1 && supersample <= 16, "--supersample must be 1..16");
  if (!bad.empty()) throw UsageError(bad);
}

cv::Mat RenderRadiance(const SceneGeometry& scene, const RenderOptions& options) {
  const Palette p = PaletteFor(options.lighting);
  cv::Mat img(options.height, options.width, CV_32F, cv::Scalar(p.background));
  DrawPlate(img, scene.plate_row, p);
  DrawRod(img, scene, p, options.supersample);
  DrawSphere(img, scene.left, scene.radius_px, p, options.supersample);
  DrawSphere(img, scene.right, scene.radius_px, p, options.supersample);
  return img;
}

cv::Mat RenderFrame(const std::vector<SceneGeometry>& exposure, const RenderOptions& options,
                    uint64_t frame_index) {
  cv::Mat sum(options.height, options.width, CV_32F, cv::Scalar(0));
  for (const auto& s : exposure) sum += RenderRadiance(s, options);
  sum /= double(std::max<size_t>(1, exposure.size()));
  const double full = options.bit_depth == 8 ? 255.0 : 65535.0;
  const double sigma = options.noise * full / 255.0;
  Gaussian gauss(FrameSeed(options.seed, frame_index));
  cv::Mat out(options.height, options.width, options.bit_depth == 8 ? CV_8U : CV_16U);
  for (int row = 0; row < out.rows; ++row) {
    const float* in = sum.ptr<float>(row);
    for (int col = 0; col < out.cols; ++col) {
      const double light = 1.0 + options.gradient * ((col + 0.5) / out.cols - 0.5);
      double v = in[col] * light * full;
      if (sigma > 0) v += sigma * gauss.Next();
      v = std::clamp(std::round(v), 0.0, full);
      if (options.bit_depth == 8) {
        out.ptr<uint8_t>(row)[col] = uint8_t(v);
      } else {
        out.ptr<uint16_t>(row)[col] = uint16_t(v);
      }
    }
  }
  return out;
}

}  // namespace dimer::tracking
