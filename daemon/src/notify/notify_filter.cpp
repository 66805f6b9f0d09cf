#include "notify_filter.hpp"

#include <algorithm>
#include <cctype>

namespace kew::daemon {

bool matches_pattern(std::string_view pattern, std::string_view text) {
  // Iterative wildcard match: on a mismatch after a '*', the star takes one more character.
  std::size_t p = 0, t = 0, star = std::string_view::npos, resume = 0;
  const auto same = [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
  };
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || (pattern[p] != '*' && same(pattern[p], text[t])))) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      resume = t;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      t = ++resume;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

NotifyFilter::NotifyFilter(const NotifyConfig& config) : config_(config) {}

bool NotifyFilter::concerns(const AlertEvent& event) const {
  if (!config_.regions.empty() &&
      std::find(config_.regions.begin(), config_.regions.end(), event.region) == config_.regions.end())
    return false;
  if (config_.callsigns.empty() && config_.addresses.empty()) return true;
  for (const AlertParty* party : {&event.a, &event.b}) {
    for (const std::string& pattern : config_.callsigns)
      if (!party->callsign.empty() && matches_pattern(pattern, party->callsign)) return true;
    for (const std::string& pattern : config_.addresses)
      if (matches_pattern(pattern, party->id)) return true;
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
