// Spheres cut by the frame's edge (tracking/cut_spheres.h): how many of those at least half in
// view are found, how far a cut one lies from where its whole frames put it, against how much of
// its disc shows (the knob kCutMinInView in frame_follower.cc trades these), its stated
// uncertainty against that error, and what the frames with a cut sphere cost.
//
// A film of our renderer: the dimer rests on the plate and slides right at `speed` px a frame
// until the right sphere and then the left one have left the frame by its right edge, and slides
// back; the left sphere hops (a lift of up to 4 px) so that its rows change. Tracked as `dimerlab
// track` does (auto, 2 threads, 512-frame chunks), and with 64-frame chunks (seams among the cut
// frames). A film as long with the dimer sliding back and forth inside the frame gives the time
// a frame without cut spheres costs.
//
// Usage: bench_cut_spheres [speed_px_per_frame=1.0] [--write DIR]
//   --write DIR: the mirror-lit film (R 23.75) written to DIR as BMP frames with truth.csv, to
//   time `dimerlab track` on it as a user runs it.
#include <Eigen/Core>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>

#include "render/scene_renderer.h"
#include "tracking/io/frame_source.h"
#include "tracking/track_sequence.h"

namespace {

using namespace dimer::tracking;

constexpr int kHeight = 256;
constexpr double kAspectRatio = 3.9;  // the paper's drift dimer

struct Film {
  std::vector<SceneGeometry> poses;
  std::vector<cv::Mat> frames;
};

// The left sphere from column `start` to `end` and back.
Film Render(Lighting lighting, double radius, int width, double start, double end,
            double speed) {
  const double length = 2 * (kAspectRatio - 1) * radius;
  const double plate = kHeight - 40.0;
  std::vector<double> xs;
  for (double x = start; x < end; x += speed) xs.push_back(x);
  for (double x = end; x > start; x -= speed) xs.push_back(x);
  RenderOptions o;
  o.width = width;
  o.height = kHeight;
  o.lighting = lighting;
  o.noise = 2.0;
  Film f;
  for (size_t i = 0; i < xs.size(); ++i) {
    SceneGeometry s;
    s.radius_px = radius;
    s.rod_half_width_px = 0.16 * radius;
    s.plate_row = plate;
    const double lift = 4.0 * std::abs(std::sin(0.05 * double(i)));
    s.left = {xs[i], plate - radius - lift};
    const double tilt = std::asin(lift / length);
    s.right = s.left + length * Eigen::Vector2d(std::cos(tilt), std::sin(tilt));
    f.poses.push_back(s);
    f.frames.push_back(RenderFrame({s}, o, i));
  }
  return f;
}

double InView(const Eigen::Vector2d& c, double r, int width) {
  return std::clamp((std::min(double(width), c.x() + r) - std::max(0.0, c.x() - r)) / (2 * r),
                    0.0, 1.0);
}

struct Run {
  SequenceResult r;
  double seconds = 0;
};

Run Track(const Film& f, size_t chunk, int lone_search_every = kLoneSearchEveryFrames,
          int coarse_candidates = kCoarseCandidates) {
  MemorySource source(f.frames);
  SequenceOptions o;
  o.follower.lone_search_every = lone_search_every;
  o.follower.coarse_candidates = coarse_candidates;
  o.follower.method = Method::kAuto;
  o.contact_radius_px = f.poses[0].radius_px;
  o.threads = 2;
  o.chunk_frames = chunk;
  const auto t0 = std::chrono::steady_clock::now();
  Run run;
  run.r = TrackSequence(source, o);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return run;
}

// In-view bins of a cut sphere: [0.3, 0.5), [0.5, 0.7), [0.7, 0.9), [0.9, 1].
constexpr int kBins = 4;
// Each sphere's mean error where whole: the film's offset, which every frame shares.
std::array<Eigen::Vector2d, 2> WholeBias(const Film& f, const SequenceResult& r) {
  std::array<Eigen::Vector2d, 2> bias{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)};
  for (int k = 0; k < 2; ++k) {
    size_t n = 0;
    for (size_t i = 0; i < r.frames.size(); ++i) {
      if (!r.frames[i].whole(k)) continue;
      bias[k] += r.frames[i].centre[k] - (k ? f.poses[i].right : f.poses[i].left), ++n;
    }
    if (n) bias[k] /= double(n);
  }
  return bias;
}

int Bin(double in_view) { return in_view < 0.5 ? 0 : in_view < 0.7 ? 1 : in_view < 0.9 ? 2 : 3; }

