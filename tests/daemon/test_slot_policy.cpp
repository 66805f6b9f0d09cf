// Who gives way at a full listener (daemon/src/connections/slot_policy.hpp): the rule
// that keeps a health probe answerable under any connection flood.

#include <gtest/gtest.h>

#include <vector>

#include "slot_policy.hpp"

namespace kew::daemon {
namespace {

using Clock = std::chrono::steady_clock;
const Clock::time_point t0{};

Clock::time_point at(int s) { return t0 + std::chrono::seconds(s); }

TEST(SlotPolicy, RoomLeftAndFewSilentConnectionsCloseNothing) {
  const std::vector<SlotHolder> holders{{"10.0.0.1", true, at(1)}, {"10.0.0.2", true, at(2)}};
  EXPECT_FALSE(connection_to_evict(holders, "10.0.0.3", 4, false));
  EXPECT_FALSE(connection_to_evict(holders, "10.0.0.1", 4, false));
}

TEST(SlotPolicy, EverySlotTakenClosesTheLongestSilentOfAllWhenEachAddressHoldsOne) {
  const std::vector<SlotHolder> holders{
      {"10.0.0.1", true, at(5)}, {"10.0.0.2", true, at(2)}, {"10.0.0.3", false, at(0)}, {"10.0.0.4", true, at(9)}};
  EXPECT_EQ(connection_to_evict(holders, "10.0.0.9", 4, true), 1u);
}

TEST(SlotPolicy, EverySlotTakenTheAddressHoldingMostSilentOnesPaysFirst) {
  // 10.0.0.2's lone connection is the oldest, but 10.0.0.7 holds three silent ones.
  const std::vector<SlotHolder> holders{{"10.0.0.7", true, at(6)},
                                        {"10.0.0.2", true, at(1)},
                                        {"10.0.0.7", true, at(4)},
                                        {"10.0.0.7", true, at(8)},
                                        {"10.0.0.5", false, at(0)}};
  EXPECT_EQ(connection_to_evict(holders, "10.0.0.9", 4, true), 2u);
  // A newcomer from the busiest address itself, under its limit: the same answer.
  EXPECT_EQ(connection_to_evict(holders, "10.0.0.7", 4, true), 2u);
}

TEST(SlotPolicy, ServedConnectionsNeverGiveWay) {
  // Every slot held by a watching subscriber (or a WebSocket): the newcomer is refused.
  const std::vector<SlotHolder> holders{{"10.0.0.1", false, at(0)}, {"10.0.0.1", false, at(1)}};
  EXPECT_FALSE(connection_to_evict(holders, "10.0.0.1", 1, true));
  EXPECT_FALSE(connection_to_evict(holders, "10.0.0.2", 1, true));
}

TEST(SlotPolicy, AnAddressAtItsLimitClosesItsOwnLongestSilentEvenWithRoomLeft) {
  const std::vector<SlotHolder> holders{{"10.0.0.7", true, at(3)},
                                        {"10.0.0.1", true, at(1)},  // older, but another address
                                        {"10.0.0.7", true, at(2)},
                                        {"10.0.0.7", false, at(0)}};  // watching: not counted
  EXPECT_EQ(connection_to_evict(holders, "10.0.0.7", 2, false), 2u);
  EXPECT_FALSE(connection_to_evict(holders, "10.0.0.7", 3, false));
  // When full, the address at its limit still pays, not the older connection of another.
  EXPECT_EQ(connection_to_evict(holders, "10.0.0.7", 2, true), 2u);
}

TEST(SlotPolicy, ALimitOfZeroActsAsOne) {
  const std::vector<SlotHolder> holders{{"::1", true, at(4)}};
  EXPECT_EQ(connection_to_evict(holders, "::1", 0, false), 0u);
}

TEST(SlotPolicy, TiesGoToTheEarlierHolder) {
  const std::vector<SlotHolder> holders{{"10.0.0.1", true, at(2)}, {"10.0.0.2", true, at(2)}};
  EXPECT_EQ(connection_to_evict(holders, "10.0.0.3", 4, true), 0u);
}

TEST(SlotPolicy, NoHoldersNothingToClose) {
  EXPECT_FALSE(connection_to_evict({}, "10.0.0.1", 1, true));
}

}  // namespace
}  // namespace kew::daemon
