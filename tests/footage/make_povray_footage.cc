// make_povray_footage: renders a folder of POV-Ray test footage with truth.csv (povray_footage.h).
//   make_povray_footage --lighting front_point --frames 40 --ar 3.9 -o DIR
// Motion: the built-in hop motion (default), a trajectory file (--sim FILE.h5, kind sim or
// track) or a pose list (--poses FILE.csv, header t,x,z,theta,plate_z). Run with --help for
// every option. Test and bench infrastructure, not part of the `dimerlab` CLI.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>

#include "common/error.h"
#include "common/h5_file.h"
#include "common/interrupt.h"
#include "common/trajectory_io.h"
#include "tests/footage/povray_footage.h"

using namespace dimer;
using namespace dimer::footage;

namespace {

const char* kUsage =
    "usage: make_povray_footage [options] -o DIR\n"
    "  --lighting NAME     front_point (default), front_softbox, bright_background, matte,\n"
    "                      backlit, one_sided_gain_ramp, underexposed, overexposed, mirror_plate,\n"
    "                      ring_light, cluttered_backdrop\n"
    "  --frames N          frames of the hop motion, or the first N samples of --sim (40)\n"
    "  --sim FILE.h5       take the motion from a trajectory file (sim or track)\n"
    "  --poses FILE.csv    take the motion from a pose list (t,x,z,theta,plate_z; SI units)\n"
    "  --ar A              aspect ratio A_r, centre distance (A_r - 1) d (3.9)\n"
    "  --diameter M        sphere diameter, m (9.5e-3; with --sim: the file's `diameter`)\n"
    "  --rod-diameter M    rod diameter, m (1.5e-3; 0: no rod)\n"
    "  --drift-speed V     hop motion: centre-of-mass speed, m/s (0.05)\n"
    "  --fps F             frame rate, frames/s (2000; with --sim: the file's sample times)\n"
    "  --exposure-us T     exposure, us (300; 0: sharp)\n"
    "  --subframes K       exposure slices averaged per frame (6)\n"
    "  --psf S             Gaussian PSF sigma, px (0.5)\n"
    "  --noise S           read noise sigma, grey levels of the 8-bit scale (2)\n"
    "  --bit-depth B       8 or 16 (8)\n"
    "  --seed N            noise seed (1)\n"
    "  --flicker A         lamps on the mains: each frame's light times 1 + A sin(2 pi F t) (0)\n"
    "  --flicker-hz F      their flicker frequency, Hz (100: 50 Hz mains)\n"
    "  --lens-k1 K         pincushion distortion of the lens (OpenCV's k1, >= 0; 0: a pinhole);\n"
    "                      the folder gets its calibration as lens.yml\n"
    "  --off-axis M        the dimer's mean x this far right of the optical axis, m (0)\n"
    "  --width W --height H  frame size, px (640 x 320)\n"
    "  --m-per-px S        scale at the dimer plane, m/px (2e-4)\n"
    "  --distance M        pinhole to dimer plane, m (0.7)\n"
    "  --elevation M       pinhole height above the plate's mean top, m (0: level;\n"
    "                      mirror_plate 0.005)\n"
    "  --horizon-row R     output row of the optical axis (249.5; mirror_plate 224.5)\n"
    "  --roll-deg A        camera turned about its axis, deg (0; the plate edge descends to\n"
    "                      the right by tan A px per px; a --sim of a tilted plate turns it\n"
    "                      by minus the tilt more: a level camera's view of that plate)\n"
    "  --plate-depth M     plate extent toward the camera, m (0.04; mirror_plate 0.2)\n"
    "  --aa-depth D        POV-Ray antialiasing depth, 0 (none) .. 7 (4)\n"
    "  --jobs N            POV-Ray processes at once (0: three per core)\n"
    "  --povray PATH       the POV-Ray program (povray)\n"
    "  --reuse             keep DIR if it was made from the same scenes (a cache)\n"
    "  --force             replace an existing DIR\n"
    "  -q                  no progress on stderr\n";

double ToDouble(const std::string& opt, const std::string& v) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(d)) {
    throw UsageError(opt + " '" + v + "': expected a number");
  }
  return d;
}

long ToInt(const std::string& opt, const std::string& v) {
  const double d = ToDouble(opt, v);
  if (d != std::floor(d) || std::abs(d) > 1e15) {
    throw UsageError(opt + " '" + v + "': expected a whole number");
  }
  return long(d);
}

