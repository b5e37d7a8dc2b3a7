#include "render/render.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "common/atomic_output.h"
#include "common/error.h"
#include "common/format.h"
#include "common/h5_file.h"
#include "common/interrupt.h"
#include "common/plate_frame.h"
#include "common/progress.h"
#include "common/provenance.h"
#include "common/trajectory_io.h"
#include "tracking/io/cine_writer.h"
#include "tracking/io/frame_source.h"
#include "tracking/io/image_codecs.h"

namespace dimer::tracking {
namespace {

// Default plate row as a fraction of the height: leaves ~40 mm above the plate in a 256-row
// frame at 2e-4 m/px, enough for the paper's jump and flutter heights.
constexpr double kDefaultRow0Fraction = 0.78;

Eigen::Vector2d Lerp(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double u) {
  return a + u * (b - a);
}

// The one .cine file of a `--format cine` folder; its frames are named FILE#i.
constexpr char kCineFile[] = "frames.cine";

std::string FrameName(size_t i, FrameFormat format) {
  char buf[40];
  if (format == FrameFormat::kCine) {
    std::snprintf(buf, sizeof buf, "%s#%zu", kCineFile, i);
  } else {
    std::snprintf(buf, sizeof buf, "frame_%06zu.%s", i, format == FrameFormat::kPng ? "png" : "tif");
  }
  return buf;
}

// Header values of a rendered .cine: the trajectory's sample rate (rounded to whole frames/s,
// as the header stores it) and the exposure the blur used.
CineWriteOptions CineOptions(const RenderArgs& a, const Trajectory& traj, size_t n) {
  CineWriteOptions o;
  o.pixels = a.image.bit_depth == 16 ? CinePixels::k16Bit : CinePixels::k8Bit;
  const double dt = n >= 2 ? traj.t[1] - traj.t[0] : 1.0 / kDefaultFps;
  o.frame_rate = uint32_t(std::lround(1.0 / dt));
  o.exposure_ns = uint32_t(std::lround(a.exposure * dt * 1e9));
  return o;
}

// A number for render.json and messages: ten significant digits.
std::string Num10(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

void CheckTrajectory(const std::string& path, const Trajectory& traj, size_t n) {
  if (n == 0) throw InputError(path + ": the trajectory has no samples");
  for (size_t i = 0; i < n; ++i) {
    if (!traj.tip_left[i].allFinite() || !traj.tip_right[i].allFinite() ||
        !std::isfinite(traj.plate_z[i]) || !std::isfinite(traj.t[i])) {
      throw InputError(path + ": sample " + std::to_string(i) +
                       " has a NaN position; render needs a complete trajectory");
    }
  }
}

std::string RenderJson(const RenderArgs& a, const RenderPlan& p, double diameter, size_t n,
                       double tilt_deg) {
  std::string j = "{\n";
  auto add = [&](const std::string& k, const std::string& v, bool last = false) {
    j += "  \"" + k + "\": " + v + (last ? "\n" : ",\n");
  };
  add("kind", "\"render\"");
  add("dimerlab_version", "\"" + DimerlabVersion() + "\"");
  add("source", "\"" + a.input + "\"");
  add("frames", std::to_string(n));
  add("width", std::to_string(a.image.width));
  add("height", std::to_string(a.image.height));
  add("m_per_px", Num10(p.map.m_per_px));
  add("row0", Num10(p.map.row0));
  add("col_offset", Num10(p.map.col_offset));
  add("diameter", Num10(diameter));
  add("tilt_deg", Num10(tilt_deg));
  add("frame", tilt_deg != 0 ? "\"plate\"" : "\"lab\"");
  add("radius_px", Num10(p.radius_px));
  add("rod_diameter", Num10(a.rod_diameter));
  add("lighting", "\"" + ToString(a.image.lighting) + "\"");
  add("noise", Num10(a.image.noise));
  add("gradient", Num10(a.image.gradient));
  add("exposure", Num10(a.exposure));
  add("blur_samples", std::to_string(a.blur_samples));
  add("bit_depth", std::to_string(a.image.bit_depth));
  add("format", "\"" + ToString(a.format) + "\"");
  add("seed", std::to_string(a.image.seed));
  add("units",
      "{\"m_per_px\": \"m/px\", \"row0\": \"px\", \"col_offset\": \"px\", "
      "\"diameter\": \"m\", \"tilt_deg\": \"deg\", \"radius_px\": \"px\", \"rod_diameter\": \"m\", "
      "\"noise\": \"grey levels (8-bit scale)\", \"gradient\": \"1\", "
      "\"exposure\": \"frame intervals\", \"width\": \"px\", \"height\": \"px\"}");
  add("format_doc", "\"docs/FORMATS.md, render folder\"", true);
  return j + "}\n";
}

void WriteTruth(const std::string& path, const RenderArgs& a, const RenderPlan& p,
                const Trajectory& traj, size_t n) {
  std::ofstream out(path);
  out << "# dimerlab render truth: exact pixel centres (col, row) at each frame's sample time; "
         "units: t s, *_col *_row plate_row px (0-based pixel centres, rows growing downward); "
         "docs/FORMATS.md\n"
      << "# m_per_px=" << Num10(p.map.m_per_px) << " row0=" << Num10(p.map.row0)
      << " col_offset=" << Num10(p.map.col_offset) << " radius_px=" << Num10(p.radius_px)
      << " lighting=" << ToString(a.image.lighting) << " noise=" << Num10(a.image.noise)
      << " seed=" << a.image.seed << "\n"
      << "frame,file,t,left_col,left_row,right_col,right_row,plate_row\n";
  char buf[256];
  for (size_t i = 0; i < n; ++i) {
    const SceneGeometry s = p.SceneAt(traj, traj.t[i]);
    std::snprintf(buf, sizeof buf, "%zu,%s,%.9g,%.6f,%.6f,%.6f,%.6f,%.6f\n", i,
                  FrameName(i, a.format).c_str(), traj.t[i], s.left.x(), s.left.y(),
                  s.right.x(), s.right.y(), s.plate_row);
    out << buf;
  }
  if (!out) throw InputError(path + ": cannot write");
}

}  // namespace

SceneGeometry RenderPlan::SceneAt(const Trajectory& traj, double t) const {
  const size_t n = traj.size();
  size_t i = size_t(std::upper_bound(traj.t.begin(), traj.t.end(), t) - traj.t.begin());
  i = std::clamp<size_t>(i, 1, std::max<size_t>(n - 1, 1));
  const size_t i0 = n > 1 ? i - 1 : 0, i1 = n > 1 ? i : 0;
  const double dt = traj.t[i1] - traj.t[i0];
  const double u = dt > 0 ? std::clamp((t - traj.t[i0]) / dt, 0.0, 1.0) : 0.0;
  SceneGeometry s;
  s.left = map.PixelFromLab(Lerp(traj.tip_left[i0], traj.tip_left[i1], u));
  s.right = map.PixelFromLab(Lerp(traj.tip_right[i0], traj.tip_right[i1], u));
  s.plate_row = map.RowFromZ(traj.plate_z[i0] + u * (traj.plate_z[i1] - traj.plate_z[i0]));
  s.radius_px = radius_px;
  s.rod_half_width_px = rod_half_width_px;
  return s;
}

std::vector<SceneGeometry> RenderPlan::Exposure(const Trajectory& traj, size_t i, double exposure,
                                                int samples) const {
  if (exposure <= 0 || samples <= 1 || traj.size() < 2) return {SceneAt(traj, traj.t[i])};
  const double dt = i + 1 < traj.size() ? traj.t[i + 1] - traj.t[i] : traj.t[i] - traj.t[i - 1];
  std::vector<SceneGeometry> out;
  for (int k = 0; k < samples; ++k) {
    const double offset = (double(k) / (samples - 1) - 0.5) * exposure * dt;
    out.push_back(SceneAt(traj, traj.t[i] + offset));
  }
  return out;
}

std::string ToString(FrameFormat f) {
  return f == FrameFormat::kTiff ? "tiff" : f == FrameFormat::kCine ? "cine" : "png";
}

FrameFormat ParseFrameFormat(const std::string& name) {
  for (FrameFormat f : {FrameFormat::kPng, FrameFormat::kTiff, FrameFormat::kCine}) {
    if (name == ToString(f)) return f;
  }
  throw UsageError("--format '" + name + "': expected png, tiff or cine");
}

void RenderArgs::Check() const {
  std::string bad;
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad += (bad.empty() ? "" : "; ") + what;
  };
  need(!input.empty(), "input: a trajectory file (sim.h5) is required");
  need(!output.empty(), "-o: the output folder is required");
  need(m_per_px > 0 && std::isfinite(m_per_px), "--m-per-px must be > 0 m/px");
  need(!diameter || (*diameter > 0 && std::isfinite(*diameter)), "--diameter must be > 0 m");
  need(rod_diameter >= 0 && std::isfinite(rod_diameter), "--rod-diameter must be >= 0 m");
  need(exposure >= 0 && exposure <= 1, "--exposure must be in [0, 1] frame intervals");
  need(blur_samples >= 1 && blur_samples <= 64, "--blur-samples must be 1..64");
  need(threads >= 0 && threads <= 256, "--threads must be 0 (all cores) .. 256");
  if (!bad.empty()) throw UsageError(bad);
  image.Check();
}

namespace {

// What a sim file gives the renderer: the trajectory in the plate's frame, its tilt, the
// spheres' diameter and how many of its samples become frames.
struct Scene {
  Trajectory traj;
  double tilt_deg = 0;
  double diameter = 0;
  size_t frames = 0;
};

Scene ReadScene(const RenderArgs& args) {
  H5Reader reader(args.input);
  Scene scene;
  // A tilted plate's simulation is drawn in the plate's frame, as a camera turned with the plate
  // sees it (the renderer's plate is level): the frame `track` measures in.
  scene.tilt_deg =
      FileKind(reader) == "sim" ? reader.AttrDouble("/", "tilt_deg").value_or(0.0) : 0.0;
  if (!std::isfinite(scene.tilt_deg)) throw InputError(args.input + ": 'tilt_deg' is not a number");
  scene.traj = InPlateFrame(ReadTrajectory(reader), scene.tilt_deg);
  if (scene.tilt_deg != 0 && !args.quiet && args.on_note) {
    args.on_note(args.input + ": plate tilted " + Num10(scene.tilt_deg) +
                 " deg: drawn in the plate's frame (a camera turned with the plate; truth.csv "
                 "likewise)");
  }
  const Trajectory& traj = scene.traj;
  scene.frames = args.max_frames > 0 ? std::min(args.max_frames, traj.size()) : traj.size();
  CheckTrajectory(args.input, traj, scene.frames);
  scene.diameter = args.diameter ? *args.diameter
                                 : reader.AttrDouble("/", "diameter").value_or(std::nan(""));
  if (!(scene.diameter > 0)) {
    throw InputError(args.input + ": no root attribute 'diameter' (m); pass --diameter");
  }
  return scene;
}

// Where the scene lands in the image: the plate at row0, the dimer's mean column centred.
RenderPlan PlanOf(const RenderArgs& args, const Scene& scene) {
  RenderPlan plan;
  plan.map.m_per_px = args.m_per_px;
  plan.map.row0 = args.row0.value_or(kDefaultRow0Fraction * args.image.height);
  double mean_x = 0;
  for (size_t i = 0; i < scene.frames; ++i)
    mean_x += 0.5 * (scene.traj.tip_left[i].x() + scene.traj.tip_right[i].x());
  const double mean_col = (mean_x / double(scene.frames)) / args.m_per_px;
  plan.map.col_offset = args.col_offset.value_or(0.5 * args.image.width - mean_col);
  plan.radius_px = 0.5 * scene.diameter / args.m_per_px;
  plan.rod_half_width_px = 0.5 * args.rod_diameter / args.m_per_px;
  return plan;
}

// --format cine: workers hand frames over; the calling thread appends them in order (frames are
// taken in increasing order, so only the few in flight wait here).
class OrderedCineFrames {
 public:
  explicit OrderedCineFrames(std::unique_ptr<CineWriter> writer) : writer_(std::move(writer)) {}
  void Hand(size_t i, const cv::Mat& img) {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_[i] = img;
  }
  void WriteReady() {
    while (true) {
      cv::Mat img;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        auto it = pending_.find(written_);
        if (it == pending_.end()) return;
        img = it->second;
        pending_.erase(it);
      }
      writer_->Add(img);
      ++written_;
    }
  }
  void Close() {
    WriteReady();
    writer_->Close();
  }

