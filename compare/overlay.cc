#include "compare/overlay.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "common/error.h"
#include "common/interrupt.h"
#include "common/progress.h"
#include "compare/report_parts.h"
#include "tracking/io/frame_source.h"
#include "tracking/io/image_codecs.h"
#include "tracking/io/lens_undistortion.h"

namespace dimer::compare {
namespace {

namespace fs = std::filesystem;

// Colours (BGR), bright enough to read over a grey frame.
const std::array<cv::Scalar, 2> kTrackColour = {cv::Scalar(255, 200, 0),   // left: cyan-blue
                                                cv::Scalar(0, 140, 255)};  // right: orange
const cv::Scalar kSimColour(60, 255, 60);                                  // simulation: green
constexpr int kMinMarkerPx = 5, kMaxMarkerPx = 25;  // cross size bounds, px
constexpr double kThickLineRadiusPx = 20;           // spheres larger than this get 2 px lines
constexpr double kTextScalePerPx = 1.0 / 900;       // OpenCV font scale per pixel of width
constexpr double kMinTextScale = 0.3, kMaxTextScale = 1.2;

// Grid frames by the names the tracker recorded (SampledRun::frame_files): "file.png" in a
// folder, "file.tif#page" for a page of a multi-page file, "video.avi#k" for a video's frame.
class FrameReader {
 public:
  explicit FrameReader(const std::string& path) : path_(path), folder_(fs::is_directory(path)) {
    auto source = tracking::OpenFrameSource(path);  // InputError naming the path if unusable
    if (!folder_) single_ = std::move(source);
  }

  // True when frames can only be read forward (a video): reading again needs a new reader.
  bool sequential() const { return single_ && !single_->random_access(); }

  // The frame, or an empty Mat with *error set.
  cv::Mat Read(const std::string& name, std::string* error) {
    const size_t hash = name.rfind('#');
    const std::string file = hash == std::string::npos ? name : name.substr(0, hash);
    const long page = hash == std::string::npos ? -1 : std::atol(name.c_str() + hash + 1);
    tracking::Frame f;
    if (folder_ && page < 0) {
      f = tracking::DecodeImageFile((fs::path(path_) / name).string(), 0, name);
    } else if (folder_) {
      auto& src = pages_[file];
      if (!src) src = tracking::OpenFrameSource((fs::path(path_) / file).string());
      f = ReadIndex(src.get(), static_cast<size_t>(page));
    } else {
      f = ReadIndex(single_.get(), static_cast<size_t>(std::max(page, 0L)));
    }
    *error = f.error;
    return f.error.empty() ? f.image : cv::Mat();
  }

 private:
  // Random-access sources read directly; a video is read forward (the overlay asks in order).
  static tracking::Frame ReadIndex(tracking::FrameSource* src, size_t index) {
    if (src->random_access()) {
      if (index < src->size()) return src->Read(index);
      return {index, "", cv::Mat(), "no such frame in the source"};
    }
    tracking::Frame f;
    while (src->Next(&f)) {
      if (f.index == index) return f;
      if (f.index > index) break;
    }
    return {index, "", cv::Mat(), "not found reading the video forward"};
  }

