#include "tests/footage/povray_footage.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <numbers>
#include <random>
#include <sstream>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>

#include "common/atomic_output.h"
#include "common/error.h"
#include "common/interrupt.h"
#include "common/progress.h"
#include "render/seeded_noise.h"

namespace dimer::footage {
namespace fs = std::filesystem;
namespace {

using tracking::FrameSeed;
using tracking::Gaussian;

// Bumped whenever the post-processing changes, so that cached footage is re-rendered.
constexpr const char* kGeneratorVersion = "povray_footage 1";

std::string Num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string Quote(const std::string& s) {  // for the shell: single quotes
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string JsonString(const std::string& s) {
  std::string j = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') j += '\\';
    if (c == '\n') {
      j += "\\n";
      continue;
    }
    j += c;
  }
  return j + "\"";
}

std::string FrameName(size_t i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06zu.png", i);
  return buf;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string LastLines(const std::string& text, int lines) {
  size_t pos = text.size();
  while (pos > 0 && (text[pos - 1] == '\n' || text[pos - 1] == '\r')) --pos;
  for (int k = 0; k < lines && pos != std::string::npos && pos > 0; ++k) {
    pos = text.rfind('\n', pos - 1);
  }
  std::string tail = text.substr(pos == std::string::npos ? 0 : pos);
  for (char& c : tail) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return tail;
}


// The instants of frame i's exposure slices: the middle of each of `n` equal slices of the
// shutter interval centred on the sample time (their mean is the sample time).
std::vector<Instant> Slices(const Motion& m, size_t i, double exposure_s, int n) {
  std::vector<Instant> out;
  for (int k = 0; k < n; ++k) {
    const double offset = exposure_s > 0 ? ((k + 0.5) / n - 0.5) * exposure_s : 0.0;
    out.push_back(m.at(m.t[i] + offset));
  }
  return out;
}

// A lens bends the optical image, which the sensor then integrates over each pixel. So a film
// with a lens is rendered at kLensSupersample times the resolution, bent there and averaged
// over each pixel (INTER_AREA: exact box sums). Bending the 1x render instead (interpolating
// between its pixels) put the plate edge 0.072 px off at worst against 0.033; the spheres'
// mean errors were the same within 0.01 px (see povray.lens).
constexpr int kLensSupersample = 3;

// The camera that renders `c`'s frame at `s` times its resolution: pixel centre u of `c` is
// s u + (s - 1) / 2 of it, so the optical axis and the field of view are the same.
Camera Supersampled(const Camera& c, int s) {
  Camera h = c;
  h.width = c.width * s;
  h.height = c.height * s;
  h.m_per_px = c.m_per_px / s;
  h.horizon_row = s * c.horizon_row + 0.5 * (s - 1);
  return h;
}

// The camera POV-Ray renders with.
Camera RenderCamera(const FootageOptions& o) {
  return o.lens_k1 != 0 ? Supersampled(o.camera, kLensSupersample) : o.camera;
}

// Where each pixel of the distorted image comes from in the pinhole one: the undistorted
// position of its own (x_d = x_u (1 + k1 r_u^2) about the axis), by OpenCV's undistortPoints;
// on the render's (supersampled) grid.
std::pair<cv::Mat, cv::Mat> DistortionMaps(const FootageOptions& o) {
  const Camera cam = RenderCamera(o);
  const cv::Matx33d k = CameraMatrix(cam);
  const std::vector<double> d = {o.lens_k1, 0, 0, 0, 0};
  const int w = cam.width, h = cam.height;
  std::vector<cv::Point2d> at;
  at.reserve(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) at.emplace_back(x, y);
  }
  std::vector<cv::Point2d> from;
  cv::undistortPoints(at, from, k, d, cv::noArray(), k,
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-9));
  cv::Mat mx(h, w, CV_32F), my(h, w, CV_32F);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      mx.at<float>(y, x) = float(from[size_t(y) * size_t(w) + size_t(x)].x);
      my.at<float>(y, x) = float(from[size_t(y) * size_t(w) + size_t(x)].y);
    }
  }
  return {mx, my};
}

