// Every log line is one line: a newline in a message (from a key, a --set value, a file name)
// is escaped, so no input can forge a line such as "terraweave: ok".
#include "core/log.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

namespace tw {
namespace {

TEST(SingleLine, EscapesNewlinesAndCarriageReturns) {
  EXPECT_EQ(single_line("a\nterraweave: ok\r\n"), "a\\nterraweave: ok\\r\\n");
  EXPECT_EQ(single_line("plain"), "plain");
}

TEST(Logger, PrintsAMessageWithANewlineOnOneLine) {
  ::testing::internal::CaptureStderr();
  logger().warn("key 'a\nterraweave: ok' is odd");
  logger().flush();
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_THAT(printed, ::testing::HasSubstr("key 'a\\nterraweave: ok' is odd"));
  EXPECT_EQ(std::count(printed.begin(), printed.end(), '\n'), 1) << printed;
}

}  // namespace
}  // namespace tw
