// Hot standby's right to speak (daemon/src/nats/speaking_right.hpp, design §5.9): the
// last renewal vouches for a time; a stall past it silences every output; every server
// lost while it vouched keeps the outputs that need no bus, never NATS publication.

#include <gtest/gtest.h>

#include "speaking_right.hpp"

namespace kew::daemon {
namespace {

using Clock = SpeakingRight::Clock;
const Clock::time_point t0 = Clock::time_point{} + std::chrono::hours(1);

Clock::time_point at(double s) {
  return t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

TEST(SpeakingRight, AHoldingSpeaksUntilItsRenewalStopsVouching) {
  SpeakingRight right;
  EXPECT_FALSE(right.may_speak(at(0)));
  right.hold(7, at(1.125));
  EXPECT_EQ(right.revision(), 7u);
  EXPECT_TRUE(right.may_speak(at(1.0)));
  EXPECT_TRUE(right.may_publish(at(1.0)));
  // A thread waking from a stall after that moment says nothing.
  EXPECT_FALSE(right.may_speak(at(1.125)));
  EXPECT_FALSE(right.may_publish(at(5.0)));
  right.release();
  EXPECT_FALSE(right.may_speak(at(0.5)));
  EXPECT_EQ(right.revision(), 0u);
}

TEST(SpeakingRight, TheBusLostWhileTheHoldingVouchedKeepsTheOtherOutputsNotNats) {
  SpeakingRight right;
  right.hold(3, at(1.125));
  right.bus_lost(at(0.4));
  EXPECT_TRUE(right.bus_away());
  // Ten seconds without a server: nobody else can have taken the key.
  EXPECT_TRUE(right.may_speak(at(10.0)));
  EXPECT_FALSE(right.may_publish(at(10.0)));
  // The bus answers: renewed (or taken again) ends the outage.
  right.hold(9, at(11.125));
  EXPECT_FALSE(right.bus_away());
  EXPECT_TRUE(right.may_publish(at(11.0)));
  EXPECT_FALSE(right.may_speak(at(12.0)));
}

TEST(SpeakingRight, TheBusLostAfterTheHoldingStoppedVouchingGivesNothingBack) {
  // A process stalled past its holding finds, on waking, its connection gone: that is no
  // outage it lived through while it held the lease.
  SpeakingRight right;
  right.hold(3, at(1.125));
  right.bus_lost(at(4.5));
  EXPECT_FALSE(right.bus_away());
  EXPECT_FALSE(right.may_speak(at(4.5)));
}

TEST(SpeakingRight, AReleasedHoldingIsNotKeptByTheBusAway) {
  SpeakingRight right;
  right.bus_lost(at(0.0));  // not held: nothing to keep
  EXPECT_FALSE(right.bus_away());
  right.hold(3, at(1.125));
  right.bus_lost(at(0.5));
  right.release();  // another instance holds the key: stepped down
  EXPECT_FALSE(right.bus_away());
  EXPECT_FALSE(right.may_speak(at(0.6)));
  right.hold(4, at(2.0));
  EXPECT_FALSE(right.bus_away()) << "a new holding starts with the bus answering";
}

TEST(SpeakingRight, AHoldingTheOutputsFoundNotVouchingStaysLapsedWhateverARenewalSays) {
  // The gate shuts on the first false; a renewal the server takes a moment later (it had
  // not expired the key yet) must not keep a lease whose outputs are shut.
  SpeakingRight right;
  right.hold(3, at(1.125));
  EXPECT_TRUE(right.keep_speaking(at(1.0)));
  EXPECT_FALSE(right.lapsed());
  EXPECT_FALSE(right.keep_speaking(at(4.5)));
  EXPECT_TRUE(right.lapsed());
  right.hold(3, at(5.5));  // the late renewal
  EXPECT_TRUE(right.lapsed()) << "the lease thread gives the holding up";
  right.release();
  EXPECT_FALSE(right.lapsed());
  // Not held: nothing lapses.
  EXPECT_FALSE(right.keep_speaking(at(6.0)));
  EXPECT_FALSE(right.lapsed());
}

TEST(SpeakingRight, TheBusAwayIsNoLapse) {
  SpeakingRight right;
  right.hold(3, at(1.125));
  right.bus_lost(at(0.5));
  EXPECT_TRUE(right.keep_speaking(at(9.0)));
  EXPECT_FALSE(right.lapsed());
}

}  // namespace
}  // namespace kew::daemon