  std::string path_;
  bool folder_;
  std::unique_ptr<tracking::FrameSource> single_;
  std::map<std::string, std::unique_ptr<tracking::FrameSource>> pages_;
};

// 8-bit BGR; 16-bit frames are scaled by one factor for the whole video (no flicker).
cv::Mat ToBgr8(const cv::Mat& image, double* scale16) {
  cv::Mat grey8;
  if (image.depth() == CV_16U) {
    if (*scale16 <= 0) {
      double max_value = 0;
      cv::minMaxLoc(image, nullptr, &max_value);
      *scale16 = max_value > 0 ? 255.0 / max_value : 1.0;
    }
    image.convertTo(grey8, CV_8U, *scale16);
  } else {
    image.convertTo(grey8, CV_8U);
  }
  cv::Mat bgr;
  if (grey8.channels() == 1) cv::cvtColor(grey8, bgr, cv::COLOR_GRAY2BGR);
  else if (grey8.channels() == 4) cv::cvtColor(grey8, bgr, cv::COLOR_BGRA2BGR);
  else bgr = grey8;
  return bgr;
}

std::string ModeAt(const Analysis& a, double t) {
  for (const ModeWindow& w : a.periods.timeline)
    if (t >= w.t_start && t < w.t_end) return w.summary.label;
  const ModeWindow& s = a.periods.settled;
  if (s.count > 0 && t >= s.t_start && t < s.t_end) return s.summary.label + " (settled)";
  return "unlabelled";
}

// Draws frame i's overlay onto `img`.
void Draw(const Analysis& a, const Comparison* c, size_t i, const std::string& extra,
          cv::Mat* img) {
  const SampledRun& r = a.run;
  const double radius_px = 0.5 * r.diameter_m / r.m_per_px;
  const int marker = std::clamp(static_cast<int>(radius_px), kMinMarkerPx, kMaxMarkerPx);
  auto pixel = [&r](double x, double z) {
    const Eigen::Vector2d p = r.PixelOf(x, z);
    return cv::Point(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  };
  const int radius = std::max(1, static_cast<int>(std::lround(radius_px)));
  const int line = radius_px > kThickLineRadiusPx ? 2 : 1;
  for (int s = 0; s < 2; ++s) {
    if (c != nullptr && i < c->sim_x[s].size() && i < c->sim_z[s].size() &&
        std::isfinite(c->sim_x[s][i]) && std::isfinite(c->sim_z[s][i])) {
      // Just outside the tracked circle: where they agree (to micrometres) both stay visible.
      cv::circle(*img, pixel(c->sim_x[s][i], c->sim_z[s][i]), radius + 2 * line, kSimColour, line,
                 cv::LINE_AA);
    }
    if (!std::isfinite(r.x[s][i]) || !std::isfinite(r.z[s][i])) continue;
    const cv::Point p = pixel(r.x[s][i], r.z[s][i]);
    cv::drawMarker(*img, p, kTrackColour[s], cv::MARKER_CROSS, marker, line, cv::LINE_AA);
    cv::circle(*img, p, radius, kTrackColour[s], line, cv::LINE_AA);
  }
  std::string text = Format("t = %.4f s  %s", r.Time(i), ModeAt(a, r.Time(i)).c_str()) + extra;
  if (c != nullptr) text += "  (green: simulation)";
  const double scale =
      std::clamp(img->cols * kTextScalePerPx, kMinTextScale, kMaxTextScale);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  const cv::Point at(3, 3 + size.height);
  // A dark outline keeps the text readable over bright and dark parts of the frame.
  cv::putText(*img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3,
              cv::LINE_AA);
  cv::putText(*img, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
}

void CheckInputs(const Analysis& a, const OverlayOptions& o) {
  std::string bad;
  for (const auto& e : o.Check()) bad += (bad.empty() ? "" : "; ") + e;
  if (!bad.empty()) throw InputError("invalid overlay options: " + bad);
  const SampledRun& r = a.run;
  if (!(r.m_per_px > 0) || !std::isfinite(r.row0_px) || r.frame_files.size() != r.n) {
    throw InputError(r.path + ": no pixel calibration or frame names (m_per_px, row0, "
                     "frame_files); the overlay needs a track file written by `dimerlab track`");
  }
  if (a.periods.settled.count == 0) {
    throw InputError(r.path + ": no settled window (no whole plate period) to draw the "
                     "overlay over");
  }
}

// Counts the frames that could not be drawn; reported once.
struct Missing {
  int count = 0;
  std::string first;
  void Add(size_t i, const std::string& name, const std::string& why) {
    if (count++ == 0) first = Format("frame %zu", i) + (name.empty() ? "" : " '" + name + "'") +
                              ": " + why;
  }
};

}  // namespace

std::vector<std::string> OverlayOptions::Check() const {
  std::vector<std::string> errors;
  if (frames_dir.empty()) errors.push_back("--frames: empty: expected the folder of frames");
  if (max_frames <= 0)
    errors.push_back("max_frames: " + std::to_string(max_frames) + ": expected > 0");
  if (stills < 0) errors.push_back("stills: " + std::to_string(stills) + ": expected >= 0");
  if (!(video_fps > 0))
    errors.push_back("video_fps: " + Format("%g", video_fps) + ": expected > 0");
  return errors;
}

void WriteOverlay(const std::string& dir, const Analysis& track, const Comparison* comparison,
                  const OverlayOptions& o) {
  CheckInputs(track, o);
  const SampledRun& r = track.run;
  const ModeWindow& w = track.periods.settled;
  FrameReader reader(o.frames_dir);
  double scale16 = 0;
  Missing missing;
  // Stills first: they are few, and a video source is then read forward once for the video.
  std::vector<size_t> still_frames;  // the first frame at or after phase k / stills
  for (int k = 0; k < o.stills; ++k) {
    size_t first = 0, last = 0;
    FramesIn(r, w.t_start + track.periods.period_s * k / o.stills, w.t_end, &first, &last);
    if (first < last) still_frames.push_back(first);
  }
  size_t i0 = 0, i1 = 0;
  FramesIn(r, w.t_start, w.t_end, &i0, &i1);
  i1 = std::min(i1, i0 + static_cast<size_t>(o.max_frames));
  // A track made through `--lens` has its centres in the undistorted frames: the recorded frames
  // are undistorted alike before anything is drawn on them.
  std::optional<tracking::LensUndistortion> undistort;
  cv::Size undistort_size;
  tracking::LensCalibration lens;
  if (r.lens_camera.size() == 9 && !r.lens_distortion.empty()) {
    lens.path = r.path;
    lens.camera = cv::Matx33d(r.lens_camera.data());
    lens.distortion = r.lens_distortion;
  }
  auto load = [&](size_t i, cv::Mat* out) {
    std::string error = r.frame_files[i].empty() ? "not in the track" : "";
    cv::Mat img = error.empty() ? reader.Read(r.frame_files[i], &error) : cv::Mat();
    if (img.empty()) {
      missing.Add(i, r.frame_files[i], error.empty() ? "empty image" : error);
      return false;
    }
    if (!lens.distortion.empty()) {
      if (!undistort || undistort_size != img.size()) {
        undistort.emplace(lens, img.size());
        undistort_size = img.size();
      }
      img = undistort->Apply(img);
    }
    *out = ToBgr8(img, &scale16);
    return true;
  };
  if (!still_frames.empty()) fs::create_directories(fs::path(dir) / "stills");
  for (size_t k = 0; k < still_frames.size(); ++k) {
    cv::Mat img;
    if (!load(still_frames[k], &img)) continue;
    Draw(track, comparison, still_frames[k], Format("  phase %d/%d", int(k), o.stills), &img);
    const std::string path = (fs::path(dir) / "stills" / Format("still_%zu.png", k)).string();
    if (!tracking::codecs::Write(path, img)) throw InputError(path + ": cannot write the still");
  }
  if (!still_frames.empty() && reader.sequential()) reader = FrameReader(o.frames_dir);

  tracking::codecs::VideoWriter video;
  cv::Size size;
  const std::string video_path = (fs::path(dir) / "overlay.avi").string();
  ProgressMeter progress("overlay", "frames", double(i1 - i0), !o.quiet);
  int written = 0;
  for (size_t i = i0; i < i1 && !InterruptRequested(); ++i) {
    progress.Update(double(i - i0));
    cv::Mat img;
    if (!load(i, &img)) continue;
    if (!video.IsOpened()) {
      size = img.size();
      if (!video.Open(video_path, "MJPG", o.video_fps, size))
        throw InputError(video_path + ": cannot open an MJPG video writer");
    }
    if (img.size() != size) cv::resize(img, img, size);
    Draw(track, comparison, i, "", &img);
    video.Write(img);
    ++written;
  }
  progress.Finish(double(i1 - i0));
  video.Release();
  if (missing.count > 0) {
    std::fprintf(stderr, "dimerlab: warning: overlay: %d frames missing or unreadable, skipped "
                 "(first: %s)\n", missing.count, missing.first.c_str());
  }
  if (InterruptRequested()) throw Interrupted();
  if (written == 0) {
    throw InputError(o.frames_dir + ": no frame of the settled window could be read; is it the "
                     "folder of frames that was tracked (" + r.path + ")?");
  }
}

}  // namespace dimer::compare
