#pragma once
// The kinetic engine's queue of scheduled events, earliest first (thesis ch. 6). An
// event that is descheduled stays queued: whoever scheduled it keeps the sequence number
// push() returned and recognises a popped entry as stale when its number is no longer
// the one on record. Descheduling is thus O(1); compact() drops the stale entries once
// they are the majority.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace kew::kinetic {

/// What a queued event does when its time comes.
enum class EventKind : std::uint8_t {
  None,         ///< nothing: in the engine's per-edge records only, never queued
  Failure,      ///< the certificate of an edge fails: the edge is flipped
  Renewal,      ///< an edge's window closes before its certificate fails: solved again
  TwinRelease,  ///< a twin may be far enough from its host to be reinserted
  Approach,     ///< the two ends of an edge come so close that one becomes a twin
  Drift,        ///< a point's kept model reaches τ from its latest report: replaced by it
};

class EventQueue {
 public:
  struct Entry {
    double time;            ///< s, on the engine's epoch
    std::uint64_t seq;      ///< from push(): > 0, unique, increasing in push order
    std::uint32_t subject;  ///< face, or point for TwinRelease and Drift
    std::uint8_t edge;      ///< edge 0..2 of the face (0 for TwinRelease and Drift)
    EventKind kind;
    std::uint16_t retries;  ///< times this failure popped before the exact predicate agreed
  };

  /// Queues an event at `time` (s, finite; one in the past simply pops first) and returns
  /// its sequence number. Entries pop by time, and entries at one time in push order, so
  /// that a run is deterministic whatever the heap's internal layout.
  std::uint64_t push(double time, std::uint32_t subject, std::uint8_t edge, EventKind kind, std::uint16_t retries);

  bool empty() const { return heap_.empty(); }
  /// Entries queued, stale ones included.
  std::size_t size() const { return heap_.size(); }
  /// The earliest entry. Requires !empty().
  const Entry& top() const { return heap_.front(); }
  /// Removes the earliest entry and returns it. Requires !empty().
  Entry pop();

  /// Drops every entry for which is_live(entry) is false, but only once they can be the
  /// majority: at least kCompactFrom entries queued and at most half of them among the
  /// `live` ones the caller knows to be scheduled. A check of two sizes when not due,
  /// O(size()) when due, so O(1) per push amortised. Pop order is unchanged.
  template <class IsLive>
  void compact(std::size_t live, IsLive&& is_live) {
    if (heap_.size() < kCompactFrom || heap_.size() < 2 * live) return;
    std::erase_if(heap_, [&](const Entry& e) { return !is_live(e); });
    std::make_heap(heap_.begin(), heap_.end(), Later{});
  }

  /// Below this many entries a queue is small enough to keep its stale ones.
  static constexpr std::size_t kCompactFrom = 1024;

 private:
  struct Later {
    bool operator()(const Entry& a, const Entry& b) const {
      return a.time > b.time || (a.time == b.time && a.seq > b.seq);
    }
  };

  std::vector<Entry> heap_;
  std::uint64_t next_seq_ = 1;
};

}  // namespace kew::kinetic
