#include "notify_filter.hpp"

#include <algorithm>
#include "kew/util/wildcard.hpp"

namespace kew::daemon {

NotifyFilter::NotifyFilter(const NotifyConfig& config) : config_(config) {}

bool NotifyFilter::concerns(const AlertEvent& event) const {
  if (std::find(config_.kinds.begin(), config_.kinds.end(), event.kind) == config_.kinds.end()) return false;
  const bool area = event.kind == AlertKind::Apw;
  if (!area && !config_.regions.empty() &&
      std::find(config_.regions.begin(), config_.regions.end(), event.region) == config_.regions.end())
    return false;
  if (config_.callsigns.empty() && config_.addresses.empty() && config_.volumes.empty()) return true;
  if (area)
    for (const std::string& pattern : config_.volumes)
      if (util::matches_wildcard(pattern, event.volume)) return true;
  // An area warning's b is empty: an address pattern such as "*" would match it.
  for (const AlertParty* party : {&event.a, &event.b}) {
    if (party->id.empty()) continue;
    for (const std::string& pattern : config_.callsigns)
      if (!party->callsign.empty() && util::matches_wildcard(pattern, party->callsign)) return true;
    for (const std::string& pattern : config_.addresses)
      if (util::matches_wildcard(pattern, party->id)) return true;
  }
  return false;
}

bool NotifyFilter::passes(NotifyState state) const {
  return std::find(config_.states.begin(), config_.states.end(), state) != config_.states.end();
}

std::optional<NotifyState> NotifyFilter::classify(const AlertEvent& event) {
  const bool serious = event.severity >= config_.min_severity && concerns(event);
  if (event.state == AlertState::End) {
    const auto it = alerts_.find(event.id);
    // An alert not followed in this run may have been announced before a restart: its
    // end is told when it would have been.
    const bool announced = it == alerts_.end() ? serious : it->second.announced;
    if (it != alerts_.end()) alerts_.erase(it);
    if (announced && passes(NotifyState::Ended)) return NotifyState::Ended;
    return std::nullopt;
  }
  Followed& followed = alerts_[event.id];
  const Severity before = followed.highest;
  const bool reached_before = followed.reached;
  followed.highest = std::max(followed.highest, event.severity);
  if (!serious) return std::nullopt;
  followed.reached = true;
  NotifyState state = NotifyState::Updated;
  if (event.state == AlertState::New) state = NotifyState::New;
  else if (!reached_before || event.severity > before) state = NotifyState::Escalated;
  if (!passes(state)) return std::nullopt;
  followed.announced = true;
  return state;
}

}  // namespace kew::daemon
