// The footage checks' shared accuracy (accuracy_cache.h): read back exactly, used only when it is
// newer than the footage's truth and the program, and never trusted in part.
#include "tests/footage/accuracy_cache.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "tests/common/test_tmpdir.h"

namespace dimer::footage {
namespace {

TrackAccuracy Sample() {
  TrackAccuracy a;
  a.method = "auto";
  a.template_run = true;
  a.frames = 20;
  a.identity_swaps = 1;
  a.plate_found = 19;
  a.plate_bias = -0.1 / 3;
  a.plate_max_error = 0.07312345678901234;
  a.seconds = 1.25;
  a.sphere[0].good = 20;
  a.sphere[0].found = 19;
  a.sphere[0].found_fraction = 0.95;
  a.sphere[0].bias = Eigen::Vector2d(std::acos(-1.0), -1e-300);
  a.sphere[0].scatter = 0.0333;
  a.sphere[1].scatter_bound = std::numeric_limits<double>::quiet_NaN();
  a.sphere[1].stated_err = Eigen::Vector2d(0.1, 0.2);
  a.sphere[1].bias_sigmas = Eigen::Vector2d(std::numeric_limits<double>::infinity(), 0.5);
  return a;
}

// Every field, bit for bit (NaN as NaN).
void ExpectSame(const TrackAccuracy& x, const TrackAccuracy& y) {
  auto same = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; };
  EXPECT_EQ(x.method, y.method);
  EXPECT_EQ(x.template_run, y.template_run);
  EXPECT_EQ(x.frames, y.frames);
  EXPECT_EQ(x.identity_swaps, y.identity_swaps);
  EXPECT_EQ(x.plate_found, y.plate_found);
  EXPECT_TRUE(same(x.plate_bias, y.plate_bias));
  EXPECT_TRUE(same(x.plate_max_error, y.plate_max_error));
  EXPECT_TRUE(same(x.seconds, y.seconds));
  for (int k = 0; k < 2; ++k) {
    const SphereAccuracy& p = x.sphere[k];
    const SphereAccuracy& q = y.sphere[k];
    EXPECT_EQ(p.good, q.good);
    EXPECT_EQ(p.found, q.found);
    for (auto [u, v] : {std::pair{p.found_fraction, q.found_fraction},
                        {p.bias.x(), q.bias.x()}, {p.bias.y(), q.bias.y()},
                        {p.scatter, q.scatter}, {p.max_error, q.max_error},
                        {p.scatter_bound, q.scatter_bound},
                        {p.bias_sampling.x(), q.bias_sampling.x()},
                        {p.bias_sampling.y(), q.bias_sampling.y()},
                        {p.stated_err.x(), q.stated_err.x()}, {p.stated_err.y(), q.stated_err.y()},
                        {p.bias_sigmas.x(), q.bias_sigmas.x()},
                        {p.bias_sigmas.y(), q.bias_sigmas.y()}}) {
      EXPECT_TRUE(same(u, v)) << "sphere " << k << ": " << u << " read back as " << v;
    }
  }
}

TEST(AccuracyCache, EveryFieldIsReadBackExactly) {
  const TrackAccuracy a = Sample();
  TrackAccuracy b;
  ASSERT_TRUE(ParseAccuracy(SerializeAccuracy(a), &b));
  ExpectSame(a, b);
}

TEST(AccuracyCache, AFileCutShortOrAlteredIsNotTrustedInPart) {
  const std::string text = SerializeAccuracy(Sample());
  TrackAccuracy b;
  EXPECT_FALSE(ParseAccuracy(text.substr(0, text.size() / 2), &b));
  EXPECT_FALSE(ParseAccuracy(text.substr(0, text.size() - 4), &b));  // no "end"
  EXPECT_FALSE(ParseAccuracy(text + "more\n", &b));
  std::string bad = text;
  bad.replace(bad.find("frames 20"), 9, "frames x0");
  EXPECT_FALSE(ParseAccuracy(bad, &b));
}

// A folder with a truth.csv but no frames: measuring it throws, so a result means the cache
// was read.
TEST(AccuracyCache, AnEntryNewerThanTheTruthIsUsedAndAStaleOneIsNot) {
  dimer::testing::TempDir tmp;
  const std::string folder = tmp / "footage";
  std::filesystem::create_directories(folder);
  std::ofstream(folder + "/truth.csv") << "frame,file,t\n";
  const std::string cache = tmp / "cache/case.auto";
  std::filesystem::create_directories(tmp / "cache");
  const std::string request = "dimerlab-track-accuracy 1\nfolder " +
                              std::filesystem::absolute(folder).lexically_normal().string() +
                              "\nrequest auto 2\n";
  std::ofstream(cache) << request << SerializeAccuracy(Sample());
  const auto now = std::filesystem::file_time_type::clock::now();
  std::filesystem::last_write_time(folder + "/truth.csv", now - std::chrono::hours(1));
  std::filesystem::last_write_time(cache, now);
  ExpectSame(CachedTrackAccuracy(folder, "auto", 2, cache), Sample());

  // Another method or thread count is another entry.
  EXPECT_ANY_THROW(CachedTrackAccuracy(folder, "template", 2, cache));
  std::ofstream(cache) << request << SerializeAccuracy(Sample());
  std::filesystem::last_write_time(cache, now);
  EXPECT_ANY_THROW(CachedTrackAccuracy(folder, "auto", 1, cache));

  // Footage rendered again after the entry was written.
  std::ofstream(cache) << request << SerializeAccuracy(Sample());
  std::filesystem::last_write_time(cache, now);
  std::filesystem::last_write_time(folder + "/truth.csv", now + std::chrono::seconds(1));
  EXPECT_ANY_THROW(CachedTrackAccuracy(folder, "auto", 2, cache));
}

}  // namespace
}  // namespace dimer::footage
