// Tracker accuracy on POV-Ray footage (tests/footage): every lighting of the issue at A_r 3.9 and
// front-lit touching spheres at A_r 2.0, 2.1, 2.3, each tracked by every method, against the
// issue's targets (tests/footage/track_accuracy.h). docs/BENCHMARKS.md,
// bench_tracking_footage.
//   bench_tracking_footage [frames] [subframes] [cache_dir] [methods] [footage]
//   bench_tracking_footage --ecc [frames] [subframes] [cache_dir]
//   bench_tracking_footage --follow [frames] [subframes] [cache_dir]
//   bench_tracking_footage --learn-passes [frames] [subframes] [cache_dir]
//   bench_tracking_footage --camera [frames] [subframes] [cache_dir]
//   bench_tracking_footage --jackknife [frames] [subframes] [cache_dir] [seeds]
//   bench_tracking_footage --exposure [frames] [subframes] [cache_dir]
//   bench_tracking_footage --seeds [frames] [subframes] [cache_dir]
//   bench_tracking_footage --seed-agreement [frames] [subframes] [cache_dir]
//   bench_tracking_footage --scale [frames] [subframes] [cache_dir]
// (--ecc: what ECC's stopping rule trades, tracking/sphere/template_locator.h EccStop; --follow:
// what the quick step that follows before ECC trades, tracking/sphere/fast_follow.h; --learn-passes:
// what the template learning's passes trade, tracking/sphere/appearance_model.h LearnOptions. Every
// case tracked by `auto` with each rule; the accuracy, how far the answers move from the first
// rule's, and the CPU time per frame. --camera: front-lit steel through other cameras,
// tests/footage/camera_variants.h: another scale, defocus, 16 bit, a camera not level; every
// method. --jackknife: the column offset's stated uncertainty over noise seeds, by the
// jackknife's groups; defaults 20 frames, 2 slices, 9 seeds. --exposure: every lighting with
// its levels lowered and as 16-bit frames of a quarter of the range; defaults 20 frames, 2
// slices. --seeds: the rough centres from the highlights, tracking/sphere/highlight_seed.h, on every
// frame of every lighting and its levels x 0.7 and x 0.5, against the truth; defaults 20
// frames, 2 slices; it writes the lowered films into CACHE/levels, as --exposure does.
// --seed-agreement: what leaving out the learning frames whose highlight seeds are not a
// dimer's length apart trades, on the films seeded from their highlights; defaults 20 frames, 2
// slices. --scale: every lighting and camera with the scale given, from the spheres' size and
// from the dimer's length (--ar), through the command; defaults 20 frames, 2 slices.)
// Defaults: 40 frames of the hop motion, 6 exposure slices (300 us at 2000 frames/s), cache
// folder bench_footage_cache (footage is reused while its scenes are unchanged), methods
// "auto,centroid,template" (comma-separated `--method` names of tracking/sphere/measure_sphere.h; auto is the
// default a user gets), every footage (or the comma-separated footage names given, to rerun
// their rows). The tracker is given the scale, as with `--m-per-px`.
// Prints the POV-Ray CPU time per frame of each footage (every slice, antialiased), then one
// row per footage and method, and the machine (cores, load average).
#include <algorithm>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "tests/common/warm_bayer.h"
#include "tests/footage/camera_variants.h"
#include "tracking/sphere/appearance_model.h"
#include "tracking/sphere/highlight_seed.h"
#include "tracking/io/mosaic_grey.h"
#include "tracking/plate/plate_edge.h"
#include "tests/footage/povray_footage.h"
#include "tests/footage/scaled_track.h"
#include "tests/footage/track_accuracy.h"

using namespace dimer::footage;

