// Tracking benchmark: accuracy against speed for every method on the project's targets (docs/BENCHMARKS.md).
//   bench_tracking [frames]   (default 2000 frames per case)
// Prints, per method: RMS error and pixel locking on uniform discs at sigma = 2 with the
// Cramér-Rao bound computed from the exact disc model; scatter about the bias on reflect-lit
// spheres (both methods end with the rim fit on mirror spheres); in-memory tracking rate on 1
// and all cores for uniform and mirror spheres; the sequence-level methods (template, auto)
// against the centroid on a resting + bouncing sequence, reflect and backlit (worst bias and
// scatter over both spheres and axes after the template's offset, the resting sphere's locking
// to the pixel grid, rates with the learning included), and `auto` on spheres of half that
// radius; and PNG decode-only vs end-to-end rates. It also
// prints the load average and how many cores a busy loop really gets, since the machine may be
// shared.
#include <opencv2/imgcodecs.hpp>

#include <Eigen/Dense>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <thread>

#include "bench/available_cores.h"
#include "common/disc_coverage.h"
#include "tracking/io/frame_source.h"
#include "tracking/sphere/measure_sphere.h"
#include "render/scene_renderer.h"
#include "tracking/run_track.h"

using namespace dimer::tracking;
using dimer::DiscPixelCoverage;  // common/disc_coverage.h
using dimer::PixelCoverage;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kRadius = 23.75, kRodHalf = 3.75, kSigma = 2.0;

double Seconds(Clock::time_point a) { return std::chrono::duration<double>(Clock::now() - a).count(); }

SceneGeometry Dimer(double col, double row, double plate) {
  SceneGeometry s;
  s.radius_px = kRadius;
  s.rod_half_width_px = kRodHalf;
  s.plate_row = plate;
  s.left = {col, row};
  s.right = s.left + Eigen::Vector2d(137.75, -10);
  return s;
}

// Cramér-Rao bound on the centre column of a disc (5 parameters: cx, cy, R, levels) with
// Gaussian noise sigma_eff (noise plus quantisation), from the exact coverage derivatives.
double CramerRao(double contrast, double sigma_eff) {
  const Eigen::Vector2d c(100.37, 100.61);
  Eigen::Matrix<double, 5, 5> fisher = Eigen::Matrix<double, 5, 5>::Zero();
  for (int row = 70; row <= 131; ++row) {
    for (int col = 70; col <= 131; ++col) {
      const PixelCoverage p = DiscPixelCoverage(col, row, c, kRadius);
      Eigen::Matrix<double, 5, 1> j;
      j << contrast * p.d_cx, contrast * p.d_cy, contrast * p.d_r, 1 - p.area, p.area;
      fisher += j * j.transpose() / (sigma_eff * sigma_eff);
    }
  }
  return std::sqrt(fisher.inverse()(0, 0));
}

// Peak to peak of the mean error (less the overall mean) in 10 bins of the true position's
// fractional part: the locking to the pixel grid.
double Locking(const std::vector<double>& truth, const std::vector<double>& error) {
  std::vector<double> sum(10, 0), count(10, 0);
  double mean = 0;
  for (double e : error) mean += e / double(error.size());
  for (size_t i = 0; i < truth.size(); ++i) {
    const int b = std::min(9, int((truth[i] - std::floor(truth[i])) * 10));
    sum[b] += error[i] - mean;
    count[b] += 1;
  }
  double lo = 1e9, hi = -1e9;
  for (int b = 0; b < 10; ++b) {
    if (count[b] == 0) continue;
    lo = std::min(lo, sum[b] / count[b]);
    hi = std::max(hi, sum[b] / count[b]);
  }
  return hi - lo;
}

struct Accuracy {
  double rms = 0, scatter = 0, locking = 0;
};

