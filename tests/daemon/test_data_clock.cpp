// The data clock between records (daemon/src/service/data_clock.hpp, design §4.1 "Live
// mode", §5.6): live, it runs on with the wall clock while the feed is silent; a replay
// runs it at its speed, stops it at the file's end, and at speed 0 leaves it to records.

#include <gtest/gtest.h>

#include "data_clock.hpp"
#include "steady_at.hpp"

namespace kew::daemon {
namespace {

using test::at;

constexpr double kLast = 1'000.0;  // the last record's data time
constexpr double kTick = 1.0;

TEST(DataClock, LiveTheClockRunsOnWithTheSilenceAndTheTickMovesItOnlyAfterAWholeTick) {
  const DataClock clock(1, {});
  EXPECT_DOUBLE_EQ(clock.at(kLast, std::nullopt, at(5)), kLast) << "no record yet: nothing runs on";
  EXPECT_DOUBLE_EQ(clock.at(kLast, 2.5, at(5)), kLast + 2.5);
  EXPECT_FALSE(clock.tick(kLast, 0.5, at(5), kTick)) << "records drive the clock while they come";
  EXPECT_FALSE(clock.tick(kLast, std::nullopt, at(5), kTick));
  ASSERT_TRUE(clock.tick(kLast, 1.0, at(5), kTick));
  EXPECT_DOUBLE_EQ(*clock.tick(kLast, 3.0, at(5), kTick), kLast + 3.0);
}

TEST(DataClock, AnUnreachableSourceHoldsTheClock) {
  DataClock clock(2, {});
  clock.source(1, SourceState::Unreachable, at(10));
  EXPECT_TRUE(clock.unreachable());
  EXPECT_DOUBLE_EQ(clock.at(kLast, 12.0, at(22)), kLast);
  EXPECT_FALSE(clock.tick(kLast, 12.0, at(22), kTick)) << "an outage is not silence";
}

TEST(DataClock, AReplayRunsAtItsSpeedAndStandsStillAtItsEnd) {
  DataClock clock(1, {.replay = true, .speed = 4.0});
  EXPECT_DOUBLE_EQ(clock.at(kLast, 2.0, at(5)), kLast + 8.0);
  EXPECT_DOUBLE_EQ(*clock.tick(kLast, 2.0, at(5), kTick), kLast + 8.0);
  EXPECT_FALSE(clock.replay_ended());
  clock.end_of_replay();
  EXPECT_TRUE(clock.replay_ended());
  EXPECT_DOUBLE_EQ(clock.at(kLast, 60.0, at(65)), kLast) << "the last state stays on show";
  EXPECT_FALSE(clock.tick(kLast, 60.0, at(65), kTick));
}

TEST(DataClock, AReplayAsFastAsPossibleLeavesTheClockToItsRecords) {
  const DataClock clock(1, {.replay = true, .speed = 0.0});
  EXPECT_DOUBLE_EQ(clock.at(kLast, 30.0, at(35)), kLast);
  EXPECT_FALSE(clock.tick(kLast, 30.0, at(35), kTick));
}

}  // namespace
}  // namespace kew::daemon
