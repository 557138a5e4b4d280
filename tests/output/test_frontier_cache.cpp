// The file frontier cache: a frontier comes back under its key and only under its key; a
// truncated, edited or stale file reads as absent (so the library recomputes it), never as a
// wrong frontier.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "output/frontier_cache.hpp"
#include "temp_dir_test.hpp"

namespace ecorail::output {
namespace {

dp::Frontier sample() {
  dp::Frontier f;
  f.min_time_s = 80.0;
  for (int k = 0; k < 5; ++k) {
    dp::FrontierPoint p;
    p.target_time_s = p.running_time_s = 80.0 + k;
    p.cost_J = p.traction_work_J = 1e7 / (1.0 + k);
    p.lambda_J_per_s = k == 0 ? INFINITY : 1e5 / k;
    f.points.push_back(p);
  }
  return f;
}

using FrontierCacheTest = ecorail::testing::TempDirTest;

TEST_F(FrontierCacheTest, RoundTripUnderItsKeyOnly) {
  FileFrontierStore store(dir_);
  store.save("key-a", sample());
  const auto back = store.load("key-a");
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->points.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(back->points[k].cost_J, sample().points[k].cost_J,
                1e-9 * sample().points[k].cost_J);
  }
  EXPECT_FALSE(store.load("key-b").has_value());
}

TEST_F(FrontierCacheTest, DamagedOrEditedOrStaleEntriesReadAsAbsent) {
  FileFrontierStore store(dir_);
  store.save("key", sample());
  const auto file = store.path_for("key");
  std::string text;
  {
    std::ifstream in(file);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto rewrite = [&](const std::string& content) {
    std::ofstream out(file, std::ios::trunc);
    out << content;
  };
  rewrite(text.substr(0, text.size() / 2));  // truncated
  EXPECT_FALSE(store.load("key").has_value());
  std::string edited = text;
  const auto at = edited.find("\"cost_kJ\":");
  ASSERT_NE(at, std::string::npos);
  edited.insert(at + 10, "1");  // one energy changed: the checksum no longer matches
  rewrite(edited);
  EXPECT_FALSE(store.load("key").has_value());
  std::string stale = text;
  stale.replace(stale.find("\"key\""), 11, "\"key\":\"old\"");  // another key in the file
  rewrite(stale);
  EXPECT_FALSE(store.load("key").has_value());
  rewrite(text);
  EXPECT_TRUE(store.load("key").has_value());
}

}  // namespace
}  // namespace ecorail::output
