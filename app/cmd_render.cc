// `dimerlab render sim.h5 -o FRAMES_DIR`: parses into RenderArgs and calls RunRender.
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.h"
#include "app/track_messages.h"
#include "render/render.h"

namespace dimer::app {
namespace {

struct RenderCli {
  tracking::RenderArgs args;
  std::string lighting = "reflect";
};

void AddRenderOptions(CLI::App* sub, RenderCli* cli) {
  tracking::RenderArgs& a = cli->args;
  sub->add_option("input", a.input, "trajectory file (sim.h5)")->required();
  sub->add_option("-o,--output", a.output, "folder to create for the frames")->required();
  sub->add_flag("--force", a.force, "replace an existing output folder");
  sub->add_option("--m-per-px", a.m_per_px, "metres per pixel")->capture_default_str();
  sub->add_option("--width", a.image.width, "frame width, px")->capture_default_str();
  sub->add_option("--height", a.image.height, "frame height, px")->capture_default_str();
  sub->add_option("--row0", a.row0, "row of z = 0 (plate mean surface), px [0.78 height]");
  sub->add_option("--col-offset", a.col_offset, "column of x = 0, px [centres the trajectory]");
  sub->add_option("--lighting", cli->lighting, "reflect | backlit | disc")->capture_default_str();
  sub->add_option("--noise", a.image.noise, "Gaussian sensor noise, grey levels (8-bit scale)")
      ->capture_default_str();
  sub->add_option("--gradient", a.image.gradient, "illumination change left to right, fraction")
      ->capture_default_str();
  sub->add_option("--exposure", a.exposure, "shutter time, fraction of the frame interval")
      ->capture_default_str();
  sub->add_option("--blur-samples", a.blur_samples, "instants averaged per exposure")
      ->capture_default_str();
  sub->add_option("--bit-depth", a.image.bit_depth, "8 or 16")->capture_default_str();
  sub->add_option_function<std::string>(
         "--format", [&a](const std::string& s) { a.format = tracking::ParseFrameFormat(s); },
         "png | tiff | cine (one frames.cine)")
      ->default_str(tracking::ToString(a.format));
  sub->add_option("--supersample", a.image.supersample, "samples per pixel side (rod, mirror)")
      ->capture_default_str();
  sub->add_option("--seed", a.image.seed, "noise seed")->capture_default_str();
  sub->add_option("--diameter", a.diameter, "sphere diameter, m [file attribute 'diameter']");
  sub->add_option("--rod-diameter", a.rod_diameter, "rod diameter, m (0: none)")
      ->capture_default_str();
  sub->add_option("--frames", a.max_frames, "render only the first N samples (0: all)");
  sub->add_option("--threads", a.threads, "worker threads (0: all cores)");
  sub->add_flag("-q,--quiet", a.quiet, "no progress on stderr");
}

}  // namespace

void RegisterRender(CLI::App& app) {
  auto cli = std::make_shared<RenderCli>();
  CLI::App* sub = app.add_subcommand(
      "render", "synthetic frames of a trajectory, with truth.csv (exact pixel centres)");
  AddRenderOptions(sub, cli.get());
  sub->callback([cli]() {
    cli->args.image.lighting = tracking::ParseLighting(cli->lighting);
    cli->args.on_note = [](const std::string& s) { std::fprintf(stderr, "render: %s\n", s.c_str()); };
    cli->args.on_summary = PrintSummaryLine;
    tracking::RunRender(cli->args);
  });
}

}  // namespace dimer::app
