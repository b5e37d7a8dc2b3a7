// Tracker accuracy on POV-Ray footage (tests/footage): every lighting of the issue at A_r 3.9 and
// front-lit touching spheres at A_r 2.0, 2.1, 2.3, each tracked by every method, against the
// issue's targets (tests/footage/track_accuracy.h). docs/BENCHMARKS.md, "Tracker on POV-Ray
// footage".
//   bench_tracking_footage [frames] [subframes] [cache_dir] [methods]
// Defaults: 40 frames of the hop motion, 6 exposure slices (300 us at 2000 frames/s), cache
// folder bench_footage_cache (footage is reused while its scenes are unchanged), methods
// "auto,centroid,template" (comma-separated `--method` names of tracking/refiner.h; auto is the
// default a user gets). The tracker is given the scale, as with `--m-per-px`.
// Prints the POV-Ray CPU time per frame of each footage (every slice, antialiased), then one
// row per footage and method, and the machine (cores, load average).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/footage/povray_footage.h"
#include "tests/footage/track_accuracy.h"

using namespace dimer::footage;

namespace {

struct Case {
  std::string name;
  Lighting lighting;
  double aspect_ratio;
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

}  // namespace

int main(int argc, char** argv) {
  const size_t frames = argc > 1 ? size_t(std::atol(argv[1])) : 40;
  const int slices = argc > 2 ? std::atoi(argv[2]) : 6;
  const std::string cache = argc > 3 ? argv[3] : "bench_footage_cache";
  const std::vector<std::string> methods =
      SplitList(argc > 4 ? argv[4] : "auto,centroid,template");
  std::vector<Case> cases;
  for (Lighting l : AllLightings()) cases.push_back({ToString(l), l, 3.9});
  for (double ar : {2.0, 2.1, 2.3}) {
    char name[40];
    std::snprintf(name, sizeof name, "front_point A_r %.1f", ar);
    cases.push_back({name, Lighting::kFrontPoint, ar});
  }
  std::filesystem::create_directories(cache);
  std::printf("POV-Ray footage: %zu frames per case, 640x320, 0.2 mm/px, 300 us exposure in %d "
              "slices, PSF 0.5 px, noise 2 grey levels, 8 bit; %u cores, load average %.1f at "
              "start\n\n",
              frames, slices, std::thread::hardware_concurrency(), LoadAverage());
  // The harness's table with two columns in front.
  const std::string header = AccuracyHeader();
  const size_t line2 = header.find('\n') + 1;
  std::printf("| footage | POV-Ray CPU s/frame %s|---|---%s", header.substr(0, line2).c_str(),
              header.substr(line2).c_str());
  for (const Case& c : cases) {
    FootageOptions o = FootageOptions::For(c.lighting);
    o.shape.aspect_ratio = c.aspect_ratio;
    o.subframes = slices;
    o.reuse = true;
    std::string dir = cache + "/" + c.name;
    for (char& ch : dir) {
      if (ch == ' ') ch = '_';
    }
    try {
      const FootageResult r = WriteFootage(HopMotion(o.shape, frames, o.fps), o, dir);
      const double cpu = r.reused ? RecordedCpuPerFrame(dir) : r.povray_cpu_seconds_per_frame;
      for (const std::string& m : methods) {
        const TrackAccuracy a = MeasureTrackAccuracy(dir, m);
        std::printf("| %s | %.2f %s", c.name.c_str(), cpu, AccuracyRow(a).c_str());
        std::fflush(stdout);
      }
    } catch (const std::exception& e) {
      std::printf("| %s | | error: %s |\n", c.name.c_str(), e.what());
    }
  }
  std::printf("\nload average at the end %.1f\n", LoadAverage());
  return 0;
}
