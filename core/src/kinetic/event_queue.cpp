#include "kew/kinetic/event_queue.hpp"

#include "kew/util/gentle_growth.hpp"

namespace kew::kinetic {

std::uint64_t EventQueue::push(double time, std::uint32_t subject, std::uint8_t edge, EventKind kind,
                               std::uint16_t retries) {
  const std::uint64_t seq = next_seq_++;
  util::push_back_gently(heap_, Entry{time, seq, subject, edge, kind, retries});
  std::push_heap(heap_.begin(), heap_.end(), Later{});
  return seq;
}

EventQueue::Entry EventQueue::pop() {
  std::pop_heap(heap_.begin(), heap_.end(), Later{});
  const Entry e = heap_.back();
  heap_.pop_back();
  return e;
}

}  // namespace kew::kinetic
