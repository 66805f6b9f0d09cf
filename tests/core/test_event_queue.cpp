#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "kew/kinetic/event_queue.hpp"

namespace {

using kew::kinetic::EventKind;
using kew::kinetic::EventQueue;

/// Pops every entry, checking that each comes after the one before by (time, seq).
std::vector<EventQueue::Entry> drain_in_order(EventQueue& q) {
  std::vector<EventQueue::Entry> popped;
  while (!q.empty()) {
    popped.push_back(q.pop());
    if (popped.size() < 2) continue;
    const EventQueue::Entry& a = popped[popped.size() - 2];
    const EventQueue::Entry& b = popped.back();
    EXPECT_TRUE(b.time > a.time || (b.time == a.time && b.seq > a.seq)) << "seq " << b.seq << " after " << a.seq;
  }
  return popped;
}

TEST(EventQueue, PopsByTimeThenInPushOrder) {
  EventQueue q;
  const std::uint64_t late = q.push(2.0, 7, 1, EventKind::Failure, 0);
  const std::uint64_t tie_first = q.push(1.0, 8, 2, EventKind::Renewal, 0);
  const std::uint64_t early = q.push(-5.0, 9, 0, EventKind::TwinRelease, 3);
  const std::uint64_t tie_second = q.push(1.0, 8, 0, EventKind::Approach, 0);
  EXPECT_LT(late, tie_first);  // sequence numbers increase in push order
  EXPECT_LT(tie_first, early);
  EXPECT_LT(early, tie_second);
  ASSERT_EQ(q.size(), 4u);

  EXPECT_EQ(q.top().seq, early);
  const EventQueue::Entry e = q.pop();
  EXPECT_EQ(e.time, -5.0);
  EXPECT_EQ(e.subject, 9u);
  EXPECT_EQ(e.edge, 0u);
  EXPECT_EQ(e.kind, EventKind::TwinRelease);
  EXPECT_EQ(e.retries, 3u);
  // Equal times: the one pushed first pops first.
  EXPECT_EQ(q.pop().seq, tie_first);
  EXPECT_EQ(q.pop().seq, tie_second);
  EXPECT_EQ(q.pop().seq, late);
  EXPECT_TRUE(q.empty());
}

TEST(EventQueue, ManyTiesPopInPushOrder) {
  EventQueue q;
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> slot(0, 9);
  for (int k = 0; k < 5000; ++k) q.push(0.5 * slot(rng), 0, 0, EventKind::Failure, 0);
  EXPECT_EQ(drain_in_order(q).size(), 5000u);
}

TEST(EventQueue, CompactionWaitsForAMajorityOfStaleEntriesThenKeepsTheOrder) {
  EventQueue q;
  const std::size_t n = 2 * EventQueue::kCompactFrom;
  std::set<std::uint64_t> live;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint64_t seq = q.push(static_cast<double>(k % 17), 0, 0, EventKind::Failure, 0);
    if (k % 3 == 0) live.insert(seq);
  }
  const auto is_live = [&](const EventQueue::Entry& e) { return live.count(e.seq) == 1; };
  // More than half live by the caller's count: nothing is dropped.
  q.compact(n / 2 + 1, is_live);
  EXPECT_EQ(q.size(), n);
  q.compact(live.size(), is_live);
  EXPECT_EQ(q.size(), live.size());
  for (const EventQueue::Entry& e : drain_in_order(q)) EXPECT_EQ(live.count(e.seq), 1u);
}

TEST(EventQueue, SmallQueuesAreNotCompacted) {
  EventQueue q;
  for (std::size_t k = 0; k + 1 < EventQueue::kCompactFrom; ++k) q.push(1.0, 0, 0, EventKind::Renewal, 0);
  q.compact(0, [](const EventQueue::Entry&) { return false; });
  EXPECT_EQ(q.size(), EventQueue::kCompactFrom - 1);
}

}  // namespace