int Run(int argc, char** argv) {
  // The lighting first: it sets the defaults of the camera and scene that other options change.
  Lighting lighting = Lighting::kFrontPoint;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--lighting") lighting = ParseLighting(argv[i + 1]);
  }
  FootageOptions o = FootageOptions::For(lighting);
  std::string output, sim, poses;
  long frames = 40;
  double diameter = std::nan("");
  HopOptions hop;
  std::map<std::string, std::function<void(const std::string&)>> value_opts = {
      {"--lighting", [&](const std::string& v) { o.lighting = ParseLighting(v); }},
      {"--frames", [&](const std::string& v) { frames = ToInt("--frames", v); }},
      {"--sim", [&](const std::string& v) { sim = v; }},
      {"--poses", [&](const std::string& v) { poses = v; }},
      {"--ar", [&](const std::string& v) { o.shape.aspect_ratio = ToDouble("--ar", v); }},
      {"--diameter", [&](const std::string& v) { diameter = ToDouble("--diameter", v); }},
      {"--rod-diameter",
       [&](const std::string& v) { o.shape.rod_diameter = ToDouble("--rod-diameter", v); }},
      {"--drift-speed",
       [&](const std::string& v) { hop.drift_speed = ToDouble("--drift-speed", v); }},
      {"--fps", [&](const std::string& v) { o.fps = ToDouble("--fps", v); }},
      {"--exposure-us",
       [&](const std::string& v) { o.exposure_s = 1e-6 * ToDouble("--exposure-us", v); }},
      {"--subframes", [&](const std::string& v) { o.subframes = int(ToInt("--subframes", v)); }},
      {"--psf", [&](const std::string& v) { o.psf_sigma_px = ToDouble("--psf", v); }},
      {"--noise", [&](const std::string& v) { o.noise = ToDouble("--noise", v); }},
      {"--bit-depth", [&](const std::string& v) { o.bit_depth = int(ToInt("--bit-depth", v)); }},
      {"--seed", [&](const std::string& v) { o.seed = uint64_t(ToInt("--seed", v)); }},
      {"--flicker", [&](const std::string& v) { o.flicker = ToDouble("--flicker", v); }},
      {"--flicker-hz", [&](const std::string& v) { o.flicker_hz = ToDouble("--flicker-hz", v); }},
      {"--lens-k1", [&](const std::string& v) { o.lens_k1 = ToDouble("--lens-k1", v); }},
      {"--off-axis", [&](const std::string& v) { o.dimer_off_axis = ToDouble("--off-axis", v); }},
      {"--width", [&](const std::string& v) { o.camera.width = int(ToInt("--width", v)); }},
      {"--height", [&](const std::string& v) { o.camera.height = int(ToInt("--height", v)); }},
      {"--m-per-px", [&](const std::string& v) { o.camera.m_per_px = ToDouble("--m-per-px", v); }},
      {"--distance", [&](const std::string& v) { o.camera.distance = ToDouble("--distance", v); }},
      {"--elevation",
       [&](const std::string& v) { o.camera.elevation = ToDouble("--elevation", v); }},
      {"--plate-depth",
       [&](const std::string& v) { o.scene.plate_depth = ToDouble("--plate-depth", v); }},
      {"--horizon-row",
       [&](const std::string& v) { o.camera.horizon_row = ToDouble("--horizon-row", v); }},
      {"--roll-deg", [&](const std::string& v) { o.camera.roll_deg = ToDouble("--roll-deg", v); }},
      {"--aa-depth", [&](const std::string& v) { o.aa_depth = int(ToInt("--aa-depth", v)); }},
      {"--jobs", [&](const std::string& v) { o.jobs = int(ToInt("--jobs", v)); }},
      {"--povray", [&](const std::string& v) { o.povray = v; }},
      {"-o", [&](const std::string& v) { output = v; }},
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--reuse") {
      o.reuse = true;
    } else if (a == "--force") {
      o.force = true;
    } else if (a == "-q" || a == "--quiet") {
      o.quiet = true;
    } else if (value_opts.count(a)) {
      if (i + 1 >= argc) throw UsageError(a + ": missing value");
      value_opts[a](argv[++i]);
    } else {
      throw UsageError("unknown option '" + a + "' (--help lists them)");
    }
  }
  if (output.empty()) throw UsageError("-o DIR: the output folder is required");
  if (!sim.empty() && !poses.empty()) throw UsageError("--sim and --poses exclude each other");
  if (frames < 1 && sim.empty()) throw UsageError("--frames must be >= 1");
  Motion motion;
  if (!sim.empty()) {
    H5Reader reader(sim);
    // A tilted plate's simulation: filmed by a level camera (footage_motion.h).
    const double tilt_deg =
        FileKind(reader) == "sim" ? reader.AttrDouble("/", "tilt_deg").value_or(0.0) : 0.0;
    const Trajectory traj = ReadTrajectory(reader);
    if (tilt_deg != 0) {
      std::fprintf(stderr, "make_povray_footage: %s: plate tilted %g deg: built in the plate's frame, "
                   "camera roll %g deg\n", sim.c_str(), tilt_deg, o.camera.roll_deg - tilt_deg);
    }
    if (std::isnan(diameter)) diameter = reader.AttrDouble("/", "diameter").value_or(std::nan(""));
    if (std::isnan(diameter)) throw InputError(sim + ": no root attribute 'diameter'; pass --diameter");
    if (traj.size() >= 2) o.fps = 1.0 / (traj.t[1] - traj.t[0]);
    o.shape.diameter = diameter;
    motion = TiltedTrajectoryMotion(traj, tilt_deg, size_t(std::max(0L, frames)), sim, &o.camera.roll_deg);
  } else {
    if (!std::isnan(diameter)) o.shape.diameter = diameter;
    if (!poses.empty()) {
      motion = PoseMotion(o.shape, ReadPoseCsv(poses));
    } else {
      o.Check();
      motion = HopMotion(o.shape, size_t(frames), o.fps, hop);
    }
  }
  const FootageResult r = WriteFootage(motion, o, output);
  if (r.reused) {
    std::printf("%s: up to date (%zu frames, scene hash %s)\n", output.c_str(), r.frames,
                r.scene_hash.c_str());
  } else {
    std::printf("%s: %zu frames %dx%d, %d-bit, %s; POV-Ray %.3g CPU s/frame (%d slices); truth.csv, "
                "footage.json; %.3g s\n",
                output.c_str(), r.frames, o.camera.width, o.camera.height, o.bit_depth,
                ToString(o.lighting).c_str(), r.povray_cpu_seconds_per_frame,
                o.exposure_s > 0 ? o.subframes : 1, r.wall_seconds);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  InstallInterruptHandler();
  try {
    return Run(argc, argv);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "make_povray_footage: error: %s\n", e.what());
    return 2;
  } catch (const Interrupted&) {
    std::fprintf(stderr, "make_povray_footage: interrupted\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_povray_footage: error: %s\n", e.what());
    return 1;
  }
}
