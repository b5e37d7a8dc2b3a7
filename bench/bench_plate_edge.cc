// Plate-edge accuracy on folders of frames with truth.csv (`dimerlab render` or the POV-Ray
// footage of tests/footage, e.g. its lightings one_sided_gain_ramp, underexposed, overexposed,
// mirror_plate), docs/BENCHMARKS.md, bench_plate_edge:
//   bench_plate_edge DIR...
//   bench_plate_edge --time [calls]   (cost of one RefinePlateRow call on a rendered frame)
//   bench_plate_edge --psf-sensitivity (a clipped edge's error when the camera's blur differs)
//   bench_plate_edge --clipped-sequence (an over-exposed plate over a sequence: the shared level)
// Per folder: the error of the acquisition's coarse row (FindPlateRowCoarse), of the sub-pixel
// row refined from it with the spheres' true columns left out (RefinePlateRow, as the tracker
// calls it), and of the tracker's own plate row (FrameFollower, spheres found by itself):
// RMS and worst, px, and how many frames gave no row.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "tests/tracking/plate/clipped_edge_frame.h"
#include <tuple>
#include <vector>

#include <chrono>

#include "tracking/plate/plate_edge.h"
#include "render/scene_renderer.h"
#include "tracking/tolerances.h"
#include "tracking/frame_follower.h"

using namespace dimer::tracking;

namespace {

struct TruthRow {
  std::string file;
  double left_col = 0, right_col = 0, plate_row = 0;
};

// truth.csv: comment lines (#), a header, then frame,file,t,left_col,left_row,right_col,
// right_row,plate_row. The radius from the comment's radius_px=.
std::vector<TruthRow> ReadTruth(const std::string& dir, double* radius_px) {
  std::ifstream in(dir + "/truth.csv");
  std::vector<TruthRow> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      const auto at = line.find("radius_px=");
      if (at != std::string::npos) *radius_px = std::atof(line.c_str() + at + 10);
      continue;
    }
    if (line.rfind("frame", 0) == 0) continue;
    std::stringstream ss(line);
    std::vector<std::string> f;
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (f.size() < 8) continue;
    rows.push_back({f[1], std::stod(f[3]), std::stod(f[5]), std::stod(f[7])});
  }
  return rows;
}

struct Stat {
  double sum2 = 0, worst = 0;
  int n = 0, missing = 0;
  void Add(double err) {
    if (!std::isfinite(err)) {
      ++missing;
      return;
    }
    sum2 += err * err;
    worst = std::max(worst, std::abs(err));
    ++n;
  }
  std::string Text() const {
    char buf[80];
    std::snprintf(buf, sizeof buf, "%.3f | %.3f | %d", n ? std::sqrt(sum2 / n) : NAN, worst,
                  missing);
    return buf;
  }
};

}  // namespace

// Microseconds per RefinePlateRow call (best of 3 runs) on a reflect-lit 512x256 frame with
// two sphere intervals left out, as the tracker calls it once per frame; then on the same frame
// over-exposed x 3 (the plate clips: the clipped-edge fit runs, ClippedEdgeRowInProfile).
int TimeRefine(int calls) {
  SceneGeometry s;
  s.left = {180.3, 176.2};
  s.right = {318.1, 166.4};
  const cv::Mat img = RenderFrame({s}, RenderOptions{}, 0);
  const cv::Mat clipped = [&] {
    cv::Mat c;
    img.convertTo(c, CV_8U, 3.0);  // saturating
    return c;
  }();
  const double clear = s.radius_px + kPlateSphereClearPx;
  const std::vector<std::pair<double, double>> excluded = {
      {s.left.x() - clear, s.left.x() + clear}, {s.right.x() - clear, s.right.x() + clear}};
  for (const auto& [name, frame, n] : {std::tuple{"RefinePlateRow", &img, calls},
                                       std::tuple{"RefinePlateRow, plate clipped", &clipped,
                                                  std::max(1, calls / 50)}}) {
    double best = 1e30, sink = 0;
    for (int run = 0; run < 3; ++run) {
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < n; ++i) sink += RefinePlateRow(*frame, 200.0 + 0.001 * (i % 3), excluded);
      const double us =
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
      best = std::min(best, us / n);
    }
    std::printf("%s: %.2f us per call (best of 3 x %d calls; row %.4f)\n", name, best, n,
                sink / (3.0 * n));
  }
  return 0;
}

