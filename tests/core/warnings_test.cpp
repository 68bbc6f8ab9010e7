#include "core/warnings.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace tw {
namespace {

TEST(Warnings, KeepsOrderAndDropsExactRepeats) {
  Warnings warnings;
  warnings.add("repaired", "features.rivers", 2, "removed 3 duplicate vertices");
  warnings.add("empty_class", "features.ridges", std::nullopt, "no feature on the heightfield");
  warnings.add("repaired", "features.rivers", 2, "removed 3 duplicate vertices");
  warnings.add("repaired", "features.rivers", 3, "removed 3 duplicate vertices");
  const std::vector<Warning> list = warnings.list();
  ASSERT_EQ(list.size(), 3u);
  EXPECT_EQ(list[0].fid, 2);
  EXPECT_EQ(list[1].code, "empty_class");
  EXPECT_EQ(list[2].fid, 3);
}

TEST(Warnings, FormatsSubjectFidAndMessageOnOneLine) {
  EXPECT_EQ(to_string({"repaired", "features.rivers", 7, "spike removed"}),
            "features.rivers: FID 7: spike removed");
  EXPECT_EQ(to_string({"empty_class", "features.ridges", std::nullopt, "none"}),
            "features.ridges: none");
  EXPECT_EQ(to_string({"x", "", std::nullopt, "a\nterraweave: ok\r"}), "a\\nterraweave: ok\\r");
}

TEST(Warnings, CollectsFromManyThreads) {
  Warnings warnings;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 100; ++i) warnings.add("w", "features.roads", t * 1000 + i, "m");
    });
  }
  for (auto& thread : threads) thread.join();
  EXPECT_EQ(warnings.size(), 400u);
  const Warnings copy = warnings;
  EXPECT_EQ(copy.size(), 400u);
}

}  // namespace
}  // namespace tw