namespace {

struct Case {
  std::string name;
  Lighting lighting;
  double aspect_ratio;
  int camera = -1;  // index into CameraVariants(); -1: the lighting's own camera
  uint64_t seed = 1;  // the frames' noise seed
};

std::vector<std::string> SplitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// The CPU time per frame recorded in a footage folder's footage.json (kept when reused).
double RecordedCpuPerFrame(const std::string& folder) {
  std::ifstream in(folder + "/footage.json");
  std::string line;
  while (std::getline(in, line)) {
    const size_t p = line.find("\"povray_cpu_seconds_per_frame\": ");
    if (p != std::string::npos) return std::atof(line.c_str() + p + 32);
  }
  return std::nan("");
}

double LoadAverage() {
  double load = std::nan("");
  std::ifstream("/proc/loadavg") >> load;
  return load;
}

std::vector<Case> AllCases() {
  std::vector<Case> cases;
  for (Lighting l : AllLightings()) cases.push_back({ToString(l), l, 3.9});
  for (double ar : {2.0, 2.1, 2.3}) {
    char name[40];
    std::snprintf(name, sizeof name, "front_point A_r %.1f", ar);
    cases.push_back({name, Lighting::kFrontPoint, ar});
  }
  return cases;
}

// front_point through each camera of tests/footage/camera_variants.h.
std::vector<Case> CameraCases() {
  std::vector<Case> cases;
  const std::vector<CameraVariant> v = CameraVariants();
  for (size_t i = 0; i < v.size(); ++i) {
    cases.push_back({v[i].name, Lighting::kFrontPoint, 3.9, int(i)});
  }
  return cases;
}

// The footage of `c` in `cache` (rendered when missing or changed); its folder.
std::string Footage(const Case& c, size_t frames, int slices, const std::string& cache,
                    double* povray_cpu) {
  FootageOptions o = CaseFootageOptions(c.lighting, c.camera);
  o.shape.aspect_ratio = c.aspect_ratio;
  o.seed = c.seed;
  o.subframes = slices;
  o.reuse = true;
  std::string dir = cache + "/" + c.name;
  for (char& ch : dir) {
    if (ch == ' ') ch = '_';
  }
  const FootageResult r = WriteFootage(HopMotion(o.shape, frames, o.fps), o, dir);
  if (povray_cpu) {
    *povray_cpu = r.reused ? RecordedCpuPerFrame(dir) : r.povray_cpu_seconds_per_frame;
  }
  return dir;
}

// One trade-off rule run over every case by `auto` on one thread (so the CPU time is the
// tracking's alone): cases meeting every target, the mean scatter and the worst |bias| over the
// spheres of all cases, each sphere's bias (to see how far a rule moves the answers), and the
// CPU time per frame.
struct RuleResult {
  int met = 0;
  double scatter = 0, worst_bias = 0, cpu_us_per_frame = 0;
  std::vector<Eigen::Vector2d> bias;
};

// `ecc` null: the tracker's default rule.
RuleResult RunRule(const std::vector<std::string>& dirs, const dimer::tracking::EccStop* ecc,
                   int learn_passes, const dimer::tracking::FollowStop* follow = nullptr) {
  RuleResult r;
  double cpu = 0;
  size_t tracked = 0;
  for (const std::string& dir : dirs) {
    const std::clock_t t0 = std::clock();
    TrackerKnobs knobs;
    knobs.ecc = ecc;
    knobs.follow = follow;
    knobs.learn_passes = learn_passes;
    const TrackAccuracy a = MeasureTrackAccuracy(dir, "auto", 1, true, knobs);
    cpu += double(std::clock() - t0) / CLOCKS_PER_SEC;
    tracked += a.frames;
    r.met += a.MeetsTargets();
    for (const SphereAccuracy& s : a.sphere) {
      r.scatter += s.scatter / double(2 * dirs.size());
      r.worst_bias = std::max(r.worst_bias, s.bias.norm());
      r.bias.push_back(s.bias);
    }
  }
  r.cpu_us_per_frame = 1e6 * cpu / double(tracked);
  return r;
}

// "median / largest" distance of each sphere's bias from the first rule's.
std::string Moved(const RuleResult& r, const RuleResult& first) {
  std::vector<double> moved;
  for (size_t i = 0; i < r.bias.size(); ++i) moved.push_back((r.bias[i] - first.bias[i]).norm());
  std::sort(moved.begin(), moved.end());
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f / %.4f", moved[moved.size() / 2], moved.back());
  return buf;
}

std::vector<std::string> AllFootage(size_t frames, int slices, const std::string& cache) {
  std::vector<std::string> dirs;
  for (const Case& c : AllCases()) dirs.push_back(Footage(c, frames, slices, cache, nullptr));
  return dirs;
}

// --ecc: every case tracked with each ECC stopping rule; how far the spheres' mean positions
// moved from the first rule's (ECC run to convergence: median and largest).
int EccTrade(size_t frames, int slices, const std::string& cache) {
  const std::vector<std::string> dirs = AllFootage(frames, slices, cache);
  std::printf("ECC stopping rule against accuracy: %zu POV-Ray cases x %zu frames, `auto`, 1 "
              "thread, load average %.1f at start\n\n| max iterations | epsilon | cases "
              "meeting the targets | mean scatter (px) | worst \\|bias\\| (px) | moved from "
              "the first rule's, median / largest (px) | CPU per frame (us) |\n"
              "|---|---|---|---|---|---|---|\n", dirs.size(), frames, LoadAverage());
  const std::vector<dimer::tracking::EccStop> rules = {
      {50, 1e-7}, {50, 1e-6}, {50, 1e-5}, {50, 1e-4}, {20, 1e-7}, {10, 1e-7}, {5, 1e-7}};
  RuleResult first;
  for (const auto& rule : rules) {
    const RuleResult r = RunRule(dirs, &rule, dimer::tracking::kLearnPasses);
    if (first.bias.empty()) first = r;
    std::printf("| %d | %.0e | %d of %zu | %.4f | %.3f | %s | %.0f |\n", rule.max_iterations,
                rule.epsilon, r.met, dirs.size(), r.scatter, r.worst_bias, Moved(r, first).c_str(),
                r.cpu_us_per_frame);
    std::fflush(stdout);
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

// --follow: every case tracked with each setting of the quick step that follows from the
// prediction (tracking/sphere/fast_follow.h, FollowStop), ECC alone first; how far the spheres'
// mean positions moved from ECC's (median and largest).
int FollowTrade(size_t frames, int slices, const std::string& cache) {
  const std::vector<std::string> dirs = AllFootage(frames, slices, cache);
  std::printf("The quick step against accuracy: %zu POV-Ray cases x %zu frames, `auto`, 1 "
              "thread, load average %.1f at start\n\n| quick step: solves, grid (px), "
              "min. correlation | cases meeting the targets | mean scatter (px) | worst "
              "\\|bias\\| (px) | moved from ECC's, median / largest (px) | CPU per frame (us) |\n"
              "|---|---|---|---|---|---|\n", dirs.size(), frames, LoadAverage());
  const dimer::tracking::FollowStop def;
  const std::vector<dimer::tracking::FollowStop> rules = {
      {0, 8, 0.8}, def, {2, 8, 0.8}, {4, 2, 0.8}, {4, 4, 0.8}, {4, 16, 0.8},
      {4, 8, 0.5}, {4, 8, 0.95}};
  RuleResult first;
  for (const auto& rule : rules) {
    const RuleResult r = RunRule(dirs, nullptr, dimer::tracking::kLearnPasses, &rule);
    if (first.bias.empty()) first = r;
    char label[96];
    if (rule.max_iterations == 0) {
      std::snprintf(label, sizeof label, "none (ECC alone)");
    } else {
      std::snprintf(label, sizeof label, "%d, 1/%d, %.2f%s", rule.max_iterations,
                    rule.shifts_per_px, rule.min_correlation,
                    rule.max_iterations == def.max_iterations &&
                            rule.shifts_per_px == def.shifts_per_px &&
                            rule.min_correlation == def.min_correlation
                        ? " (default)" : "");
    }
    std::printf("| %s | %d of %zu | %.4f | %.3f | %s | %.0f |\n", label, r.met, dirs.size(),
                r.scatter, r.worst_bias, Moved(r, first).c_str(), r.cpu_us_per_frame);
    std::fflush(stdout);
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

// --learn-passes: every case tracked with each number of the template learning's passes
// (tracking/sphere/appearance_model.h, LearnOptions), the tracker's default first; how far the
// spheres' mean positions moved from the default's.
int LearnPassesTrade(size_t frames, int slices, const std::string& cache) {
  const std::vector<std::string> dirs = AllFootage(frames, slices, cache);
  std::printf("Learning passes against accuracy: %zu POV-Ray cases x %zu frames, `auto`, 1 "
              "thread, load average %.1f at start\n\n| learning passes | cases meeting the "
              "targets | mean scatter (px) | worst \\|bias\\| (px) | moved from the default's, "
              "median / largest (px) | CPU per frame (us) |\n|---|---|---|---|---|---|\n",
              dirs.size(), frames, LoadAverage());
  RuleResult first;
  std::vector<int> passes_list = {dimer::tracking::kLearnPasses};
  for (int p : {3, 2, 1, 0}) {
    if (p != dimer::tracking::kLearnPasses) passes_list.push_back(p);
  }
  for (int passes : passes_list) {
    const RuleResult r = RunRule(dirs, nullptr, passes);
    if (first.bias.empty()) first = r;
    std::printf("| %d%s | %d of %zu | %.4f | %.3f | %s | %.0f |\n", passes,
                passes == dimer::tracking::kLearnPasses ? " (default)" : "", r.met, dirs.size(),
                r.scatter, r.worst_bias, Moved(r, first).c_str(), r.cpu_us_per_frame);
    std::fflush(stdout);
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

// --jackknife: the column offset's stated uncertainty against the spread it states, by the
// number of jackknife groups (tracking/sphere/appearance_model.h, kJackknifeGroups; 0: the outline
// pairs' scatter alone). front_point at A_r 3.9 and 5.5, each rendered with noise seeds
// 1..`seeds` (one draw each: the scene and its truth are the same), tracked by `auto` on one
// thread. Per footage and setting, over its spheres: the column bias in units of the stated
// uncertainty (with the bias's sampling error) as RMS (1 when the uncertainty is right),
// largest and how many beyond 2; the RMS stated uncertainty and the RMS bias; the CPU time per
// sequence (the jackknife runs once per sequence, on the learning frames).
int JackknifeTrade(size_t frames, int slices, const std::string& cache, int seeds) {
  struct Family {
    const char* name;
    double aspect_ratio;
    std::vector<std::string> dirs;
  };
  std::vector<Family> families = {{"front_point", 3.9, {}}, {"front_point A_r 5.5", 5.5, {}}};
  for (Family& f : families) {
    for (int seed = 1; seed <= seeds; ++seed) {
      const std::string name = std::string(f.name) + " seed " + std::to_string(seed);
      f.dirs.push_back(Footage({name, Lighting::kFrontPoint, f.aspect_ratio, -1, uint64_t(seed)},
                               frames, slices, cache, nullptr));
    }
  }
  std::printf("Jackknife groups against the column uncertainty's truth: front_point, %zu frames, "
              "%d noise seeds, `auto`, 1 thread, load average %.1f at start\n\n| footage | "
              "jackknife groups | spheres | bias / stated: RMS | largest | beyond 2 | stated "
              "column RMS (px) | column bias RMS (px) | CPU per sequence (ms) |\n"
              "|---|---|---|---|---|---|---|---|---|\n",
              frames, seeds, LoadAverage());
  std::vector<int> groups_list = {dimer::tracking::kJackknifeGroups};
  for (int g : {0, 4, 8, 24}) {
    if (g != dimer::tracking::kJackknifeGroups) groups_list.push_back(g);
  }
  for (const Family& f : families) {
    for (int groups : groups_list) {
      double z2 = 0, worst = 0, stated2 = 0, bias2 = 0, cpu = 0;
      int n = 0, beyond = 0;
      for (const std::string& dir : f.dirs) {
        TrackerKnobs knobs;
        knobs.jackknife_groups = groups;
        const std::clock_t t0 = std::clock();
        const TrackAccuracy a = MeasureTrackAccuracy(dir, "auto", 1, true, knobs);
        cpu += double(std::clock() - t0) / CLOCKS_PER_SEC;
        for (const SphereAccuracy& s : a.sphere) {
          const double z = s.bias_sigmas.x();
          z2 += z * z;
          worst = std::max(worst, z);
          beyond += z > 2;
          stated2 += s.stated_err.x() * s.stated_err.x();
          bias2 += s.bias.x() * s.bias.x();
          ++n;
        }
      }
      std::printf("| %s | %d%s | %d | %.2f | %.2f | %d | %.3f | %.3f | %.0f |\n", f.name, groups,
                  groups == dimer::tracking::kJackknifeGroups ? " (default)" : "", n,
                  std::sqrt(z2 / n), worst, beyond, std::sqrt(stated2 / n), std::sqrt(bias2 / n),
                  1e3 * cpu / double(f.dirs.size()));
      std::fflush(stdout);
    }
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

// Footage `dir` written again with its levels x `factor` into `depth` (rounded), as the folder
// CACHE/levels/NAME_VERSION; returns the folder.
std::string LevelsVersion(const std::string& dir, const std::string& cache,
                          const std::string& name, const std::string& version, double factor,
                          int depth) {
  std::string out = cache + "/levels/" + name + " " + version;
  for (char& ch : out) {
    if (ch == ' ') ch = '_';
  }
  std::filesystem::create_directories(out);
  std::filesystem::copy_file(dir + "/truth.csv", out + "/truth.csv",
                             std::filesystem::copy_options::overwrite_existing);
  for (const TruthRow& row : ReadTruthCsv(dir + "/truth.csv")) {
    cv::Mat img = cv::imread(dir + "/" + row.file, cv::IMREAD_UNCHANGED), scaled;
    img.convertTo(scaled, depth, factor);
    cv::imwrite(out + "/" + row.file, scaled);
  }
  return out;
}

// --seeds: the highlights' rough centres (tracking/sphere/highlight_seed.h) on every frame, as the
// template learning takes them where the silhouette methods find nothing: above the plate's
// coarse row (FindPlateRowCoarse, the tracker's fallback), the film's split chosen by SeedFilm
// (the weighed one or the widest gap: more frames whose seeds stand the median separation apart
// within twice the learning's search, 8 px at R = 23.75), the frames that do not left out. A
// lamp's highlight stands off the centre by the same amount in every frame (the soft box's 6 px,
// the one-sided light's 12), which the learning does not mind: it registers the frames to one
// another and finds the centre on the outline. What it minds is the seeds' scatter about that:
// each sphere's column error less its median over the kept frames, mean and worst, and how many
// kept frames have a seed farther off than the learning's search (LearnSearchPx, 4 px): such a
// seed is averaged in where it is.
int SeedsTrade(size_t frames, int slices, const std::string& cache) {
  std::printf("Highlight seeds against the truth: %zu frames per case, every frame, load average "
              "%.1f at start\n\n", frames, LoadAverage());
  std::printf("| footage | levels | split | frames a dimer apart: weighed / widest gap | kept / "
              "seeded | median column error L / R (px) | scatter about it mean / worst (px) | "
              "kept frames off by more than the learning's search |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : AllCases()) {
    const std::string dir = Footage(c, frames, slices, cache, nullptr);
    for (double factor : {1.0, 0.7, 0.5}) {
      char version[32];
      std::snprintf(version, sizeof version, "levels x %.1f", factor);
      const std::string film =
          factor == 1.0 ? dir : LevelsVersion(dir, cache, c.name, version, factor, CV_8U);
      double radius = 0;
      const std::vector<TruthRow> truth = ReadTruthCsv(film + "/truth.csv", &radius);
      const int search = dimer::tracking::LearnSearchPx(radius);
      std::vector<std::vector<dimer::tracking::HighlightBlob>> blobs;
      for (const TruthRow& row : truth) {
        const cv::Mat img = cv::imread(film + "/" + row.file, cv::IMREAD_UNCHANGED);
        blobs.push_back(dimer::tracking::FindHighlightBlobs(
            img, dimer::tracking::FindPlateRowCoarse(img), radius));
      }
      const dimer::tracking::HighlightSeeds seeds =
          dimer::tracking::SeedFilm(blobs, radius, 2.0 * search, 3);
      std::array<std::vector<double>, 2> error;
      size_t seeded = 0;
      for (size_t i = 0; i < truth.size(); ++i) {
        seeded += seeds.seeded[i];
        if (!seeds.agrees[i]) continue;
        for (int k = 0; k < 2; ++k) {
          error[k].push_back(seeds.seeds[i][k].x() - truth[i].centre[k].x());
        }
      }
      const size_t n = error[0].size();
      std::array<double, 2> median{0, 0};
      for (int k = 0; k < 2 && n > 0; ++k) {
        std::vector<double> e = error[k];
        std::nth_element(e.begin(), e.begin() + std::ptrdiff_t(n / 2), e.end());
        median[k] = e[n / 2];
      }
      double sum = 0, worst = 0;
      size_t off = 0;
      for (size_t i = 0; i < n; ++i) {
        const double d = std::max(std::abs(error[0][i] - median[0]),
                                  std::abs(error[1][i] - median[1]));
        sum += d;
        worst = std::max(worst, d);
        off += d > search;
      }
      std::printf("| %s | x %.1f | %s | %zu / %zu | %zu / %zu | %+.2f / %+.2f | %.2f / %.2f | "
                  "%zu |\n",
                  c.name.c_str(), factor,
                  seeded == 0 ? "-" : seeds.by_mass ? "weighed" : "widest gap",
                  seeds.by_mass ? seeds.agreeing : seeds.other_agreeing,
                  seeds.by_mass ? seeds.other_agreeing : seeds.agreeing, n, seeded, median[0],
                  median[1], n ? sum / double(n) : 0.0, worst, off);
      std::fflush(stdout);
    }
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

// --seed-agreement: how near the film's median separation a learning frame's two highlight seeds
// must stand to be learnt from (tracking/sphere/highlight_seed.h, SeedFilm; LearnOptions::
// seed_agreement_px): by default twice the learning's search (LearnSearchPx, 4 px at R = 23.75),
// each seed then possibly within it; 64 px keeps nearly every frame. It also decides between the
// two splits (more frames agreeing). The films whose learning is seeded from the highlights:
// ring_light, under-exposed and the cluttered backdrop as rendered and at 0.7 of their levels,
// the one-sided light, and front_point through a warm-lit colour sensor made grey by a 3x3
// filter (tests/common/warm_bayer.h, MosaicFilterToGrey; rounded to 8 bits). Tracked by `auto`
// on one thread: each sphere's |bias|, the worst over the films, the films meeting the bias
// target, and the CPU time per sequence.
int SeedAgreementTrade(size_t frames, int slices, const std::string& cache) {
  std::vector<std::pair<std::string, std::string>> films;
  for (const Case& c : AllCases()) {
    if (c.name != "ring_light" && c.name != "underexposed" && c.name != "cluttered_backdrop" &&
        c.name != "one_sided_gain_ramp" && c.name != "front_point") {
      continue;
    }
    const std::string dir = Footage(c, frames, slices, cache, nullptr);
    if (c.name == "front_point") {
      const std::string out = cache + "/levels/front_point_filtered_colour";
      std::filesystem::create_directories(out);
      std::filesystem::copy_file(dir + "/truth.csv", out + "/truth.csv",
                                 std::filesystem::copy_options::overwrite_existing);
      for (const TruthRow& row : ReadTruthCsv(dir + "/truth.csv")) {
        const cv::Mat img = cv::imread(dir + "/" + row.file, cv::IMREAD_UNCHANGED);
        cv::Mat grey;
        dimer::tracking::MosaicFilterToGrey(dimer::testing::WarmBayerMosaic(img))
            .convertTo(grey, CV_8U);
        cv::imwrite(out + "/" + row.file, grey);
      }
      films.emplace_back("front_point, colour sensor, 3x3 filter", out);
      continue;
    }
    films.emplace_back(c.name, dir);
    if (c.name != "one_sided_gain_ramp") {
      films.emplace_back(c.name + " x 0.7",
                         LevelsVersion(dir, cache, c.name, "levels x 0.7", 0.7, CV_8U));
    }
  }
  const double chosen = 2.0 * dimer::tracking::LearnSearchPx(23.75);
  std::printf("Highlight seeds' agreement with the dimer's length: %zu films of %zu frames, R = "
              "23.75 px, `auto`, 1 thread, load average %.1f at start\n\n| agreement (px) | ",
              films.size(), frames, LoadAverage());
  for (const auto& f : films) std::printf("%s: bias L / R (px) | ", f.first.c_str());
  std::printf("worst bias (px) | films within 0.1 px | CPU per sequence (ms) |\n|---|");
  for (size_t i = 0; i < films.size(); ++i) std::printf("---|");
  std::printf("---|---|---|\n");
  for (double agreement : {4.0, 6.0, chosen, 12.0, 64.0}) {
    std::printf("| %.0f%s | ", agreement,
                agreement == chosen ? " (default)" : agreement == 64 ? " (nearly all kept)" : "");
    double worst = 0, cpu = 0;
    int within = 0;
    for (const auto& f : films) {
      TrackerKnobs knobs;
      knobs.seed_agreement_px = agreement;
      const std::clock_t t0 = std::clock();
      const TrackAccuracy a = MeasureTrackAccuracy(f.second, "auto", 1, true, knobs);
      cpu += double(std::clock() - t0) / CLOCKS_PER_SEC;
      const double l = a.sphere[0].bias.norm(), r = a.sphere[1].bias.norm();
      worst = std::max({worst, l, r});
      within += l <= kBiasTargetPx && r <= kBiasTargetPx;
      std::printf("%.3f / %.3f | ", l, r);
      std::fflush(stdout);
    }
    std::printf("%.3f | %d of %zu | %.0f |\n", worst, within, films.size(),
                1e3 * cpu / double(films.size()));
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

// --exposure: how the tracking depends on the film's levels. Every lighting's footage written
// again with its levels x 0.7 and x 0.5 (8-bit, rounded: a lower gain, the noise scaled with
// the signal, so that only the levels change) and as 16-bit frames x 64 (a quarter of the
// 16-bit range, no header: a 14-bit camera's, or a 16-bit one's at a quarter of full scale),
// tracked by `auto`; one row per footage and version, the 8-bit original first.
int ExposureTrade(size_t frames, int slices, const std::string& cache) {
  struct Version {
    const char* name;
    double factor;
    int depth;
  };
  const std::vector<Version> versions = {
      {"levels x 0.7", 0.7, CV_8U}, {"levels x 0.5", 0.5, CV_8U}, {"16-bit x 64", 64, CV_16U}};
  std::printf("The film's levels against accuracy: %zu frames per case, `auto`, load average "
              "%.1f at start\n\n", frames, LoadAverage());
  const std::string header = AccuracyHeader();
  const size_t line2 = header.find('\n') + 1;
  std::printf("| footage | levels %s|---|---%s", header.substr(0, line2).c_str(),
              header.substr(line2).c_str());
  for (const Case& c : AllCases()) {
    const std::string dir = Footage(c, frames, slices, cache, nullptr);
    std::printf("| %s | as rendered %s", c.name.c_str(),
                AccuracyRow(MeasureTrackAccuracy(dir, "auto")).c_str());
    std::fflush(stdout);
    for (const Version& v : versions) {
      const std::string out = LevelsVersion(dir, cache, c.name, v.name, v.factor, v.depth);
      std::printf("| %s | %s %s", c.name.c_str(), v.name,
                  AccuracyRow(MeasureTrackAccuracy(out, "auto")).c_str());
      std::fflush(stdout);
    }
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

// --scale: where the scale comes from, against the truth. Every lighting and camera tracked
// through the command's whole path (tests/footage/scaled_track.h) with the scale given
// (--m-per-px, the truth's), from the spheres' size (--diameter alone, the default) and from
// the dimer's length (--ar): the scale's error, the passes --ar ran, the command's wall time,
// and each sphere's mean error (the rows rest on the radius the scale implies).
int ScaleTrade(size_t frames, int slices, const std::string& cache) {
  std::printf("Where the scale comes from: %zu frames per case, `auto`, %u cores, load average "
              "%.1f at start\n\n",
              frames, std::thread::hardware_concurrency(), LoadAverage());
  std::printf("| footage | scale from | m/px error | --ar passes | s | left mean error (col, row) "
              "px | right mean error (col, row) px |\n|---|---|---|---|---|---|---|\n");
  std::vector<Case> cases = AllCases();
  for (const Case& c : CameraCases()) cases.push_back(c);
  const std::string out = cache + "/scale_trade.h5";
  for (const Case& c : cases) {
    const std::string dir = Footage(c, frames, slices, cache, nullptr);
    const double truth = CaseFootageOptions(c.lighting, c.camera).camera.m_per_px;
    const double nan = std::nan("");
    const struct {
      const char* name;
      double m_per_px, ar;
    } sources[] = {{"`--m-per-px` (true)", truth, nan},
                   {"the spheres' size", nan, nan},
                   {"`--ar`", nan, c.aspect_ratio}};
    for (const auto& src : sources) {
      // The row is printed whole after the command, whose own summary line goes to stdout.
      char row[256];
      std::string line = "| " + c.name + " | " + src.name + " | ";
      try {
        const ScaledTrack t = TrackScaled(dir, out, src.m_per_px, src.ar);
        std::snprintf(row, sizeof row, "%+.3f %% | %.0f | %.2f |",
                      100.0 * (t.m_per_px / truth - 1.0), t.ar_passes, t.seconds);
        line += row;
        for (int k = 0; k < 2; ++k) {
          std::snprintf(row, sizeof row, " (%+.3f, %+.3f) |", t.bias[k].x(), t.bias[k].y());
          line += t.found[k] == 0 ? std::string(" not found |") : std::string(row);
        }
      } catch (const std::exception& e) {
        line += std::string("fails: ") + e.what() + " | | | | |";
      }
      std::printf("%s\n", line.c_str());
      std::fflush(stdout);
    }
  }
  std::filesystem::remove(out);
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const bool camera = argc > 1 && std::string(argv[1]) == "--camera";
  if (camera) {
    --argc;
    ++argv;
  }
  // The modes of 20-frame films in 2 slices by default: [frames] [subframes] [cache_dir].
  using ShortMode = int (*)(size_t, int, const std::string&);
  const std::vector<std::pair<std::string, ShortMode>> short_modes = {
      {"--exposure", ExposureTrade},
      {"--scale", ScaleTrade},
      {"--seed-agreement", SeedAgreementTrade},
      {"--seeds", SeedsTrade}};
  for (const auto& [flag, run] : short_modes) {
    if (argc < 2 || std::string(argv[1]) != flag) continue;
    const size_t frames = argc > 2 ? size_t(std::atol(argv[2])) : 20;
    const int slices = argc > 3 ? std::atoi(argv[3]) : 2;
    const std::string cache = argc > 4 ? argv[4] : "bench_footage_cache";
    std::filesystem::create_directories(cache);
    return run(frames, slices, cache);
  }
  if (argc > 1 && std::string(argv[1]) == "--jackknife") {
    const size_t frames = argc > 2 ? size_t(std::atol(argv[2])) : 20;
    const int slices = argc > 3 ? std::atoi(argv[3]) : 2;
    const std::string cache = argc > 4 ? argv[4] : "bench_footage_cache";
    const int seeds = argc > 5 ? std::atoi(argv[5]) : 9;
    std::filesystem::create_directories(cache);
    return JackknifeTrade(frames, slices, cache, seeds);
  }
  if (argc > 1 && std::string(argv[1]) == "--follow") {
    const size_t frames = argc > 2 ? size_t(std::atol(argv[2])) : 40;
    const int slices = argc > 3 ? std::atoi(argv[3]) : 6;
    return FollowTrade(frames, slices, argc > 4 ? argv[4] : "bench_footage_cache");
  }
  if (argc > 1 && (std::string(argv[1]) == "--ecc" || std::string(argv[1]) == "--learn-passes")) {
    const size_t frames = argc > 2 ? size_t(std::atol(argv[2])) : 40;
    const int slices = argc > 3 ? std::atoi(argv[3]) : 6;
    const std::string cache = argc > 4 ? argv[4] : "bench_footage_cache";
    return std::string(argv[1]) == "--ecc" ? EccTrade(frames, slices, cache)
                                           : LearnPassesTrade(frames, slices, cache);
  }
  const size_t frames = argc > 1 ? size_t(std::atol(argv[1])) : 40;
  const int slices = argc > 2 ? std::atoi(argv[2]) : 6;
  const std::string cache = argc > 3 ? argv[3] : "bench_footage_cache";
  const std::vector<std::string> methods =
      SplitList(argc > 4 ? argv[4] : "auto,centroid,template");
  std::vector<Case> cases = camera ? CameraCases() : AllCases();
  if (argc > 5) {
    const std::vector<std::string> only = SplitList(argv[5]);
    std::erase_if(cases, [&](const Case& c) {
      return std::find(only.begin(), only.end(), c.name) == only.end();
    });
  }
  std::filesystem::create_directories(cache);
  std::printf("POV-Ray footage: %zu frames per case, 640x320, %s, 300 us exposure in %d "
              "slices, noise 2 grey levels; %u cores, load average %.1f at start\n\n",
              frames, camera ? "front_point, the camera as named" : "0.2 mm/px, PSF 0.5 px, 8 bit",
              slices, std::thread::hardware_concurrency(), LoadAverage());
  // The harness's table with two columns in front.
  const std::string header = AccuracyHeader();
  const size_t line2 = header.find('\n') + 1;
  std::printf("| footage | POV-Ray CPU s/frame %s|---|---%s", header.substr(0, line2).c_str(),
              header.substr(line2).c_str());
  for (const Case& c : cases) {
    try {
      double cpu = 0;
      const std::string dir = Footage(c, frames, slices, cache, &cpu);
      // A camera with a lens (pincushion_lens) is tracked with its calibration, as `track
      // --lens` (its lens.yml), and as recorded beside it.
      TrackerKnobs lens;
      lens.lens = LensFileOf(c.camera, dir);
      for (const std::string& m : methods) {
        const TrackAccuracy a = MeasureTrackAccuracy(dir, m, 0, true, lens);
        std::printf("| %s%s | %.2f %s", c.name.c_str(), lens.lens.empty() ? "" : " --lens", cpu,
                    AccuracyRow(a).c_str());
        if (!lens.lens.empty()) {
          std::printf("| %s as recorded | %.2f %s", c.name.c_str(), cpu,
                      AccuracyRow(MeasureTrackAccuracy(dir, m)).c_str());
        }
        std::fflush(stdout);
      }
    } catch (const std::exception& e) {
      std::printf("| %s | | error: %s |\n", c.name.c_str(), e.what());
    }
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}
