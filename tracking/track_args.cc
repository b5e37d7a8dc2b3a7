#include "tracking/track_args.h"

#include <cmath>

#include "common/error.h"
#include "tracking/dimer_length_scale.h"
#include "tracking/io/frame_range.h"

namespace dimer::tracking {

std::string ToString(Polarity p) {
  return p == Polarity::kBright ? "bright" : p == Polarity::kDark ? "dark" : "auto";
}

Polarity ParsePolarity(const std::string& name, const std::string& option) {
  for (Polarity p : {Polarity::kAuto, Polarity::kBright, Polarity::kDark}) {
    if (name == ToString(p)) return p;
  }
  throw UsageError(option + " '" + name + "': expected auto, bright or dark");
}

int Sign(Polarity p) { return p == Polarity::kBright ? 1 : p == Polarity::kDark ? -1 : 0; }

void TrackArgs::Check() const {
  std::string bad;
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) bad += (bad.empty() ? "" : "; ") + what;
  };
  need(!input.empty(), "input: a folder of frames, a TIFF, a .cine or a video is required");
  need(!output.empty(), "-o: the output track file is required");
  need(!fps || (*fps >= kMinTrackFps && *fps <= kMaxTrackFps),
       "--fps must be 1 .. 1e7 frames/s");
  try {
    ParseFrameRange(frames);
  } catch (const InputError& e) {
    need(false, e.what());
  }
  need(!m_per_px || (*m_per_px > 0 && std::isfinite(*m_per_px)), "--m-per-px must be > 0 m/px");
  need(!plate_m_per_px || (*plate_m_per_px > 0 && std::isfinite(*plate_m_per_px)),
       "--plate-m-per-px must be > 0 m/px");
  // The ratio of the two scales is what moves the plate rows, and it is needed while tracking
  // (the template's plate-contact offsets read them), before a scale from --diameter exists.
  need(!plate_m_per_px || m_per_px || ar,
       "--plate-m-per-px needs --m-per-px or --ar (the dimer plane's scale)");
  need(diameter > 0 && std::isfinite(diameter), "--diameter must be > 0 m");
  need(!ar || (*ar >= kMinAspectRatio && std::isfinite(*ar)),
       "--ar must be >= 2 (the dimer's length over a sphere's diameter; 2: spheres touching)");
  if (!bad.empty()) throw UsageError(bad);
  sequence.Check();
}

}  // namespace dimer::tracking
