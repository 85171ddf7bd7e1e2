// The coupler's limit on unauthenticated traffic (coupler/stranger_limit.h), on a simulated clock.
#include <gtest/gtest.h>

#include "coupler/stranger_limit.h"

using cosim::coupler::StrangerLimit;

TEST(StrangerLimit, AdmitsItsRateAndBurstAndCountsTheRest) {
  StrangerLimit lim;
  bool log = false;
  int admitted = 0;
  for (int i = 0; i < 1000; ++i) admitted += lim.admit(100.0, log) ? 1 : 0;  // 1000 at one instant: the burst
  EXPECT_EQ(admitted, static_cast<int>(StrangerLimit::kBurst));
  EXPECT_EQ(lim.dropped(), 1000 - admitted);
  // One second later the bucket holds kRate more.
  admitted = 0;
  for (int i = 0; i < 1000; ++i) admitted += lim.admit(101.0, log) ? 1 : 0;
  EXPECT_EQ(admitted, static_cast<int>(StrangerLimit::kRate));
  const std::string s = lim.summary(101.0);
  EXPECT_NE(s.find("1940 message(s) dropped unanswered"), std::string::npos) << s;
  EXPECT_EQ(lim.summary(105.0), "") << "a second summary within 10 s";
}

TEST(StrangerLimit, StopsNamingMessagesAfterItsLineBudget) {
  StrangerLimit lim;
  bool log = false;
  long named = 0;
  for (int i = 0; i < 10 * StrangerLimit::kMaxLogged; ++i) {  // slow enough to be admitted every time
    ASSERT_TRUE(lim.admit(i * 0.1, log));
    named += log ? 1 : 0;
  }
  EXPECT_EQ(named, StrangerLimit::kMaxLogged);
  EXPECT_NE(lim.summary(1e4).find("answered without a log line"), std::string::npos);
}
