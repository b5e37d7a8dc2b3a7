#include "tracking/template_sequence.h"

#include <algorithm>
#include <cmath>

namespace dimer::tracking {

std::vector<size_t> LearningIndices(size_t frames) {
  const size_t span = std::min(frames, kLearnSpanFrames);
  const size_t step = std::max<size_t>(1, span / kLearnFrames);
  std::vector<size_t> out;
  for (size_t i = 0; i < span && out.size() < kLearnFrames; i += step) out.push_back(i);
  return out;
}

SequenceMethod PrepareSequenceMethod(const std::vector<Frame>& learning,
                                     const TrackerOptions& reference, Method requested) {
  SequenceMethod m;
  std::vector<FrameTrack> probes;
  std::vector<LearningSample> samples;
  std::vector<std::array<bool, 2>> clean;
  TrackerOptions o = reference;
  o.method = Method::kCentroid;
  o.appearance.reset();
  for (const Frame& f : learning) {
    SequenceTracker t(o);  // a fresh acquisition per frame: the learning frames are far apart
    probes.push_back(t.Process(f.image, f.index));
    LearningSample s;
    s.image = f.image;
    s.plate_row = probes.back().plate_row;
    s.found = probes.back().found;
    s.centre = probes.back().centre;
    samples.push_back(s);
    std::array<bool, 2> c{false, false};
    for (int k = 0; k < 2; ++k) {
      if (s.found[0] && s.found[1]) {
        c[k] = CleanSilhouette(f.image, s.centre[k], reference.radius_px, s.centre[1 - k],
                               s.plate_row);
      } else if (s.found[k]) {
        c[k] = CleanSilhouette(f.image, s.centre[k], reference.radius_px, s.centre[k], s.plate_row);
      }
    }
    clean.push_back(c);
  }
  m.choice = ChooseMethod(probes, clean, requested);
  if (m.choice.method != Method::kTemplate) return m;
  m.learnt = LearnAppearances(samples, reference.radius_px, !m.choice.silhouettes);
  if (!m.learnt[0].appearance.valid() || !m.learnt[1].appearance.valid()) {
    // Nothing to learn from (fewer than 3 learning frames with both spheres): the silhouette
    // methods are what is left.
    m.choice.method = Method::kCentroid;
    m.choice.reason += "; too few learning frames with both spheres to learn an appearance, "
                       "centroid instead";
    return m;
  }
  m.appearance = std::make_shared<const std::array<Appearance, 2>>(
      std::array<Appearance, 2>{m.learnt[0].appearance, m.learnt[1].appearance});
  return m;
}

TemplateOffsets EstimateOffsets(const SequenceMethod& m, const std::vector<FrameTrack>& frames,
                                double contact_radius_px) {
  TemplateOffsets o;
  for (int k = 0; k < 2; ++k) {
    if (m.choice.silhouettes) {
      o.col[k] = SilhouetteOffset(m.learnt[k], 0);
      o.row[k] = SilhouetteOffset(m.learnt[k], 1);
      continue;
    }
    std::vector<double> rows, plate;
    for (const FrameTrack& f : frames) {
      rows.push_back(f.found[k] ? f.centre[k].y() : std::nan(""));
      plate.push_back(f.plate_row);
    }
    o.row[k] = ContactRowOffset(rows, plate, contact_radius_px);
    o.col[k] = SymmetryColumnOffset(m.learnt[k].appearance);
  }
  if (m.choice.silhouettes) return o;
  // The sphere that rests longer (more frames in its contact cluster) sets the contact; the
  // other one, if it rests much less (it bounces: the frames near its impacts are flight, up to
  // a few tenths of a pixel above contact, and bias its own estimate upward), gets that offset
  // carried over by registering the two appearances.
  const int ref = o.row[1].n > o.row[0].n ? 1 : 0, other = 1 - ref;
  if (o.row[ref].source == "plate_contact" && o.row[ref].n >= kMinRestingFrames &&
      double(o.row[other].n) < kTransferBelowFraction * double(o.row[ref].n)) {
    const OffsetEstimate t = TransferOffset(m.learnt[ref].appearance, m.learnt[other].appearance,
                                            o.row[ref], 1);
    if (t.source != "none") o.row[other] = t;
  }
  return o;
}

void ApplyOffsets(const TemplateOffsets& o, std::vector<FrameTrack>* frames) {
  for (FrameTrack& f : *frames) {
    for (int k = 0; k < 2; ++k) {
      if (f.found[k]) f.centre[k] += Eigen::Vector2d(o.col[k].value, o.row[k].value);
    }
  }
}

}  // namespace dimer::tracking
