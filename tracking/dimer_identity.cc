#include "tracking/dimer_identity.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "common/median.h"

namespace dimer::tracking {
namespace {

bool Both(const FrameTrack& f) { return f.found[0] && f.found[1]; }

double Distance(const FrameTrack& f) { return (f.centre[1] - f.centre[0]).norm(); }

// The rigid dimer as last seen: where each end is (the unseen one carried with the seen one) and
// the rod from sphere 0 to sphere 1.
struct RigidDimer {
  std::array<Eigen::Vector2d, 2> end;
  Eigen::Vector2d rod;
};

class Namer {
 public:
  Namer(double length, const RigidDimer& start) : length_(length), dimer_(start) {}

  // Names the spheres of `f` against the dimer so far, then moves the dimer to them.
  void Name(FrameTrack* f, DimerNames* out) {
    if (Both(*f)) {
      NamePair(f, out);
    } else if (f->found[0] || f->found[1]) {
      NameLone(f, out);
    }
  }

 private:
  bool IsDimer(const FrameTrack& f) const {
    return std::abs(Distance(f) - length_) <= kPairLengthFraction * length_;
  }

  // A pair at the dimer's length: sphere 1 is the end the rod points to (the rod turns far less
  // than a quarter turn between frames). Any other pair: the assignment nearer the ends.
  void NamePair(FrameTrack* f, DimerNames* out) {
    bool swap;
    if (IsDimer(*f)) {
      swap = (f->centre[1] - f->centre[0]).dot(dimer_.rod) < 0;
    } else {
      const double keep =
          (f->centre[0] - dimer_.end[0]).norm() + (f->centre[1] - dimer_.end[1]).norm();
      const double cross =
          (f->centre[0] - dimer_.end[1]).norm() + (f->centre[1] - dimer_.end[0]).norm();
      swap = cross < keep;
    }
    if (swap) {
      f->SwapSpheres();
      ++out->renamed;
    }
    if (IsDimer(*f)) {
      dimer_.end = f->centre;
      dimer_.rod = f->centre[1] - f->centre[0];
    }
  }

  void NameLone(FrameTrack* f, DimerNames* out) {
    const int seen = f->found[0] ? 0 : 1;
    const Eigen::Vector2d c = f->centre[seen];
    const double d0 = (c - dimer_.end[0]).norm(), d1 = (c - dimer_.end[1]).norm();
    const int name = d0 <= d1 ? 0 : 1;
    if (std::abs(d0 - d1) < kLoneNameMarginFraction * length_) {
      f->found[seen] = false;
      f->centre[seen] = Eigen::Vector2d(0, 0);
      f->score[seen] = std::numeric_limits<double>::quiet_NaN();
      ++out->unnamed;
      return;
    }
    if (name != seen) {
      f->SwapSpheres();
      ++out->renamed;
    }
    dimer_.end[name] = c;
    dimer_.end[1 - name] = name == 0 ? Eigen::Vector2d(c + dimer_.rod) : Eigen::Vector2d(c - dimer_.rod);
  }

  double length_;
  RigidDimer dimer_;
};

}  // namespace

DimerNames NameSpheresByTheDimer(std::vector<FrameTrack>* frames) {
  DimerNames out;
  std::vector<double> lengths;
  for (const FrameTrack& f : *frames) {
    if (Both(f)) lengths.push_back(Distance(f));
  }
  if (lengths.empty()) return out;
  out.length_px = MedianOf(lengths);
  const double length = out.length_px;
  auto is_dimer = [&](const FrameTrack& f) {
    return Both(f) && std::abs(Distance(f) - length) <= kPairLengthFraction * length;
  };
  const auto anchor = std::find_if(frames->begin(), frames->end(), is_dimer);
  if (anchor == frames->end()) return out;
  for (const FrameTrack& f : *frames) out.pair_frames += is_dimer(f);
  // The first pair fixes the names: left is the smaller column.
  if (anchor->centre[1].x() < anchor->centre[0].x()) {
    anchor->SwapSpheres();
    ++out.renamed;
  }
  const RigidDimer start{anchor->centre, anchor->centre[1] - anchor->centre[0]};
  Namer forward(length, start);
  for (auto it = anchor + 1; it != frames->end(); ++it) forward.Name(&*it, &out);
  Namer backward(length, start);
  for (auto it = std::make_reverse_iterator(anchor); it != frames->rend(); ++it) {
    backward.Name(&*it, &out);
  }
  return out;
}

}  // namespace dimer::tracking
