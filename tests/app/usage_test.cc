#include "app/usage.h"

#include <gtest/gtest.h>

namespace dimer::app {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutions) {
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("sim", "sim"), 0u);
  EXPECT_EQ(EditDistance("simm", "sim"), 1u);      // insertion
  EXPECT_EQ(EditDistance("trak", "track"), 1u);    // deletion
  EXPECT_EQ(EditDistance("--fsp", "--fps"), 2u);   // transposition = two substitutions
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("abc", ""), 3u);
}

TEST(NearestName, SuggestsOnlyLikelyTypos) {
  const std::vector<std::string> subs = {"sim", "render", "track"};
  EXPECT_EQ(NearestName("simm", subs), "sim");
  EXPECT_EQ(NearestName("trak", subs), "track");
  EXPECT_EQ(NearestName("rendr", subs), "render");
  EXPECT_EQ(NearestName("compare", subs), "");  // far from every name: no suggestion
}

// A CLI11 app is neither copyable nor movable: filled in place.
void FillApp(CLI::App& app) {
  CLI::App* sim = app.add_subcommand("sim", "");
  sim->add_option("--fps", "");
  sim->add_option("-o,--output", "");
  app.add_subcommand("track", "");
}

TEST(CheckSubcommand, NamesTheWordAndTheNearestSubcommand) {
  CLI::App app{"test"};
  FillApp(app);
  EXPECT_FALSE(CheckSubcommand(app, {"sim", "-o", "x"}).has_value());
  EXPECT_FALSE(CheckSubcommand(app, {"--version"}).has_value());
  const auto msg = CheckSubcommand(app, {"simm", "-o", "x"});
  ASSERT_TRUE(msg.has_value());
  EXPECT_NE(msg->find("unknown subcommand 'simm'; did you mean 'sim'?"), std::string::npos);
  const auto none = CheckSubcommand(app, {});
  ASSERT_TRUE(none.has_value());
  EXPECT_NE(none->find("a subcommand is required: sim, track"), std::string::npos);
}

TEST(ExtrasMessage, NamesEachUnknownOptionWithTheNearestOne) {
  CLI::App app{"test"};
  FillApp(app);
  const std::string msg =
      ExtrasMessage(app, {"sim", "--fsp=3", "-o", "x", "--outptu", "y"}, "cli11 text");
  EXPECT_NE(msg.find("sim: unknown option '--fsp'; did you mean '--fps'?"), std::string::npos);
  EXPECT_NE(msg.find("unknown option '--outptu'; did you mean '--output'?"), std::string::npos);
  // A negative number is a value, not an option; with no unknown option CLI11's text stands.
  EXPECT_EQ(ExtrasMessage(app, {"sim", "--fps", "-5", "extra"}, "cli11 text"), "cli11 text");
}

}  // namespace
}  // namespace dimer::app
