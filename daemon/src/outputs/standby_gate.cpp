#include "standby_gate.hpp"

#include <algorithm>

namespace kew::daemon {

StandbyGate::StandbyGate(std::size_t history, std::function<bool()> may_speak)
    : may_speak_(std::move(may_speak)), history_limit_(std::max<std::size_t>(history, 1)), open_(false) {}

StandbyGate::Passage StandbyGate::admit(const AlertEvent& event) {
  if (hot_standby()) {
    // Kept whether open or not: an instance that steps down and takes the lease back
    // sends again what its outbox had not published (JetStream keeps each seq once).
    history_.push_back(event);
    if (history_.size() > history_limit_) history_.pop_front();
  }
  const Passage passage = speak();
  return passage == Passage::Pass && event.seq <= floor_ ? Passage::Hold : passage;
}

StandbyGate::Passage StandbyGate::speak() {
  if (!open_) return Passage::Hold;
  // The lease thread may be stuck in a slow call, or the whole process stalled: speak
  // only while the last renewal the server took guarantees that nobody else can.
  if (hot_standby() && !may_speak_()) {
    open_ = false;
    return Passage::StepDown;
  }
  return Passage::Pass;
}

StandbyGate::Takeover StandbyGate::take_over(std::uint64_t published) {
  Takeover takeover;
  if (open_) return takeover;
  floor_ = std::max(floor_, published);
  open_ = true;
  if (!history_.empty() && history_.front().seq > floor_ + 1) takeover.lost_before = history_.front().seq;
  for (const AlertEvent& event : history_)
    if (event.seq > floor_) takeover.to_send.push_back(event);
  return takeover;
}

bool StandbyGate::step_down() {
  if (!open_) return false;
  open_ = false;
  return true;
}

}  // namespace kew::daemon