// Averaged slices -> lens distortion (at the render's resolution, `lens_maps` from
// DistortionMaps; empty: a pinhole) -> gain -> PSF -> noise -> quantisation.
cv::Mat PostProcess(const std::vector<cv::Mat>& slices, const FootageOptions& o, size_t frame,
                    double t, const std::pair<cv::Mat, cv::Mat>& lens_maps) {
  cv::Mat sum = cv::Mat::zeros(slices[0].size(), CV_32F);
  for (const cv::Mat& s : slices) sum += s;
  const double flicker =
      o.flicker == 0 ? 1.0 : 1.0 + o.flicker * std::sin(2 * std::numbers::pi * o.flicker_hz * t);
  cv::Mat grey = sum * (255.0 * flicker / double(slices.size()));  // 8-bit scale
  if (!lens_maps.first.empty()) {
    // The optical image at kLensSupersample times the resolution, bent by the lens (Lanczos),
    // then integrated over each sensor pixel.
    cv::Mat bent, down;
    cv::remap(grey, bent, lens_maps.first, lens_maps.second, cv::INTER_LANCZOS4,
              cv::BORDER_REPLICATE);
    cv::resize(bent, down, cv::Size(o.camera.width, o.camera.height), 0, 0, cv::INTER_AREA);
    grey = down;
  }
  for (int col = 0; col < grey.cols; ++col) {
    const double gain = LightingGain(o.lighting, col, grey.cols);
    if (gain != 1.0) grey.col(col) *= gain;
  }
  if (o.psf_sigma_px > 0) {
    const int k = 2 * int(std::ceil(3 * o.psf_sigma_px)) + 1;
    cv::GaussianBlur(grey, grey, cv::Size(k, k), o.psf_sigma_px, o.psf_sigma_px,
                     cv::BORDER_REFLECT_101);
  }
  Gaussian noise(FrameSeed(o.seed, frame));
  const double scale = o.bit_depth == 16 ? 257.0 : 1.0, top = o.bit_depth == 16 ? 65535 : 255;
  cv::Mat out(grey.size(), o.bit_depth == 16 ? CV_16U : CV_8U);
  for (int r = 0; r < grey.rows; ++r) {
    const float* g = grey.ptr<float>(r);
    for (int c = 0; c < grey.cols; ++c) {
      const double v = std::clamp(std::round((g[c] + o.noise * noise.Next()) * scale), 0.0, top);
      if (o.bit_depth == 16) {
        out.at<uint16_t>(r, c) = uint16_t(v);
      } else {
        out.at<uint8_t>(r, c) = uint8_t(v);
      }
    }
  }
  return out;
}

std::string TruthCsv(const Motion& m, const FootageOptions& o) {
  const Camera& cam = o.camera;
  const double row0 = cam.PlateRow(0.0), col_offset = cam.Project(0.0, 0.0, 0.0).x();
  const double radius_px = 0.5 * o.shape.diameter / cam.m_per_px;
  std::string s =
      "# dimerlab povray footage truth: sphere centres projected through the pinhole (col, row) "
      "at each frame's sample time; units: t s, *_col *_row plate_row px (0-based pixel "
      "centres, rows growing downward); docs/FORMATS.md\n";
  s += "# m_per_px=" + Num(cam.m_per_px) + " row0=" + Num(row0) + " col_offset=" +
       Num(col_offset) + " radius_px=" + Num(radius_px) + " lighting=" + ToString(o.lighting) +
       " noise=" + Num(o.noise) + " seed=" + std::to_string(o.seed) + "\n";
  s += "frame,file,t,left_col,left_row,right_col,right_row,plate_row\n";
  char buf[256];
  for (size_t i = 0; i < m.t.size(); ++i) {
    const Instant in = m.at(m.t[i]);
    const Eigen::Vector2d l = cam.Project(in.left), r = cam.Project(in.right);
    // The plate's row under the dimer: at the column midway between the centres (the same as
    // anywhere when the camera is level).
    std::snprintf(buf, sizeof buf, "%zu,%s,%.9g,%.6f,%.6f,%.6f,%.6f,%.6f\n", i,
                  FrameName(i).c_str(), m.t[i], l.x(), l.y(), r.x(), r.y(),
                  cam.PlateRowAt(in.plate_z, 0.5 * (l.x() + r.x())));
    s += buf;
  }
  return s;
}