// Lifted spheres at random sub-pixel positions; locking = peak to peak of the binned mean
// error against the fractional column (10 bins).
Accuracy MeasureAccuracy(Method method, Lighting lighting, int n) {
  RenderOptions o;
  o.lighting = lighting;
  o.noise = kSigma;
  o.gradient = 0;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> ex, ey, col;
  for (int i = 0; i < n; ++i) {
    const SceneGeometry s = Dimer(150 + 20 * u(rng), 150 + 10 * u(rng), 200);
    const cv::Mat img = RenderFrame({s}, o, i);
    RefineContext ctx;
    ctx.polarity = 1;
    ctx.plate_row = s.plate_row;
    ctx.rod_dir = (s.right - s.left).normalized();
    const SphereMeasurement m = MeasureSphere(img, s.left + Eigen::Vector2d(0.7, -0.5), kRadius, ctx, method);
    if (!m.found()) continue;
    ex.push_back(m.centre.x() - s.left.x());
    ey.push_back(m.centre.y() - s.left.y());
    col.push_back(s.left.x());
  }
  Accuracy a;
  double mx = 0, my = 0;
  for (size_t i = 0; i < ex.size(); ++i) mx += ex[i] / ex.size(), my += ey[i] / ey.size();
  for (size_t i = 0; i < ex.size(); ++i) {
    a.rms += (ex[i] * ex[i] + ey[i] * ey[i]) / ex.size();
    a.scatter += ((ex[i] - mx) * (ex[i] - mx) + (ey[i] - my) * (ey[i] - my)) / ex.size();
  }
  a.rms = std::sqrt(a.rms);
  a.scatter = std::sqrt(a.scatter);
  a.locking = Locking(col, ex);
  return a;
}

std::vector<cv::Mat> Frames(int n, Lighting l) {
  RenderOptions o;
  o.lighting = l;
  o.noise = kSigma;
  std::vector<cv::Mat> out;
  for (int i = 0; i < n; ++i) out.push_back(RenderFrame({Dimer(150 + 0.01 * i, 170, 200)}, o, i));
  return out;
}

// Best of three runs (the machine is shared: the best run is the least disturbed one).
double InMemoryRate(Method method, const std::vector<cv::Mat>& frames, int threads) {
  double best = 0;
  for (int rep = 0; rep < 3; ++rep) {
    MemorySource src(frames);
    SequenceOptions opts;
    opts.follower.method = method;
    opts.threads = threads;
    const auto t0 = Clock::now();
    const SequenceResult r = TrackSequence(src, opts);
    best = std::max(best, double(r.frames.size()) / Seconds(t0));
  }
  return best;
}

// A sequence in memory for the sequence-level methods (template, auto): the plate moves up and
// down by kPlateSwingPx every 80 frames (25 Hz at 2000 frames/s), the left sphere rests on it,
// the right one lifts up to 14 px (at R = 23.75 px; scaled with the radius) and lands every 80
// frames, the dimer creeps 0.05 px per frame: both fractions of the resting sphere's position
// sweep every value (its locking to the pixel grid shows). Truth per frame.
constexpr double kPlateSwingPx = 1.0;
struct Sequence {
  double radius = kRadius;
  std::vector<cv::Mat> frames;
  std::vector<SceneGeometry> truth;
};
Sequence HopSequence(int n, Lighting l, double radius = kRadius) {
  RenderOptions o;
  o.lighting = l;
  o.noise = kSigma;
  Sequence q;
  q.radius = radius;
  const double scale = radius / kRadius;
  for (int i = 0; i < n; ++i) {
    SceneGeometry s;
    s.radius_px = radius;
    s.rod_half_width_px = kRodHalf * scale;
    s.plate_row = 200 + kPlateSwingPx * std::sin(2 * M_PI * i / 80.0);
    s.left = {150 + 0.05 * i, s.plate_row - radius};
    const double lift = 14.0 * scale * std::abs(std::sin(M_PI * i / 80.0));
    const double d = 137.75 * scale;
    s.right = s.left + Eigen::Vector2d(std::sqrt(d * d - lift * lift), -lift);
    q.truth.push_back(s);
    q.frames.push_back(RenderFrame({s}, o, i));
  }
  return q;
}

struct SequenceAccuracy {
  double worst_bias = 0, worst_scatter = 0, found = 0, rate1 = 0, rate2 = 0;
  double locking_col = 0, locking_row = 0;  // the resting (left) sphere's, px
  // CPU microseconds per frame (user + system, all threads; least over the runs): unlike the
  // rates, it hardly depends on what else runs on a shared machine.
  double cpu_us1 = 1e30, cpu_us2 = 1e30;
  std::string method;
};

double SelfCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

