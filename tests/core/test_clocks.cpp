#include <gtest/gtest.h>

#include <chrono>
#include <ctime>
#include <thread>

#include "kew/util/clocks.hpp"

namespace {

TEST(Clocks, UnixNowIsTheSystemClockInSecondsSince1970) {
  const std::time_t before = std::time(nullptr);
  const double now = kew::util::unix_now_s();
  const std::time_t after = std::time(nullptr);
  EXPECT_GE(now, static_cast<double>(before));
  EXPECT_LT(now, static_cast<double>(after) + 1.0);
  EXPECT_GT(now, 1.7e9);  // after 2023-11-14: not a steady clock's arbitrary epoch
}

TEST(Clocks, SteadyNowNeverGoesBackAndCountsSeconds) {
  const double first = kew::util::steady_now_s();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double second = kew::util::steady_now_s();
  EXPECT_GE(second - first, 0.020);  // seconds, not milliseconds or ticks
}

}  // namespace