// CPU seconds of the finished child processes so far (POV-Ray runs as children).
double ChildCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

std::string PostProcessKey(const FootageOptions& o, const std::string& version) {
  return std::string(kGeneratorVersion) + "|" + version + "|psf=" + Num(o.psf_sigma_px) +
         "|noise=" + Num(o.noise) + "|bits=" + std::to_string(o.bit_depth) + "|seed=" +
         std::to_string(o.seed) + "|aa=" + std::to_string(o.aa_depth) + "|size=" +
         std::to_string(o.camera.width) + "x" + std::to_string(o.camera.height) + "|fps=" +
         Num(o.fps) + "|gain=" + Num(LightingGain(o.lighting, 0, o.camera.width)) + "," +
         Num(LightingGain(o.lighting, o.camera.width - 1, o.camera.width)) +
         (o.flicker == 0 ? "" : "|flicker=" + Num(o.flicker) + "@" + Num(o.flicker_hz)) +
         (o.lens_k1 == 0 ? ""
                         : "|lens_k1=" + Num(o.lens_k1) + "x" + std::to_string(kLensSupersample));
}

std::string Sidecar(const Motion& m, const FootageOptions& o, const std::string& version,
                    const std::string& hash, double seconds_per_frame) {
  const Camera& c = o.camera;
  std::string j = "{\n";
  auto add = [&](const std::string& k, const std::string& v, bool last = false) {
    j += "  \"" + k + "\": " + v + (last ? "\n" : ",\n");
  };
  add("kind", "\"povray_footage\"");
  add("generator", "\"tests/footage/povray_footage.cc\"");
  add("povray_version", JsonString(version));
  add("lighting", JsonString(ToString(o.lighting)));
  add("motion", JsonString(m.description));
  add("frames", std::to_string(m.t.size()));
  add("width", std::to_string(c.width));
  add("height", std::to_string(c.height));
  add("m_per_px", Num(c.m_per_px));
  add("camera_distance", Num(c.distance));
  add("camera_elevation", Num(c.elevation));
  add("camera_centre_x", Num(c.centre_x));
  add("horizon_row", Num(c.horizon_row));
  add("camera_roll_deg", Num(c.roll_deg));
  add("focal_px", Num(c.FocalPx()));
  add("render_height", std::to_string(c.RenderHeight()));
  add("render_top", std::to_string(c.RenderTop()));
  add("pov_camera", JsonString(c.PovCamera()));
  add("row0", Num(c.PlateRow(0.0)));
  add("col_offset", Num(c.Project(0.0, 0.0, 0.0).x()));
  add("diameter", Num(o.shape.diameter));
  add("aspect_ratio", Num(o.shape.aspect_ratio));
  add("rod_diameter", Num(o.shape.rod_diameter));
  add("radius_px", Num(0.5 * o.shape.diameter / c.m_per_px));
  add("plate_depth", Num(o.scene.plate_depth));
  add("fps", Num(o.fps));
  add("exposure", Num(o.exposure_s));
  add("subframes", std::to_string(o.subframes));
  add("psf_sigma_px", Num(o.psf_sigma_px));
  add("noise", Num(o.noise));
  add("bit_depth", std::to_string(o.bit_depth));
  add("seed", std::to_string(o.seed));
  add("flicker", Num(o.flicker));
  add("flicker_hz", Num(o.flicker_hz));
  add("lens_k1", Num(o.lens_k1));
  add("aa_depth", std::to_string(o.aa_depth));
  add("gain_left", Num(LightingGain(o.lighting, 0, c.width)));
  add("gain_right", Num(LightingGain(o.lighting, c.width - 1, c.width)));
  add("povray_cpu_seconds_per_frame", Num(seconds_per_frame));
  add("scene_hash", JsonString(hash));
  add("units",
      "{\"m_per_px\": \"m/px\", \"camera_distance\": \"m\", \"camera_elevation\": \"m\", "
      "\"camera_centre_x\": \"m\", \"horizon_row\": \"px\", \"focal_px\": \"px\", \"row0\": "
      "\"px\", \"col_offset\": \"px\", \"diameter\": \"m\", \"rod_diameter\": \"m\", "
      "\"radius_px\": \"px\", \"plate_depth\": \"m\", \"fps\": \"frames/s\", \"exposure\": \"s\", "
      "\"psf_sigma_px\": \"px\", \"noise\": \"grey levels (8-bit scale)\", "
      "\"camera_roll_deg\": \"deg\", \"flicker\": \"1\", \"flicker_hz\": \"Hz\", "
      "\"povray_cpu_seconds_per_frame\": \"s\"}",
      true);
  return j + "}\n";
}