// Spheres found nearer the other's true centre than their own.
size_t Swaps(const Film& f, const SequenceResult& r) {
  size_t swaps = 0;
  for (size_t i = 0; i < r.frames.size(); ++i) {
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d truth = k ? f.poses[i].right : f.poses[i].left;
      const Eigen::Vector2d other = k ? f.poses[i].left : f.poses[i].right;
      const Eigen::Vector2d& c = r.frames[i].centre[k];
      swaps += r.frames[i].found[k] && (c - other).norm() < (c - truth).norm();
    }
  }
  return swaps;
}

void Row(const char* label, const Film& f, const Run& run, int width, double wide_seconds) {
  const SequenceResult& r = run.r;
  const double radius = f.poses[0].radius_px;
  const std::array<Eigen::Vector2d, 2> bias = WholeBias(f, r);
  size_t half = 0, found = 0, cut_frames = 0;
  double worst[kBins] = {}, sum2[kBins] = {}, z2[kBins] = {};
  size_t count[kBins] = {};
  for (size_t i = 0; i < r.frames.size(); ++i) {
    const FrameTrack& t = r.frames[i];
    cut_frames += (t.found[0] && t.cut[0]) || (t.found[1] && t.cut[1]);
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d truth = k ? f.poses[i].right : f.poses[i].left;
      const double in = InView(truth, radius, width);
      if (in >= 0.5) ++half, found += t.found[k];
      if (!t.found[k] || !t.cut[k]) continue;
      const Eigen::Vector2d e = t.centre[k] - truth - bias[k];
      const int b = Bin(in);
      worst[b] = std::max(worst[b], e.norm());
      sum2[b] += e.squaredNorm() / 2;
      z2[b] += e.cwiseQuotient(t.sigma_px[k]).squaredNorm() / 2;
      ++count[b];
    }
  }
  std::printf("| %s | %s | %zu | %.1f | %zu |", label, ToString(r.method).c_str(), half,
              half ? 100.0 * double(found) / double(half) : 0.0, Swaps(f, r));
  for (int b = 0; b < kBins; ++b) {
    if (count[b] == 0) {
      std::printf(" - |");
      continue;
    }
    std::printf(" %zu: %.3f / %.3f / %.1f |", count[b], std::sqrt(sum2[b] / double(count[b])),
                worst[b], std::sqrt(z2[b] / double(count[b])));
  }
  const double per_frame = run.seconds / double(r.frames.size());
  const double wide_per_frame = wide_seconds / double(r.frames.size());
  std::printf(" %zu | %.2f | %.2f |\n", cut_frames, 1e3 * per_frame, 1e3 * wide_per_frame);
}

// The knobs FollowerOptions::lone_search_every and coarse_candidates on one film: what they save
// (whole-frame searches, time) against what they could cost (spheres at least half in view
// found, swaps, the cut ones' error).
void KnobRow(const Film& f, const char* label, size_t chunk, int every, int coarse, int width) {
  const Run run = Track(f, chunk, every, coarse);
  const double radius = f.poses[0].radius_px;
  size_t half = 0, found = 0, searched = 0, cut = 0;
  double sum2 = 0;
  const std::array<Eigen::Vector2d, 2> bias = WholeBias(f, run.r);
  for (size_t i = 0; i < run.r.frames.size(); ++i) {
    const FrameTrack& t = run.r.frames[i];
    searched += t.acquired;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d truth = k ? f.poses[i].right : f.poses[i].left;
      if (InView(truth, radius, width) >= 0.5) ++half, found += t.found[k];
      if (t.found[k] && t.cut[k]) sum2 += (t.centre[k] - truth - bias[k]).squaredNorm() / 2, ++cut;
    }
  }
  std::printf("| %s, chunks of %zu | %d | %d | %.1f | %zu | %zu | %zu: %.3f | %zu | %.2f |\n",
              label, chunk, every, coarse, half ? 100.0 * double(found) / double(half) : 0.0,
              Swaps(f, run.r), half, cut,
              cut ? std::sqrt(sum2 / double(cut)) : 0.0, searched,
              1e3 * run.seconds / double(run.r.frames.size()));
}

}  // namespace

