// The live tick's rule (daemon/src/service/feed_silence.hpp, design §4.1 "Live mode"): a
// feed is silent only while every source that knows its backlog has nothing more for
// kewd, and the time a source was unreachable or behind is not silence.

#include <gtest/gtest.h>

#include "feed_silence.hpp"
#include "steady_at.hpp"

namespace kew::daemon {
namespace {

using test::at;

TEST(FeedSilence, SourcesThatNeverTellCountSilenceFromTheLastRecord) {
  const FeedSilence silence(2);  // UDP, TCP, files, plain NATS subscriptions
  EXPECT_FALSE(silence.silent_s(std::nullopt, at(5)));
  EXPECT_DOUBLE_EQ(*silence.silent_s(4.0, at(5)), 4.0);
  EXPECT_FALSE(silence.unreachable());
}

TEST(FeedSilence, AnUnreachableSourceHoldsTheClockAndSaysSo) {
  FeedSilence silence(2);
  silence.source(1, SourceState::Unreachable, at(10));
  EXPECT_TRUE(silence.unreachable());
  EXPECT_DOUBLE_EQ(*silence.silent_s(12.0, at(22)), 0.0) << "a 10 s outage is not 10 s of silence";
  EXPECT_FALSE(silence.silent_s(std::nullopt, at(22))) << "no record yet: nothing to move";
}

TEST(FeedSilence, ABacklogHoldsTheClockUntilItIsRead) {
  FeedSilence silence(1);
  silence.source(0, SourceState::Behind, at(10));
  EXPECT_FALSE(silence.unreachable()) << "behind is not unreachable: the records are coming";
  EXPECT_DOUBLE_EQ(*silence.silent_s(3.0, at(13)), 0.0);
  silence.source(0, SourceState::CaughtUp, at(14));
  EXPECT_DOUBLE_EQ(*silence.silent_s(4.0, at(14)), 0.0);
  EXPECT_DOUBLE_EQ(*silence.silent_s(6.0, at(16)), 2.0) << "silence counts from the catching up";
}

TEST(FeedSilence, AfterAnOutageSilenceCountsFromTheLaterOfTheRecordAndTheReturn) {
  FeedSilence silence(1);
  silence.source(0, SourceState::Unreachable, at(100));
  silence.source(0, SourceState::CaughtUp, at(111));  // back, nothing published meanwhile
  EXPECT_DOUBLE_EQ(*silence.silent_s(11.5, at(111.5)), 0.5) << "not the 11.5 s since the last record";
  EXPECT_DOUBLE_EQ(*silence.silent_s(1.0, at(113)), 1.0) << "a record after the return counts from itself";
  EXPECT_FALSE(silence.unreachable());
}

TEST(FeedSilence, EverySourceMustHaveCaughtUp) {
  FeedSilence silence(2);
  silence.source(0, SourceState::Unreachable, at(0));
  silence.source(1, SourceState::Behind, at(1));
  silence.source(0, SourceState::CaughtUp, at(5));
  EXPECT_DOUBLE_EQ(*silence.silent_s(9.0, at(9)), 0.0) << "input 1 still has a backlog";
  silence.source(1, SourceState::CaughtUp, at(7));
  EXPECT_DOUBLE_EQ(*silence.silent_s(9.0, at(9)), 2.0);
  // A source telling again that it is caught up does not restart the count.
  silence.source(0, SourceState::CaughtUp, at(8));
  EXPECT_DOUBLE_EQ(*silence.silent_s(10.0, at(10)), 3.0);
}

}  // namespace
}  // namespace kew::daemon
