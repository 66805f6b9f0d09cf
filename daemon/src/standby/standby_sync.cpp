#include "standby_sync.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace kew::daemon {

StandbySync::StandbySync(std::uint64_t origin_last_seq) : own_seq_(origin_last_seq), active_seq_(origin_last_seq) {}

StandbySync::Identity StandbySync::identity(const AlertEvent& event) {
  return {event.id, event.number, event.state, event.severity, event.end_reason};
}

std::string StandbySync::describe(std::uint64_t seq, const Identity& identity) {
  return fmt::format("seq {} {} #{} {} {}{}", seq, identity.id, identity.number, to_string(identity.state),
                     to_string(identity.severity),
                     identity.reason == AlertEndReason::None ? "" : fmt::format(" ({})", to_string(identity.reason)));
}

void StandbySync::seed_open(const std::vector<AlertEvent>& open) {
  for (const AlertEvent& event : open) open_on_active_[event.id] = event;
}

void StandbySync::active_alert(const AlertEvent& event) {
  if (event.seq <= active_seq_) return;  // read again after a reconnection
  active_seq_ = event.seq;
  if (event.state == AlertState::End) open_on_active_.erase(event.id);
  else open_on_active_[event.id] = event;
  const Identity theirs = identity(event);
  if (const auto mine = own_ahead_.find(event.seq); mine != own_ahead_.end()) {
    compare(event.seq, mine->second, theirs);
    own_ahead_.erase(own_ahead_.begin(), std::next(mine));
  } else if (event.seq > own_seq_) {
    active_ahead_.emplace(event.seq, theirs);
  }
  judge();
}

void StandbySync::active_acknowledgement(std::uint64_t seq, std::vector<std::string> ids) {
  acknowledgements_.emplace_back(seq, std::move(ids));
}

void StandbySync::stream_read_up_to(std::uint64_t seq) {
  stream_read_to_ = std::max(seq, active_seq_);
  judge();
}

void StandbySync::own_alert(const AlertEvent& event) {
  own_seq_ = event.seq;
  const Identity mine = identity(event);
  if (const auto theirs = active_ahead_.find(event.seq); theirs != active_ahead_.end()) {
    compare(event.seq, mine, theirs->second);
    active_ahead_.erase(active_ahead_.begin(), std::next(theirs));
  } else if (event.seq > active_seq_) {
    own_ahead_.emplace(event.seq, mine);
  }
  judge();
}

std::vector<std::vector<std::string>> StandbySync::due_acknowledgements() {
  std::vector<std::vector<std::string>> due;
  // An acknowledgement published after the active's event `seq` applies between that
  // event and the next: once this instance has computed `seq` itself.
  while (!acknowledgements_.empty() && acknowledgements_.front().first <= own_seq_) {
    due.push_back(std::move(acknowledgements_.front().second));
    acknowledgements_.pop_front();
  }
  return due;
}

std::vector<AlertEvent> StandbySync::open_on_active() const {
  std::vector<AlertEvent> open;
  open.reserve(open_on_active_.size());
  for (const auto& [id, event] : open_on_active_) open.push_back(event);
  std::sort(open.begin(), open.end(), [](const AlertEvent& a, const AlertEvent& b) { return a.seq < b.seq; });
  return open;
}

void StandbySync::compare(std::uint64_t seq, const Identity& mine, const Identity& theirs) {
  if (!(mine == theirs))
    depart(fmt::format("the active sent {}, this instance computed {}", describe(seq, theirs), describe(seq, mine)));
}

void StandbySync::depart(std::string why) {
  if (state_ == State::OutOfStep) return;
  state_ = State::OutOfStep;
  departure_ = std::move(why);
}

void StandbySync::judge() {
  if (state_ != State::Syncing || !stream_read_to_) return;
  // Caught up: this instance has computed every event the stream held when it was read.
  if (own_seq_ >= *stream_read_to_) state_ = State::InStep;
}

}  // namespace kew::daemon
