#include "fan_out.hpp"

#include <spdlog/spdlog.h>

namespace kew::daemon {
namespace {

template <class Encode>
SharedLine encode(Encode&& write) {
  auto line = std::make_shared<std::string>();
  write(*line);
  return line;
}

}  // namespace

FanOut::FanOut(StandbyGate gate, RoleHandler on_role) : gate_(std::move(gate)), on_role_(std::move(on_role)) {}

void FanOut::start() {
  for (const auto& output : outputs_) {
    if (const std::string what = output->describe(); !what.empty()) spdlog::info("{}", what);
    output->role_changed(gate_.open());
  }
}

void FanOut::alert(const AlertEvent& event) {
  const StandbyGate::Passage passage = gate_.admit(event);
  const SharedLine line = encode([&](std::string& out) { protocol::append_alert_json(out, event, event.seq); });
  send_alert(event, line, event.seq > journal_floor_, passage == StandbyGate::Passage::Pass);
  if (passage == StandbyGate::Passage::StepDown) tell_role(false);
}

void FanOut::send_alert(const AlertEvent& event, const SharedLine& line, bool to_journal, bool to_others) {
  for (const auto& output : outputs_) {
    if (output->audience() == Audience::Journal ? to_journal : to_others) output->alert(event, line);
  }
}

void FanOut::acknowledgement(const protocol::Acknowledgement& ack, std::uint64_t seq) {
  // A standby's operators acknowledge on the active.
  if (const StandbyGate::Passage passage = gate_.speak(); passage != StandbyGate::Passage::Pass) {
    if (passage == StandbyGate::Passage::StepDown) tell_role(false);
    return;
  }
  const SharedLine line = encode([&](std::string& out) { protocol::append_ack_json(out, ack, seq); });
  for (const auto& output : outputs_) output->acknowledgement(ack, seq, line);
}

void FanOut::alive(const AliveEvent& alive) {
  const StandbyGate::Passage passage = gate_.speak();
  if (passage == StandbyGate::Passage::StepDown) tell_role(false);
  const SharedLine line = encode([&](std::string& out) { protocol::append_alive_json(out, alive.status, alive.seq); });
  for (const auto& output : outputs_) {
    if (output->audience() == Audience::OwnClients ||
        (output->audience() == Audience::Shared && passage == StandbyGate::Passage::Pass))
      output->alive(alive, line);
  }
}

std::size_t FanOut::take_over(std::uint64_t published, std::span<const AlertEvent> active, std::uint64_t seq) {
  const bool was_open = gate_.open();
  StandbyGate::Takeover takeover = gate_.take_over(published);
  if (was_open) return 0;
  if (takeover.lost_before)
    spdlog::error("active now, but events {} to {} are neither in the stream nor kept here: they are lost",
                  gate_.floor() + 1, takeover.lost_before - 1);
  for (const AlertEvent& event : takeover.to_send) {
    const SharedLine line = encode([&](std::string& out) { protocol::append_alert_json(out, event, event.seq); });
    send_alert(event, line, false, true);
  }
  // This instance's own clients saw nothing of the alerts the previous active sent.
  for (const auto& output : outputs_)
    if (output->audience() == Audience::OwnClients) output->resynchronise(active, seq);
  tell_role(true);
  return takeover.to_send.size();
}

bool FanOut::step_down() {
  if (!gate_.step_down()) return false;
  tell_role(false);
  return true;
}

void FanOut::tell_role(bool active) {
  for (const auto& output : outputs_) output->role_changed(active);
  if (on_role_) on_role_(active);
}

void FanOut::report(protocol::ServiceStatistics& statistics) const {
  for (const auto& output : outputs_) output->report(statistics);
}

}  // namespace kew::daemon