SequenceAccuracy MeasureSequence(Method method, const Sequence& q, int cores,
                                 const EccStop& ecc = FollowerOptions{}.ecc,
                                 const FollowStop& follow = FollowerOptions{}.follow) {
  SequenceAccuracy a;
  for (int threads : {1, cores}) {
    double best = 0;
    SequenceResult r;
    for (int rep = 0; rep < 3; ++rep) {
      MemorySource src(q.frames);
      SequenceOptions opts;
      opts.follower.method = method;
      opts.threads = threads;
      opts.contact_radius_px = q.radius;  // the scale is known
      opts.follower.ecc = ecc;
      opts.follower.follow = follow;
      const auto t0 = Clock::now();
      const double c0 = SelfCpuSeconds();
      r = TrackSequence(src, opts);
      best = std::max(best, double(r.frames.size()) / Seconds(t0));
      double& cpu = threads == 1 ? a.cpu_us1 : a.cpu_us2;
      cpu = std::min(cpu, 1e6 * (SelfCpuSeconds() - c0) / double(r.frames.size()));
    }
    (threads == 1 ? a.rate1 : a.rate2) = best;
    if (threads != 1) continue;
    a.method = ToString(r.method);
    double sum[2][2] = {}, sum2[2][2] = {};
    size_t n = 0;
    std::vector<double> truth_col, truth_row, error_col, error_row;  // the resting sphere's
    for (size_t i = 0; i < r.frames.size(); ++i) {
      const FrameTrack& t = r.frames[i];
      if (!t.found[0] || !t.found[1]) continue;
      ++n;
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector2d e = t.centre[k] - (k == 0 ? q.truth[i].left : q.truth[i].right);
        for (int ax = 0; ax < 2; ++ax) sum[k][ax] += e(ax), sum2[k][ax] += e(ax) * e(ax);
      }
      const Eigen::Vector2d e = t.centre[0] - q.truth[i].left;
      truth_col.push_back(q.truth[i].left.x()), error_col.push_back(e.x());
      truth_row.push_back(q.truth[i].left.y()), error_row.push_back(e.y());
    }
    a.locking_col = Locking(truth_col, error_col);
    a.locking_row = Locking(truth_row, error_row);
    for (int k = 0; k < 2; ++k) {
      for (int ax = 0; ax < 2; ++ax) {
        const double b = sum[k][ax] / double(n);
        a.worst_bias = std::max(a.worst_bias, std::abs(b));
        a.worst_scatter = std::max(a.worst_scatter, std::sqrt(std::max(0.0, sum2[k][ax] / double(n) - b * b)));
      }
    }
    a.found = double(n) / double(q.frames.size());
  }
  return a;
}

using dimer::bench::AvailableCores;