// Worst error of RefinePlateRow (fit sigma kPlatePsfSigmaPx) on synthetic clipped edges made as
// the POV-Ray footage makes them (box-sampled step from 0 to 128 x gain, cv::GaussianBlur of
// the true sigma, noise sigma 2, rounded, clipped to 8 bits), 50 edge rows across a pixel, for
// a plate at 1.2, 2 and 4 times the clip and a camera blur of 0.4 to 0.8 px.
int PsfSensitivity() {
  const auto frame = [](double edge, double gain, double psf, uint64_t seed) {
    return dimer::tracking::ClippedBlurredEdge(edge, gain, psf, seed);
  };
  std::printf("| true sigma (px) | plate 1.2 x clip | 2 x clip | 4 x clip |\n|---|---|---|---|\n");
  for (double psf : {0.4, 0.5, 0.6, 0.8}) {
    std::printf("| %.1f |", psf);
    for (double gain : {2.4, 4.0, 8.0}) {
      double worst = 0;
      for (int i = 0; i < 50; ++i) {
        const double y = 59.51 + 0.02 * i;
        worst = std::max(worst, std::abs(RefinePlateRow(frame(y, gain, psf, i), 60.5, {}) - y));
      }
      std::printf(" %.2f |", worst);
    }
    std::printf("\n");
  }
  return 0;
}

