#include "tracking/dimer_length_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/stderr_capture.h"
#include "tracking/frame_range.h"

namespace dimer::tracking {

double MedianDimerLength(const std::vector<FrameTrack>& frames, size_t* used) {
  std::vector<double> len;
  for (const FrameTrack& f : frames) {
    if (f.found[0] && f.found[1]) len.push_back((f.centre[1] - f.centre[0]).norm());
  }
  if (used) *used = len.size();
  if (len.size() < kLengthScaleMinFrames) return std::numeric_limits<double>::quiet_NaN();
  // The lower median for an even count: the same value whatever the frames' order.
  auto mid = len.begin() + std::ptrdiff_t((len.size() - 1) / 2);
  std::nth_element(len.begin(), mid, len.end());
  return *mid;
}

double RadiusFromDimerLength(double length_px, double ar) {
  return length_px / (2.0 * (ar - 1.0));
}

double ScaleFromDimerLength(double length_px, double ar, double diameter_m) {
  return (ar - 1.0) * diameter_m / length_px;
}

LengthScale IterateDimerLengthScale(const std::function<double(double radius_px)>& length_of,
                                    double ar) {
  LengthScale s;
  double radius = std::numeric_limits<double>::quiet_NaN();  // the first pass measures it
  for (int pass = 0; pass < kLengthScaleMaxPasses; ++pass) {
    LengthScalePass p;
    p.radius_px_used = radius;
    p.length_px = length_of(radius);
    s.passes.push_back(p);
    if (!(std::isfinite(p.length_px) && p.length_px > 0)) {
      s.ok = false;  // a radius that loses the spheres is no calibration
      char r[32];
      std::snprintf(r, sizeof r, "%.3f", radius);
      s.failure = pass == 0 ? "too few frames show both spheres"
                            : std::string("too few frames show both spheres once tracked with a "
                                          "radius of ") + r + " px";
      return s;
    }
    const double next = RadiusFromDimerLength(p.length_px, ar);
    s.ok = true;
    s.radius_px = next;
    if (std::isfinite(radius) && std::abs(next - radius) < kLengthScaleTolPx) {
      s.converged = true;
      return s;
    }
    radius = next;
  }
  return s;
}

LengthScale TrackedDimerLengthScale(const TrackArgs& args, const SequenceOptions& seq) {
  const FrameRange film = ParseFrameRange(args.frames);
  FrameRange first = film;
  first.end = film.first + kLengthScaleFrames;
  if (film.end) first.end = std::min(*film.end, *first.end);
  auto length_of = [&](double radius_px) {
    SequenceOptions o = seq;
    o.contact_radius_px = radius_px;
    // The plate edge's own scale over the dimer plane's, that radius's (measured: fitted).
    o.plate_motion_scale = std::isnan(args.plate_m_per_px) || std::isnan(radius_px)
                               ? std::numeric_limits<double>::quiet_NaN()
                               : args.plate_m_per_px / (0.5 * args.diameter / radius_px);
    auto source = SelectFrames(FrameSource::Open(args.input), first, args.input);
    SequenceResult r;
    {
      StderrCapture drop([](const std::string&) {});
      r = TrackSequence(*source, o);
    }
    if (!r.complete) throw Interrupted();
    return MedianDimerLength(r.frames);
  };
  return IterateDimerLengthScale(length_of, args.ar);
}

}  // namespace dimer::tracking
