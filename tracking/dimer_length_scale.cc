#include "tracking/dimer_length_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/format.h"
#include "common/stderr_capture.h"
#include "tracking/io/frame_range.h"
#include "common/median.h"

namespace dimer::tracking {

double MedianDimerLength(const std::vector<FrameTrack>& frames, size_t* used) {
  std::vector<double> len;
  for (const FrameTrack& f : frames) {
    if (f.whole(0) && f.whole(1)) len.push_back((f.centre[1] - f.centre[0]).norm());
  }
  if (used) *used = len.size();
  return len.size() < kLengthScaleMinFrames ? std::numeric_limits<double>::quiet_NaN()
                                            : MedianOf(len);
}

namespace {

std::string FormatPx(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f px", v);
  return b;
}

// The radius a pass without a scale measured, where it can check --ar: the outline's (the two
// spheres' agreeing), or the silhouette methods' where they were chosen (clean silhouettes:
// 0.04-0.14 % on the POV-Ray backlit and bright-background films). NaN otherwise: the
// silhouette methods' radius beside a template, 20-65 % short under a soft box, a one-sided lamp
// or on the under-exposed film.
double CheckRadius(const SequenceResult& r) {
  if (r.method == Method::kTemplate) {
    return r.radius_source == "outline" && r.appearance[0].valid()
               ? r.appearance[0].radius_px
               : std::numeric_limits<double>::quiet_NaN();
  }
  std::vector<double> radii;
  for (const FrameTrack& f : r.frames) {
    for (int k = 0; k < 2; ++k) {
      if (f.whole(k) && f.radius_px[k] > 0) radii.push_back(f.radius_px[k]);
    }
  }
  return MedianOf(radii);
}

}  // namespace

double RadiusFromDimerLength(double length_px, double ar) {
  return length_px / (2.0 * (ar - 1.0));
}

double ScaleFromDimerLength(double length_px, double ar, double diameter_m) {
  return (ar - 1.0) * diameter_m / length_px;
}

std::vector<double> DimerLengthRadiusGuesses(int width, double ar) {
  std::vector<double> out;
  for (double r = kGuessMinRadiusPx; 2.0 * ar * r <= double(width); r *= kGuessRatio) {
    out.push_back(r);
  }
  return out;
}

LengthScale IterateDimerLengthScale(const std::function<double(double radius_px)>& length_of,
                                    double ar,
                                    const std::function<std::vector<double>()>& guesses) {
  LengthScale s;
  auto measure = [&](double radius) {
    LengthScalePass p;
    p.radius_px_used = radius;
    p.length_px = length_of(radius);
    s.passes.push_back(p);
    return std::isfinite(p.length_px) && p.length_px > 0;
  };
  // From a start (the radius measured as without a scale, then each guess): passes with the
  // radius the last length implies. True once settled or after the last pass; false where a
  // pass loses the spheres (a guess's length can be 13 % off, and the radius it implies then
  // too far to find them: the POV-Ray camera turned 8 degrees).
  std::string lost;
  auto settle = [&](double start) {
    if (!measure(start)) return false;
    double radius = RadiusFromDimerLength(s.passes.back().length_px, ar);
    for (int pass = 1; pass < kLengthScaleMaxPasses; ++pass) {
      if (!measure(radius)) {
        char r[32];
        std::snprintf(r, sizeof r, "%.3f", radius);
        lost = std::string("too few frames show both spheres once tracked with a radius of ") + r +
               " px";
        return false;
      }
      const double next = RadiusFromDimerLength(s.passes.back().length_px, ar);
      const bool settled = std::abs(next - radius) < kLengthScaleTolPx;
      radius = next;
      if (settled) {
        s.converged = true;
        break;
      }
    }
    s.radius_px = radius;
    return true;
  };
  size_t starts = 1;
  s.ok = settle(std::numeric_limits<double>::quiet_NaN());
  if (!s.ok && guesses) {
    for (double g : guesses()) {
      ++starts;
      if ((s.ok = settle(g))) break;
    }
  }
  if (!s.ok) {
    s.failure = starts > 1 ? "too few frames show both spheres, from the radius measured or any of " +
                                 std::to_string(starts - 1) +
                                 " guessed and the radii their lengths implied"
                : !lost.empty() ? lost
                                : "too few frames show both spheres";
  }
  return s;
}

LengthScale TrackedDimerLengthScale(const LengthScaleFilm& args, const SequenceOptions& seq,
                                    Diagnostics* diag) {
  const FrameRange film = ParseFrameRange(args.frames);
  FrameRange first = film;
  first.end = film.first + kLengthScaleFrames;
  if (film.end) first.end = std::min(*film.end, *first.end);
  int width = 0;  // the frames', from the first pass: bounds the guesses
  size_t readable = 0;  // frames a pass could read
  double outline = std::numeric_limits<double>::quiet_NaN();  // the first pass's outline radius
  size_t passes = 0;
  auto length_of = [&](double radius_px) {
    SequenceOptions o = seq;
    o.contact_radius_px = radius_px;
    // The plate edge's own scale over the dimer plane's, that radius's (measured: fitted).
    o.plate_motion_scale = !args.plate_m_per_px || std::isnan(radius_px)
                               ? std::numeric_limits<double>::quiet_NaN()
                               : *args.plate_m_per_px / (0.5 * args.diameter / radius_px);
    auto source = SelectFrames(OpenFrameSource(args.input), first, args.input);
    SequenceResult r;
    {
      StderrCapture drop([](const std::string&) {});
      r = TrackSequence(*source, o);
    }
    if (!r.complete) throw Interrupted();
    if (r.width > 0) width = r.width;
    if (std::isnan(radius_px)) outline = CheckRadius(r);
    readable = std::max(readable, r.frames.size());
    size_t both = 0;
    const double length = MedianDimerLength(r.frames, &both);
    diag->Note("length_scale_pass",
               Format("--ar pass %zu, radius %s: both spheres in %zu of %zu frames, length %.3f px",
                      ++passes, std::isnan(radius_px) ? "measured" : FormatPx(radius_px).c_str(),
                      both, r.frames.size(), length));
    return length;
  };
  // Guesses cannot help a film too short for a length.
  LengthScale s = IterateDimerLengthScale(length_of, args.ar, [&] {
    return readable < kLengthScaleMinFrames ? std::vector<double>{}
                                            : DimerLengthRadiusGuesses(width, args.ar);
  });
  s.outline_radius_px = outline;
  if (!s.ok && readable < kLengthScaleMinFrames) {
    s.failure = std::to_string(readable) + " readable frames, and a length needs " +
                std::to_string(kLengthScaleMinFrames) + " showing both spheres";
  }
  return s;
}

}  // namespace dimer::tracking