// An over-exposed plate over a sequence (tracking/plate/clipped_edge.h): the plate moving across two
// pixels (edge at 59.02 + 0.04 i, 50 frames, made as PsfSensitivity's), each frame's row alone
// and then at the level the frames share, for plates at 1.2 to 5 x the clip and a camera blur of
// 0.4 to 0.8 px, the blur assumed (0.5) or fitted with the level; then what the number of
// frames the level is fitted on trades, on 400 frames across eight pixels. Times: the fits and
// the refit, per sequence.
int ClippedSequence() {
  const auto sweep = [](double gain, double psf, int frames, double step, uint64_t seed0) {
    std::vector<ClippedEdgeProfile> p(frames);
    std::vector<double> rows(frames), truth(frames);
    for (int i = 0; i < frames; ++i) {
      truth[i] = 59.02 + step * i;
      rows[i] = RefinePlateRow(dimer::tracking::ClippedBlurredEdge(truth[i], gain, psf, seed0 + i),
                               60.5 + std::floor(step * i), {}, kPlatePsfSigmaPx, &p[i]);
    }
    return std::tuple{p, rows, truth};
  };
  const auto worst = [](const std::vector<double>& a, const std::vector<double>& b) {
    double w = 0;
    for (size_t i = 0; i < a.size(); ++i) w = std::max(w, std::abs(a[i] - b[i]));
    return w;
  };
  const auto pointers = [](const std::vector<ClippedEdgeProfile>& p) {
    std::vector<const ClippedEdgeProfile*> out;
    for (const auto& x : p) out.push_back(&x);
    return out;
  };
  std::printf("| true sigma (px) | plate level (x clip) | frames with two lit rows | worst row "
              "alone (px) | blur 0.5 assumed: level error (%%) | worst row (px) | blur fitted "
              "(px) | level error (%%) | worst row (px) | fit + refit (ms) |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n");
  for (double psf : {0.4, 0.5, 0.6, 0.8}) {
    for (double gain : {2.4, 4.0, 10.0}) {
      auto [p, rows, truth] = sweep(gain, psf, 50, 0.04, 100);
      std::printf("| %.1f | %.1f | ", psf, gain * 128 / 255);
      const double alone = worst(rows, truth);
      for (bool fit : {false, true}) {
        std::vector<double> r = rows;
        const auto t0 = std::chrono::steady_clock::now();
        const ClippedLevel level =
            SharedClippedLevel(pointers(p), kPlatePsfSigmaPx, kClippedLevelMaxFrames, fit);
        RefitClippedRows(pointers(p), level, &r);
        const double ms = std::chrono::duration<double, std::milli>(
                              std::chrono::steady_clock::now() - t0).count();
        if (!fit) std::printf("%zu | %.3f | ", level.informative, alone);
        if (fit) std::printf("%.2f | ", level.psf_sigma);
        std::printf("%+.1f | %.3f | ", 100 * (level.value / (128 * gain) - 1), worst(r, truth));
        if (fit) std::printf("%.0f |\n", ms);
      }
    }
  }
  std::printf("\nLevel fitted on at most N of the informative frames (400 frames, plate at 2 x "
              "clip, sigma 0.5):\n\n| N | frames used | level error (%%) | worst row (px) | "
              "RMS row (px) | level (ms) |\n|---|---|---|---|---|---|\n");
  auto [p, rows0, truth] = sweep(4.0, 0.5, 400, 0.02, 1000);
  for (size_t n : {3, 8, 16, 32, 64, 128}) {
    std::vector<double> rows = rows0;
    const auto t0 = std::chrono::steady_clock::now();
    const ClippedLevel level = SharedClippedLevel(pointers(p), kPlatePsfSigmaPx, n);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    RefitClippedRows(pointers(p), level, &rows);
    double ss = 0;
    for (size_t i = 0; i < rows.size(); ++i) ss += (rows[i] - truth[i]) * (rows[i] - truth[i]);
    std::printf("| %zu | %zu | %+.2f | %.3f | %.3f | %.1f |\n", n, level.used,
                100 * (level.value / 512.0 - 1), worst(rows, truth),
                std::sqrt(ss / double(rows.size())), ms);
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "--clipped-sequence") return ClippedSequence();
  if (argc >= 2 && std::string(argv[1]) == "--psf-sensitivity") return PsfSensitivity();
  if (argc >= 2 && std::string(argv[1]) == "--time") {
    return TimeRefine(argc >= 3 ? std::atoi(argv[2]) : 20000);
  }
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_plate_edge DIR...\n");
    return 2;
  }
  std::printf("| folder | frames | coarse RMS (px) | coarse worst | coarse none | refined RMS (px) "
              "| refined worst | refined none | tracker RMS (px) | tracker worst | tracker none |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int a = 1; a < argc; ++a) {
    const std::string dir = argv[a];
    double radius = 23.75;
    const std::vector<TruthRow> truth = ReadTruth(dir, &radius);
    Stat coarse, refined, tracked;
    FrameFollower tracker(FollowerOptions{});
    for (size_t i = 0; i < truth.size(); ++i) {
      const cv::Mat img = cv::imread(dir + "/" + truth[i].file, cv::IMREAD_UNCHANGED);
      if (img.empty() || img.channels() != 1) {
        std::fprintf(stderr, "%s/%s: not a single-channel image\n", dir.c_str(),
                     truth[i].file.c_str());
        return 1;
      }
      if (i == 0 && std::getenv("PLATE_PROFILE")) {  // rows around the edge, columns 0..99
        const int r = int(std::lround(truth[i].plate_row));
        for (int row = r - 6; row <= r + 6; ++row) {
          double sum = 0;
          for (int col = 0; col < 100; ++col) sum += img.depth() == CV_8U ? img.at<uint8_t>(row, col) : img.at<uint16_t>(row, col);
          std::fprintf(stderr, "  row %d mean %.2f\n", row, sum / 100);
        }
      }
      const double c = FindPlateRowCoarse(img);
      coarse.Add(c - truth[i].plate_row);
      const double clear = radius + kPlateSphereClearPx;
      const double fine =
          RefinePlateRow(img, c,
                         {{truth[i].left_col - clear, truth[i].left_col + clear},
                          {truth[i].right_col - clear, truth[i].right_col + clear}});
      refined.Add(fine - truth[i].plate_row);
      tracked.Add(tracker.Process(img, i).plate_row - truth[i].plate_row);
    }
    std::printf("| %s | %zu | %s | %s | %s |\n", dir.c_str(), truth.size(),
                coarse.Text().c_str(), refined.Text().c_str(), tracked.Text().c_str());
  }
  return 0;
}