std::string LoadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string a;
  in >> a;
  return a.empty() ? "?" : a;
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 2000;
  const int cores = int(std::thread::hardware_concurrency());
  const double crb = CramerRao(0.68 * 255, std::sqrt(kSigma * kSigma + 1.0 / 12));
  std::printf("tracking benchmark: 512x256 8-bit, spheres %.1f px across, sigma %.0f, %d cores\n",
              2 * kRadius, kSigma, cores);
  std::printf("Cramer-Rao bound (disc, per axis): %.4f px\n\n", crb);
  const std::vector<cv::Mat> frames = Frames(n, Lighting::kDisc);
  const std::vector<cv::Mat> mirror = Frames(n, Lighting::kReflect);
  std::printf("load average %s; cores available to a 2-thread busy loop: %.2f\n\n",
              LoadAverage().c_str(), AvailableCores(cores));
  std::printf("| method | disc RMS (px) | disc RMS / (sqrt2 CRB) | locking p-p (px) | reflect scatter (px) | frames/s 1 thread | frames/s %d threads | reflect frames/s %d threads |\n", cores, cores);
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (Method m : {Method::kCentroid, Method::kDiscFit}) {
    const Accuracy disc = MeasureAccuracy(m, Lighting::kDisc, std::min(n, 400));
    const Accuracy refl = MeasureAccuracy(m, Lighting::kReflect, std::min(n, 200));
    std::printf("| %s | %.4f | %.2f | %.4f | %.3f | %.0f | %.0f | %.0f |\n", ToString(m).c_str(),
                disc.rms, disc.rms / (std::sqrt(2.0) * crb), disc.locking, refl.scatter,
                InMemoryRate(m, frames, 1), InMemoryRate(m, frames, cores),
                InMemoryRate(m, mirror, cores));
  }
  // Sequence-level methods: learnt appearance (template) and the per-footage choice (auto),
  // against the centroid, on a sequence with a resting and a bouncing sphere.
  std::printf("\nSequences of %d frames (the plate moving +-1 px, left sphere resting, right one "
              "bouncing; learning and offset estimation included in the rates):\n\n",
              std::min(n, 800));
  std::printf("| lighting | method asked | method run | worst \\|bias\\| (px) | worst scatter (px) | resting sphere's locking p-p, col / row (px) | found | frames/s 1 thread | frames/s %d threads | µs CPU/frame 1 thread | µs CPU/frame %d threads |\n", cores, cores);
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  // Each lighting at R = 23.75 px by every method, and `auto` at half that radius (9.5 mm
  // spheres at 0.4 mm/px), where the template locks to the pixel grid.
  for (const double radius : {kRadius, 0.5 * kRadius}) {
    for (Lighting l : {Lighting::kReflect, Lighting::kBacklit}) {
      const Sequence q = HopSequence(std::min(n, 800), l, radius);
      for (Method m : {Method::kCentroid, Method::kTemplate, Method::kAuto}) {
        if (radius != kRadius && m != Method::kAuto) continue;
        const SequenceAccuracy a = MeasureSequence(m, q, cores);
        char label[64];
        std::snprintf(label, sizeof label, "%s%s", ToString(l).c_str(),
                      radius == kRadius ? "" : ", R 11.9 px");
        std::printf("| %s | %s | %s | %.4f | %.4f | %.3f / %.3f | %.1f %% | %.0f | %.0f | %.0f | %.0f |\n",
                    label, ToString(m).c_str(), a.method.c_str(), a.worst_bias, a.worst_scatter,
                    a.locking_col, a.locking_row, 100 * a.found, a.rate1, a.rate2, a.cpu_us1,
                    a.cpu_us2);
        std::fflush(stdout);
      }
    }
  }
  // The quick step that follows from the prediction before ECC (tracking/sphere/fast_follow.h,
  // FollowStop): what its knobs trade, on the reflect sequence; ECC alone first.
  const FollowStop def;
  std::printf("\nThe quick step, template on the reflect sequence (%d frames; the tracker's "
              "default: %d iterations, grid 1/%d px, correlation >= %.2f):\n\n"
              "| quick step: solves, grid (px), min. correlation | worst \\|bias\\| (px) | "
              "worst scatter (px) | found | µs CPU/frame 1 thread |\n|---|---|---|---|---|\n",
              std::min(n, 800), def.max_iterations, def.shifts_per_px, def.min_correlation);
  {
    const Sequence q = HopSequence(std::min(n, 800), Lighting::kReflect);
    for (const FollowStop& rule : std::vector<FollowStop>{{0, 8, 0.8}, def, {2, 8, 0.8},
                                                          {4, 2, 0.8}, {4, 4, 0.8}, {4, 16, 0.8},
                                                          {4, 8, 0.5}, {4, 8, 0.95}}) {
      const SequenceAccuracy a =
          MeasureSequence(Method::kTemplate, q, 1, FollowerOptions{}.ecc, rule);
      char label[96];
      if (rule.max_iterations == 0) {
        std::snprintf(label, sizeof label, "none (ECC alone)");
      } else {
        const bool is_def = rule.max_iterations == def.max_iterations &&
                            rule.shifts_per_px == def.shifts_per_px &&
                            rule.min_correlation == def.min_correlation;
        std::snprintf(label, sizeof label, "%d, 1/%d, %.2f%s", rule.max_iterations,
                      rule.shifts_per_px, rule.min_correlation, is_def ? " (default)" : "");
      }
      std::printf("| %s | %.4f | %.4f | %.1f %% | %.0f |\n", label, a.worst_bias,
                  a.worst_scatter, 100 * a.found, a.cpu_us1);
      std::fflush(stdout);
    }
  }
  // End to end from PNG files against decode only, both on all cores.
  const std::string dir = (std::filesystem::temp_directory_path() / "bench_tracking_png").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (int i = 0; i < n; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "/frame_%06d.png", i);
    cv::imwrite(dir + name, frames[i]);
  }
  auto src = OpenFrameSource(dir);
  double decode = 0, e2e = 0;
  for (int rep = 0; rep < 2; ++rep) {  // alternated, best of two each (shared machine)
    std::atomic<size_t> next{0};
    auto t0 = Clock::now();
    std::vector<std::thread> pool;
    for (int k = 0; k < cores; ++k) {
      pool.emplace_back([&] {
        for (size_t i = next++; i < src->size(); i = next++) (void)src->Read(i);
      });
    }
    for (auto& t : pool) t.join();
    decode = std::max(decode, double(src->size()) / Seconds(t0));
    SequenceOptions opts;
    t0 = Clock::now();
    const SequenceResult r = TrackSequence(*src, opts);
    e2e = std::max(e2e, double(r.frames.size()) / Seconds(t0));
  }
  std::printf("\nPNG folder (%d frames): decode only %.0f frames/s, decode + centroid tracking %.0f frames/s (%.0f %%)\n",
              n, decode, e2e, 100 * e2e / decode);
  std::filesystem::remove_all(dir);
  return 0;
}
