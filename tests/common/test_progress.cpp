// Durations on the progress lines (common/util/progress.h): whole seconds first, so no "3m60s".
#include <gtest/gtest.h>

#include "common/util/progress.h"

namespace cosim::util {
namespace {

TEST(Progress, DurationsRoundToWholeUnitsWithoutSixty) {
  EXPECT_EQ(format_duration(12.4), "12s");
  EXPECT_EQ(format_duration(59.7), "1m00s");
  EXPECT_EQ(format_duration(239.7), "4m00s");  // was "3m60s"
  EXPECT_EQ(format_duration(61), "1m01s");
  EXPECT_EQ(format_duration(3599.9), "1h00m");
  EXPECT_EQ(format_duration(2 * 3600 + 59.8 * 60), "3h00m");
  EXPECT_EQ(format_duration(-1), "?");
}

}  // namespace
}  // namespace cosim::util
