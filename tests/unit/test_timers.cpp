// Named timers (include/mote/core/timers.hpp).
#include <gtest/gtest.h>

#include <thread>

#include "mote/core/timers.hpp"

TEST(Timers, AccumulateAndSummarise) {
  mote::core::Timers timers;
  for (int i = 0; i < 3; ++i) {
    mote::core::ScopedTimer t(timers, "sleep");
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_GE(timers.total("sleep"), 0.015);
  EXPECT_LT(timers.total("sleep"), 1.0);
  EXPECT_EQ(timers.total("never"), 0.0);
  const auto s = timers.summary(1.0);
  EXPECT_NE(s.find("sleep"), std::string::npos);
  EXPECT_NE(s.find("         3"), std::string::npos) << s;
}