// The scene_hash recorded in an existing folder's footage.json, or "".
std::string RecordedHash(const std::string& folder) {
  const std::string text = ReadAll(folder + "/footage.json");
  const std::string key = "\"scene_hash\": \"";
  const size_t p = text.find(key);
  if (p == std::string::npos) return "";
  const size_t e = text.find('"', p + key.size());
  return e == std::string::npos ? "" : text.substr(p + key.size(), e - p - key.size());
}

}  // namespace

FootageOptions FootageOptions::For(Lighting lighting) {
  FootageOptions o;
  o.lighting = lighting;
  o.camera = DefaultCamera(lighting);
  o.camera.centre_x = std::numeric_limits<double>::quiet_NaN();
  o.scene = DefaultSceneOptions(lighting);
  return o;
}

void FootageOptions::Check() const {
  std::string bad = camera.Check();
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad += (bad.empty() ? "" : "; ") + what;
  };
  need(shape.diameter > 0 && std::isfinite(shape.diameter), "--diameter must be > 0 m");
  need(shape.aspect_ratio >= 2.0 && std::isfinite(shape.aspect_ratio),
       "--ar must be >= 2 (touching spheres)");
  need(shape.rod_diameter >= 0 && shape.rod_diameter < shape.diameter,
       "--rod-diameter must be in [0, diameter)");
  need(fps > 0 && std::isfinite(fps), "--fps must be > 0");
  need(exposure_s >= 0 && exposure_s <= 1.0 / fps, "--exposure-us must be in [0, 1e6 / fps]");
  need(subframes >= 1 && subframes <= 64, "--subframes must be 1..64");
  need(psf_sigma_px >= 0 && psf_sigma_px <= 10, "--psf must be 0..10 px");
  need(noise >= 0 && std::isfinite(noise), "--noise must be >= 0");
  need(bit_depth == 8 || bit_depth == 16, "--bit-depth must be 8 or 16");
  need(jobs >= 0 && jobs <= 64, "--jobs must be 0 (three per core) .. 64");
  need(aa_depth >= 0 && aa_depth <= 7, "--aa-depth must be 0..7");
  need(flicker >= 0 && flicker < 1, "--flicker must be in [0, 1)");
  need(flicker_hz > 0 && std::isfinite(flicker_hz), "--flicker-hz must be > 0");
  need(lens_k1 >= 0 && lens_k1 <= 2, "--lens-k1 must be in [0, 2] (pincushion)");
  need(std::isfinite(dimer_off_axis), "--off-axis must be finite");
  if (!bad.empty()) throw UsageError(bad);
}

std::string HashText(const std::string& text) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string PovrayVersion(const std::string& povray) {
  FILE* p = popen((Quote(povray) + " --version 2>&1").c_str(), "r");
  if (!p) return "";
  std::string out;
  char buf[256];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int rc = pclose(p);
  if (rc != 0) return "";
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("POV-Ray", 0) == 0) return line;
  }
  return "";
}

constexpr int kPovrayStartAttempts = 3;
constexpr const char* kPovrayStartTimeout = "Timed out waiting for worker thread startup";

