#include "tracking/dimer_presence.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/format.h"
#include "common/median.h"

namespace dimer::tracking {

DimerPresence MeasureDimerPresence(const SequenceResult& r) {
  DimerPresence p;
  p.frames = r.frames.size();
  std::vector<double> lengths, radii;
  for (const FrameTrack& f : r.frames) {
    if (f.found[0] && f.found[1]) {
      lengths.push_back((f.centre[1] - f.centre[0]).norm());
      radii.insert(radii.end(), f.radius_px.begin(), f.radius_px.end());
    } else if (f.found[0] || f.found[1]) {
      ++p.one;
    }
  }
  p.both = lengths.size();
  if (lengths.empty()) return p;
  p.length_px = MedianOf(lengths);
  const double tolerance =
      std::max(kDimerLengthTolerancePx, kDimerLengthToleranceFraction * p.length_px);
  p.dimer = size_t(std::count_if(lengths.begin(), lengths.end(), [&](double d) {
    return std::abs(d - p.length_px) <= tolerance;
  }));
  // The left sphere alone has its partner to the right, the right one to the left; its place
  // is cut or out where its centre is within a radius of the edge (pixel centres), as in
  // FrameFollower::OtherCanBeOutOfView, whose circle of tilts reaches furthest along the row.
  const double median_radius = FiniteMedian(radii);
  const double radius = median_radius > 0 ? median_radius : 0.0;
  for (const FrameTrack& f : r.frames) {
    if (f.found[0] == f.found[1]) continue;
    p.leaving += f.found[0] ? f.centre[0].x() + p.length_px > r.width - 0.5 - radius
                            : f.centre[1].x() - p.length_px < radius - 0.5;
  }
  return p;
}

std::string NoDimerMessage(const DimerPresence& p, bool scale_given) {
  const char* without_scale =
      scale_given ? ""
                  : "; without --m-per-px the spheres are looked for at the first frame's "
                    "silhouette size, which can miss dim or front-lit steel: give the scale if "
                    "the film shows the dimer";
  return Format("no dimer: two spheres a constant distance apart in %zu of %zu frames (needed: "
                "half of the %zu that show anything, and %zu at least); found two objects in "
                "%zu (any distance), one in %zu (%zu with the other's place out of view), none "
                "in %zu; track the frames that show the dimer (--frames)%s",
                p.dimer, p.frames, p.shown(), p.needed(), p.both, p.one, p.leaving,
                p.frames - p.shown(), without_scale);
}

std::string DimerOutOfViewNote(const DimerPresence& p) {
  if (!p.seen() || 2 * p.dimer >= p.frames) return "";
  return Format("the dimer is in view in %zu of %zu frames (one sphere, the other out of view, "
                "in %zu; nothing in view in %zu): tracked where it is, found = 0 elsewhere",
                p.dimer, p.frames, p.leaving, p.frames - p.shown());
}

}  // namespace dimer::tracking