 private:
  std::unique_ptr<CineWriter> writer_;
  std::mutex mutex_;
  std::map<size_t, cv::Mat> pending_;
  size_t written_ = 0;
};

// Draws every frame on `threads` workers into `folder`: image files written by the workers, or
// one .cine appended in order by this thread. Throws the first write error; stops on Ctrl-C.
void RenderFrames(const RenderArgs& args, const RenderPlan& plan, const Scene& scene,
                  const std::string& folder) {
  const size_t n = scene.frames;
  const int threads = args.threads > 0 ? args.threads
                                        : int(std::max(1u, std::thread::hardware_concurrency()));
  std::atomic<size_t> next{0}, done{0};
  std::mutex error_mutex;
  std::string error;
  auto fail = [&](const std::string& what) {
    std::lock_guard<std::mutex> lock(error_mutex);
    error = what;
    next = n;
  };
  std::unique_ptr<OrderedCineFrames> cine;
  if (args.format == FrameFormat::kCine) {
    cine = std::make_unique<OrderedCineFrames>(std::make_unique<CineWriter>(
        folder + "/" + kCineFile, args.image.width, args.image.height, n,
        CineOptions(args, scene.traj, n)));
  } else {
    // PNG/TIFF frames are written by the workers, whose threads cannot carry the loader's
    // exception out: load OpenCV's codecs (image_codecs.h) here, before any of them starts.
    codecs::Require();
  }
  auto worker = [&]() {
    for (size_t i = next++; i < n && !InterruptRequested(); i = next++) {
      const cv::Mat img = RenderFrame(
          plan.Exposure(scene.traj, i, args.exposure, args.blur_samples), args.image, i);
      if (cine) {
        cine->Hand(i, img);
      } else {
        const std::string path = folder + "/" + FrameName(i, args.format);
        bool ok = false;
        try {
          ok = codecs::Write(path, img);
        } catch (const cv::Exception&) {
        }
        if (!ok) fail(path + ": cannot write frame");
      }
      ++done;
    }
  };
  ProgressMeter progress("render", "frames", double(n), !args.quiet);
  std::vector<std::thread> pool;
  for (int k = 0; k < threads; ++k) pool.emplace_back(worker);
  while (done < n && !InterruptRequested() && error.empty()) {
    progress.Update(double(done));
    if (cine) {
      try {  // a failed write (disk full) must not unwind past running workers
        cine->WriteReady();
      } catch (const std::exception& e) {
        fail(e.what());
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(cine ? 5 : 50));
  }
  for (auto& t : pool) t.join();
  if (!error.empty()) throw InputError(error);
  if (InterruptRequested()) throw Interrupted();  // the temporary folder is removed
  if (cine) cine->Close();
  progress.Finish(double(n));
}

}  // namespace

void RunRender(const RenderArgs& args) {
  args.Check();
  AtomicOutput out(args.output, args.force, AtomicOutput::Kind::kDirectory);
  const Scene scene = ReadScene(args);
  const RenderPlan plan = PlanOf(args, scene);
  RenderFrames(args, plan, scene, out.temp_path());
  WriteTruth(out.temp_path() + "/truth.csv", args, plan, scene.traj, scene.frames);
  std::ofstream(out.temp_path() + "/render.json")
      << RenderJson(args, plan, scene.diameter, scene.frames, scene.tilt_deg);
  out.Commit();
  // The one-line summary every subcommand ends with (stdout; -q silences progress only).
  if (args.on_summary) {
    args.on_summary(Format("%s: %zu frames %dx%d, %d-bit %s, %s lighting, %.3g m/px; truth.csv, "
                           "render.json",
                           args.output.c_str(), scene.frames, args.image.width,
                           args.image.height, args.image.bit_depth, ToString(args.format).c_str(),
                           ToString(args.image.lighting).c_str(), args.m_per_px));
  }
}

}  // namespace dimer::tracking
