// `dimerlab track FRAMES -o track.h5`: parses into TrackArgs and calls RunTrack.
#include <memory>

#include "app/commands.h"
#include "app/usage.h"
#include "app/track_messages.h"
#include "tracking/run_track.h"

namespace dimer::app {
namespace {

void AddTrackOptions(CLI::App* sub, tracking::TrackArgs* a) {
  sub->add_option("input", a->input, "folder of frames, multi-page TIFF, .cine or video")
      ->required();
  sub->add_option("--frames", a->frames, "frames A..B-1 only (A:B, A: or :B; 0-based)");
  sub->add_option("-o,--output", a->output, "track file to write (HDF5)")->required();
  sub->add_flag("--force", a->force, "replace an existing output file");
  sub->add_option("--fps", a->fps, "frame rate, frames/s [a .cine's time stamps or header, else 2000]")->check(FiniteNumber());
  sub->add_option("--m-per-px", a->m_per_px, "metres per pixel [from --diameter]")->check(FiniteNumber());
  sub->add_option("--diameter", a->diameter, "sphere diameter, m (calibrates m/px)")->check(FiniteNumber())
      ->capture_default_str();
  sub->add_option("--ar", a->ar,
                  "the dimer's aspect ratio, length / diameter: m/px from its centre distance "
                  "(A_r - 1) x diameter, tracked [not given: from the spheres' size]; with "
                  "--m-per-px, a check")->check(FiniteNumber());
  sub->add_option("--row0", a->row0, "row of z = 0, px [median plate row]")->check(FiniteNumber());
  sub->add_option("--plate-m-per-px", a->plate_m_per_px,
                  "metres per pixel at the plate edge seen (nearer or further than the dimer); "
                  "needs --m-per-px or --ar [the dimer plane's]")->check(FiniteNumber());
  sub->add_option("--lens", a->lens,
                  "the lens's calibration (OpenCV YAML/XML: camera_matrix, "
                  "distortion_coefficients): frames undistorted before tracking [as recorded]");
  // Names typed where they are read: a wrong one is a one-line error naming the option.
  sub->add_option_function<std::string>(
         "--method", [a](const std::string& s) { a->method = tracking::ParseMethod(s, "--method"); },
         "auto | centroid | discfit | template")
      ->default_str(tracking::ToString(a->method));
  sub->add_option_function<std::string>(
         "--polarity", [a](const std::string& s) { a->polarity = tracking::ParsePolarity(s); },
         "auto | bright | dark")
      ->default_str(tracking::ToString(a->polarity));
  sub->add_option("--radius-px", a->sequence.follower.radius_px, "sphere radius, px [measured]")->check(FiniteNumber());
  // Given, the blur is the user's; not given, an over-exposed plate's frames fit it.
  sub->add_option("--psf-sigma", a->sequence.follower.psf_sigma_px,
                  "camera blur, Gaussian sigma px (places a clipped plate edge) [fitted]")->check(FiniteNumber())
      ->each([a](const std::string&) { a->sequence.follower.fit_psf_sigma = false; });
  sub->add_option("--bits", a->sequence.camera_bits,
                  "the camera's bits per pixel in 16-bit frames (8-16; 16: as stored) "
                  "[a .cine's RealBPP, else as stored]");
  sub->add_option("--threads", a->sequence.threads, "worker threads (0: all cores)");
  sub->add_option("--chunk-frames", a->sequence.chunk_frames, "frames per parallel chunk")
      ->capture_default_str();
  sub->add_flag("-q,--quiet", a->quiet, "no progress on stderr");
}

}  // namespace

void RegisterTrack(CLI::App& app) {
  auto args = std::make_shared<tracking::TrackArgs>();
  CLI::App* sub = app.add_subcommand(
      "track", "sub-pixel sphere centres and plate edge in every frame, to a track file");
  AddTrackOptions(sub, args.get());
  sub->callback([args]() {
    args->on_diagnostic = PrintTrackDiagnostics(args->quiet);
    args->on_summary = PrintSummaryLine;
    tracking::RunTrack(*args);
  });
}

}  // namespace dimer::app
