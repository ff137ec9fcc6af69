// Named timers (include/mote/core/timers.hpp) and the durations the log prints.
#include <gtest/gtest.h>

#include <thread>

#include "mote/core/log.hpp"
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

// The timers' whole is the time since they were made, so that a scope timed before a
// run (the set-up) is a share of it: measured against the run's own wall time, a
// set-up longer than the run came out above 100 %.
TEST(Timers, ElapsedHoldsEveryTimedScope) {
  mote::core::Timers timers;
  {
    mote::core::ScopedTimer setup(timers, "setup");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const auto run_start = std::chrono::steady_clock::now();
  {
    mote::core::ScopedTimer step(timers, "step");
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const double run_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count();
  EXPECT_GT(timers.total("setup"), run_wall);
  EXPECT_GE(timers.elapsed(), timers.total("setup") + timers.total("step"));
}

TEST(Timers, DurationsPrintAsHoursMinutesSeconds) {
  EXPECT_EQ(mote::logging::hms(3725.4), "01:02:05");
  EXPECT_EQ(mote::logging::hms(-1.0), "--:--:--");
  EXPECT_EQ(mote::logging::hms(3.5e9), "972222:13:20");
  // An ETA of a run whose step collapsed: beyond a million hours, not an overflowed count.
  EXPECT_EQ(mote::logging::hms(1e19), ">1e6 h");
  EXPECT_EQ(mote::logging::hms(3.6e9), ">1e6 h");
}
