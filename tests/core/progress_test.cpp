// Progress in logs: a line every 10 % (from 0 %) once a stage has run for its quiet period, nothing
// for short stages, and a 100 % line only after earlier ones.
#include "core/progress.hpp"

#include <gtest/gtest.h>
#include <spdlog/sinks/ringbuffer_sink.h>

#include <memory>
#include <string>
#include <vector>

#include "core/log.hpp"

namespace tw {
namespace {

// The lines the terraweave logger receives while `body` runs.
template <class Body>
std::vector<std::string> logged_lines(Body body) {
  auto sink = std::make_shared<spdlog::sinks::ringbuffer_sink_mt>(100);
  sink->set_pattern("%v");
  logger().sinks().push_back(sink);
  body();
  logger().sinks().pop_back();
  return sink->last_formatted();
}

std::string without_newline(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

TEST(Progress, LongStagesLogEveryTenPercent) {
  const auto lines = logged_lines([] {
    Progress progress("features.roads: FID 3: DP rows", 50, {false, std::chrono::milliseconds(0)});
    for (int i = 0; i < 50; ++i) progress.advance();
  });
  ASSERT_EQ(lines.size(), 11u);  // 0 %, 10 %, ..., 100 %
  EXPECT_EQ(without_newline(lines.front()), "features.roads: FID 3: DP rows: 0%");
  EXPECT_EQ(without_newline(lines[5]), "features.roads: FID 3: DP rows: 50%");
  EXPECT_EQ(without_newline(lines.back()), "features.roads: FID 3: DP rows: 100%");
}

TEST(Progress, ShortStagesLogNothingNotEvenTheirEnd) {
  const auto lines = logged_lines([] {
    Progress progress("DP rows", 50, {false, std::chrono::hours(1)});
    for (int i = 0; i < 50; ++i) progress.advance();
  });
  EXPECT_TRUE(lines.empty()) << lines.front();
}

TEST(Progress, ItemsLogEachItemWithItsCountAndAnEta) {
  const auto lines = logged_lines([] {
    Progress progress("render", 3, "tile", {false, std::chrono::milliseconds(0)});
    for (int i = 0; i < 3; ++i) progress.advance();
  });
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(without_newline(lines[0]).substr(0, 24), "render: tile 1 of 3, ETA");
  EXPECT_EQ(without_newline(lines[2]), "render: tile 3 of 3, ETA 0 s");
}

TEST(Progress, EtaScalesTheElapsedTimeByTheItemsLeft) {
  EXPECT_EQ(eta_text(0, 10, 5.0), "ETA ?");
  EXPECT_EQ(eta_text(1, 4, 10.0), "ETA 30 s");
  EXPECT_EQ(eta_text(2, 10, 46.0), "ETA 3 min 04 s");
  EXPECT_EQ(eta_text(1, 100, 80.0), "ETA 2 h 12 min");
  EXPECT_EQ(eta_text(10, 10, 99.0), "ETA 0 s");
}

}  // namespace
}  // namespace tw