// The film's frames and its truth (left and right centres, px) in `dir`.
int WriteFilm(const Film& f, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::ofstream truth(dir + "/truth.csv");
  truth << "frame,left_col,left_row,right_col,right_row\n";
  for (size_t i = 0; i < f.frames.size(); ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "/frame_%06zu.bmp", i);
    if (!cv::imwrite(dir + name, f.frames[i])) {
      std::fprintf(stderr, "bench_cut_spheres: %s%s: could not write\n", dir.c_str(), name);
      return 1;
    }
    truth << i << ',' << f.poses[i].left.x() << ',' << f.poses[i].left.y() << ','
          << f.poses[i].right.x() << ',' << f.poses[i].right.y() << '\n';
  }
  return 0;
}

int main(int argc, char** argv) {
  const double speed = argc > 1 ? std::atof(argv[1]) : 1.0;
  if (argc > 3 && std::string(argv[2]) == "--write") {
    return WriteFilm(Render(Lighting::kReflect, 23.75, 512, 128, 512 + 23.75, speed), argv[3]);
  }
  if (!(speed > 0 && speed <= 8)) {
    std::fprintf(stderr, "bench_cut_spheres: the speed must be in (0, 8] px a frame\n");
    return 2;
  }
  std::printf("Spheres cut by the frame's edge: a dimer (A_r %.1f) sliding out by the right edge "
              "at %.2f px a frame and back, 512x%d, noise 2; auto, 2 threads.\n",
              kAspectRatio, speed, kHeight);
  std::printf("Per in-view bin of a cut sphere (fraction of its disc in the frame): count: rms "
              "and worst distance from its whole frames' bias (px) / rms error in stated "
              "sigmas.\n\n");
  std::printf("| film | method | spheres >= half in view | found (%%) | swaps | cut 0.3-0.5 | "
              "cut 0.5-0.7 | cut 0.7-0.9 | cut 0.9-1 | frames with a cut sphere | ms a frame "
              "(wall) | ms a frame, nothing cut (wall) |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  struct Setup {
    Lighting lighting;
    double radius;
  };
  for (const Setup s : {Setup{Lighting::kReflect, 23.75}, Setup{Lighting::kReflect, 11.9},
                        Setup{Lighting::kDisc, 23.75}, Setup{Lighting::kBacklit, 23.75}}) {
    const int width = 512;
    // Out until the left sphere is a radius beyond the right edge, and back.
    const Film film = Render(s.lighting, s.radius, width, 0.25 * width, width + s.radius, speed);
    // As many frames with both spheres whole in view throughout.
    const double length = 2 * (kAspectRatio - 1) * s.radius;
    const double inside = width - length - 2 * s.radius - 8 - (2 * s.radius + 8);
    const size_t n = film.frames.size();
    Film whole;
    for (size_t done = 0; done < n;) {
      const Film leg = Render(s.lighting, s.radius, width, 2 * s.radius + 8,
                              2 * s.radius + 8 + inside, speed);
      for (size_t i = 0; i < leg.frames.size() && done < n; ++i, ++done) {
        whole.poses.push_back(leg.poses[i]);
        whole.frames.push_back(leg.frames[i]);
      }
    }
    const Run wide_run = Track(whole, 512);
    for (const size_t chunk : {size_t(512), size_t(64)}) {
      const Run run = Track(film, chunk);
      const std::string label = ToString(s.lighting) + " R " +
                                (s.radius == 23.75 ? std::string("23.75") : std::string("11.9")) +
                                ", chunks of " + std::to_string(chunk);
      Row(label.c_str(), film, run, width, wide_run.seconds);
    }
  }
  std::printf("\nA frame whose whole-frame search finds one sphere: the other searched for on the "
              "whole frame again only every N frames (FollowerOptions::lone_search_every; 1: "
              "every frame). A whole-frame search at half resolution, then at full resolution "
              "about K of its best peaks (FollowerOptions::coarse_candidates; 0: full resolution "
              "everywhere). Spheres at least half in view found, swaps, cut ones' rms distance "
              "from their whole frames' bias (px), frames searched whole, wall time a "
              "frame.\n\n");
  std::printf("| film | N | K | found (%%) | swaps | spheres >= half in view | cut: rms (px) | "
              "frames searched whole | ms a frame (wall) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  // The mirror-lit film: the backlit one, also followed by the template, shows the same.
  const Film film = Render(Lighting::kReflect, 23.75, 512, 128, 512 + 23.75, speed);
  for (const size_t chunk : {size_t(512), size_t(64)}) {
    for (const int every : {1, 16}) {
      for (const int coarse : {0, kCoarseCandidates}) {
        KnobRow(film, "reflect R 23.75", chunk, every, coarse, 512);
      }
    }
  }
  return 0;
}