std::vector<cv::Mat> RenderPov(const std::string& scene_text, const Camera& camera,
                               int subframes, int aa_depth, const std::string& work_dir,
                               const std::string& povray) {
  fs::remove_all(work_dir);
  fs::create_directories(work_dir);
  struct Cleanup {
    std::string dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{work_dir};
  std::ofstream(work_dir + "/scene.pov") << scene_text;
  const int top = camera.RenderTop();
  // +SR/+ER are 1-based; only the output's rows are traced. File_Gamma=1: linear values.
  std::string cmd = "cd " + Quote(work_dir) + " && " + Quote(povray) +
                    " +Iscene.pov +Oslice.png +FN16 File_Gamma=1.0 -D +WT1 -V +W" +
                    std::to_string(camera.width) + " +H" +
                    std::to_string(camera.RenderHeight()) + " +SR" + std::to_string(top + 1) +
                    " +ER" + std::to_string(top + camera.height) +
                    (aa_depth > 0 ? " +A0.02 +AM2 -J +R" + std::to_string(aa_depth) : std::string(" -A"));
  if (subframes > 1) cmd += " +KFI0 +KFF" + std::to_string(subframes - 1);
  cmd += " > povray.log 2>&1";
  // Under load POV-Ray 3.7 sometimes gives up before it starts ("Timed out waiting for worker
  // thread startup": a 2401-frame render died at frame 1204 with the test suite running beside
  // it) or crashes while parsing (a segmentation fault on one chunk of front_point_ar2_0 in a
  // fresh-clone CI run; the same chunk rendered when run again). Such a run has traced nothing,
  // so it is run again, up to kPovrayStartAttempts in all; any other failure is reported at once.
  auto slices = [&work_dir] {
    std::vector<std::string> files;
    for (const auto& de : fs::directory_iterator(work_dir)) {
      const std::string name = de.path().filename().string();
      if (name.rfind("slice", 0) == 0 && de.path().extension() == ".png") files.push_back(name);
    }
    return files;
  };
  int rc = 0;
  for (int attempt = 1; attempt <= kPovrayStartAttempts; ++attempt) {
    rc = std::system(cmd.c_str());
    const bool never_started =
        ReadAll(work_dir + "/povray.log").find(kPovrayStartTimeout) != std::string::npos;
    // The shell reports a process killed by signal n as exit status 128 + n.
    const bool crashed_before_any_image = WIFEXITED(rc) && WEXITSTATUS(rc) > 128 && slices().empty();
    if (rc == 0 || !(never_started || crashed_before_any_image)) break;
  }
  std::vector<std::string> files = slices();
  std::sort(files.begin(), files.end());  // slice00.png ...: fixed width, so sorted = in order
  if (rc != 0 || int(files.size()) != subframes) {
    throw InputError(povray + " failed in " + work_dir + " (exit " + std::to_string(rc) + ", " +
                     std::to_string(files.size()) + " of " + std::to_string(subframes) +
                     " images): " + LastLines(ReadAll(work_dir + "/povray.log"), 3));
  }
  std::vector<cv::Mat> out;
  for (const std::string& f : files) {
    const std::string path = work_dir + "/" + f;
    cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
    if (img.empty() || img.depth() != CV_16U) throw InputError(path + ": not a 16-bit PNG");
    if (img.channels() == 3) cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
    if (img.channels() == 4) cv::cvtColor(img, img, cv::COLOR_BGRA2GRAY);
    if (img.rows != camera.RenderHeight() || img.cols != camera.width) {
      throw InputError(path + ": unexpected size " + std::to_string(img.cols) + "x" +
                       std::to_string(img.rows));
    }
    cv::Mat grey;
    img(cv::Rect(0, top, camera.width, camera.height)).convertTo(grey, CV_32F, 1.0 / 65535.0);
    out.push_back(grey);
  }
  return out;
}

cv::Matx33d CameraMatrix(const Camera& c) {
  return {c.FocalPx(), 0, 0.5 * (c.width - 1), 0, c.FocalPx(), c.horizon_row, 0, 0, 1};
}

FootageResult WriteFootage(const Motion& motion, const FootageOptions& options_in,
                           const std::string& output) {
  options_in.Check();
  if (motion.t.empty()) throw InputError(output + ": no frames to render");
  const auto start = std::chrono::steady_clock::now();
  FootageOptions o = options_in;
  if (std::isnan(o.camera.centre_x)) {
    double sum = 0;
    for (double t : motion.t) {
      const Instant s = motion.at(t);
      sum += 0.5 * (s.left.x() + s.right.x());
    }
    o.camera.centre_x = sum / double(motion.t.size()) - o.dimer_off_axis;
  }
  const std::string version = PovrayVersion(o.povray);
  if (version.empty()) {
    throw InputError(o.povray + ": POV-Ray does not run (Debian package povray)");
  }
  const size_t n = motion.t.size();
  const int slices = o.exposure_s > 0 ? o.subframes : 1;
  std::vector<std::string> scenes(n);
  std::string all = PostProcessKey(o, version);
  for (size_t i = 0; i < n; ++i) {
    scenes[i] = SceneText(o.lighting, o.shape, RenderCamera(o), o.scene,
                          Slices(motion, i, o.exposure_s, slices));
    all += scenes[i];
  }
  const std::string truth = TruthCsv(motion, o);
  FootageResult result;
  result.frames = n;
  result.scene_hash = HashText(all + truth);
  if (o.reuse && fs::is_directory(output) && RecordedHash(output) == result.scene_hash) {
    result.reused = true;
    return result;
  }
  // A stale cache is ours to replace.
  const bool replace = o.force || (o.reuse && fs::exists(output + "/footage.json"));
  AtomicOutput out(output, replace, AtomicOutput::Kind::kDirectory);
  fs::create_directories(out.temp_path() + "/pov");
  for (size_t i = 0; i < n; ++i) {
    std::ofstream(out.temp_path() + "/pov/" + FrameName(i).replace(13, 3, "pov")) << scenes[i];
  }

  // The lens's maps, once for the film (1.8 M points at 3x a 640 x 320 frame).
  const std::pair<cv::Mat, cv::Mat> lens_maps =
      o.lens_k1 != 0 ? DistortionMaps(o) : std::pair<cv::Mat, cv::Mat>{};
  std::atomic<size_t> next{0}, done{0};
  const double cpu_start = ChildCpuSeconds();
  std::mutex error_mutex;
  std::string error;
  auto worker = [&]() {
    for (size_t i = next++; i < n && !InterruptRequested(); i = next++) {
      try {
        const std::vector<cv::Mat> imgs =
            RenderPov(scenes[i], RenderCamera(o), slices, o.aa_depth,
                      out.temp_path() + "/.work_" + std::to_string(i), o.povray);
        const std::string path = out.temp_path() + "/" + FrameName(i);
        if (!cv::imwrite(path, PostProcess(imgs, o, i, motion.t[i], lens_maps))) {
          throw InputError(path + ": cannot write");
        }
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (error.empty()) error = e.what();
        next = n;
      }
      ++done;
    }
  };
  ProgressMeter progress("povray " + ToString(o.lighting), "frames", double(n), !o.quiet);
  std::vector<std::thread> pool;
  const int jobs = o.jobs > 0 ? o.jobs : 3 * int(std::max(1u, std::thread::hardware_concurrency()));
  for (int k = 0; k < std::min<int>(jobs, int(n)); ++k) pool.emplace_back(worker);
  while (done < n && !InterruptRequested()) {
    {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error.empty()) break;
    }
    progress.Update(double(done));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  for (auto& t : pool) t.join();
  if (!error.empty()) throw InputError(error);
  if (InterruptRequested()) throw Interrupted();
  progress.Finish(double(n));
  result.povray_cpu_seconds_per_frame = (ChildCpuSeconds() - cpu_start) / double(n);
  std::ofstream(out.temp_path() + "/truth.csv") << truth;
  if (o.lens_k1 != 0) {  // the lens's calibration, as OpenCV's calibration sample writes it
    cv::FileStorage lens(out.temp_path() + "/lens.yml", cv::FileStorage::WRITE);
    lens << "image_width" << o.camera.width << "image_height" << o.camera.height;
    lens << "camera_matrix" << cv::Mat(CameraMatrix(o.camera));
    lens << "distortion_coefficients" << cv::Mat(std::vector<double>{o.lens_k1, 0, 0, 0, 0});
  }
  std::ofstream(out.temp_path() + "/footage.json")
      << Sidecar(motion, o, version, result.scene_hash, result.povray_cpu_seconds_per_frame);
  out.Commit();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace dimer::footage
