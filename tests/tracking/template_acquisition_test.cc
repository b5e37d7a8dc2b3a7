// The template method on our renderer's mirror-lit steel in the jump mode, where neither sphere
// rests: the learnt appearance's reference point is set at the sphere's centre by the landings
// (RestingRowShift, appearance_model.cc), and a chunk whose first frame shows the spheres
// touching the plate must still find them there (FindAppearance's search below its bound).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/tracking/synthetic.h"
#include "tracking/io/frame_source.h"
#include "tracking/track_sequence.h"

namespace dimer::tracking {
namespace {

// Three plate periods of 80 frames, a landing at 0, 80 and 160.
constexpr size_t kFrames = 161;

const testing::RenderedFilm& JumpFilm() {
  static const testing::RenderedFilm film =
      testing::RenderTrajectory(testing::JumpTrajectory(kFrames, 2000.0), Lighting::kReflect);
  return film;
}

TEST(TemplateLearning, CentresTheReferenceOnAJumpFilm) {
  const testing::RenderedFilm& film = JumpFilm();
  MemorySource src(film.frames);
  SequenceOptions so;
  so.follower.method = Method::kTemplate;
  so.threads = 2;
  so.contact_radius_px = 0.5 * testing::kDiameterM / testing::kMPerPx;
  const SequenceResult r = TrackSequence(src, so);
  // The reference point within half a pixel of the centre, so the template (half-size R + 4)
  // holds the whole sphere. Where the flights' samples, bunched at some height, were taken for
  // a rest, it lay 5.5 px below it on bench/auto_choice.sh's A_r 3.9 jump.
  for (int k = 0; k < 2; ++k) {
    EXPECT_LE(std::abs(r.offsets.row[k].value), 0.5) << "sphere " << k;
    EXPECT_LE(std::abs(r.offsets.col[k].value), 0.5) << "sphere " << k;
  }
}

TEST(TemplateAcquisition, FindsSpheresTouchingThePlateAtAChunksFirstFrame) {
  // Chunks of 16 frames start at each landing (0, 80, 160).
  const size_t n = kFrames;
  const testing::RenderedFilm& film = JumpFilm();
  const std::vector<SceneGeometry>& truth = film.truth;
  MemorySource src(film.frames);
  SequenceOptions so;
  so.follower.method = Method::kTemplate;
  so.threads = 2;
  so.chunk_frames = 16;
  so.contact_radius_px = 0.5 * testing::kDiameterM / testing::kMPerPx;  // --m-per-px given
  const SequenceResult r = TrackSequence(src, so);
  ASSERT_EQ(r.frames.size(), n);
  // Each sphere's rows less their median error (the offset's own uncertainty is not what is
  // judged here): within 0.1 px in every frame, the landings included. With the reference
  // point 5.5 px below the centre and the search bounded a radius above the plate, the chunks'
  // first frames at the landings were 2.4-3.4 px high.
  for (int k = 0; k < 2; ++k) {
    std::vector<double> err;
    for (size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(r.frames[i].found[k]) << "frame " << i << " sphere " << k;
      err.push_back(r.frames[i].centre[k].y() - (k == 0 ? truth[i].left : truth[i].right).y());
    }
    std::vector<double> sorted = err;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(n / 2), sorted.end());
    const double median = sorted[n / 2];
    for (size_t i = 0; i < n; ++i) {
      EXPECT_LE(std::abs(err[i] - median), 0.1)
          << "sphere " << k << ", frame " << i << " (a landing every 80 frames)";
    }
  }
}

}  // namespace
}  // namespace dimer::tracking
