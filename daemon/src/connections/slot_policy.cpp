#include "slot_policy.hpp"

#include <algorithm>
#include <unordered_map>

namespace kew::daemon {

namespace {

/// The longest-silent holder among those `pick` accepts; none when no silent one is.
template <class Pick>
std::optional<std::size_t> longest_silent(std::span<const SlotHolder> holders, Pick pick) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < holders.size(); ++i) {
    const SlotHolder& h = holders[i];
    if (!h.silent || !pick(h)) continue;
    if (!best || h.silent_since < holders[*best].silent_since) best = i;
  }
  return best;
}

}  // namespace

std::optional<std::size_t> connection_to_evict(std::span<const SlotHolder> holders, std::string_view address,
                                               std::size_t silent_per_address, bool every_slot_taken) {
  const auto same_address = [address](const SlotHolder& h) { return h.address == address; };
  const auto held = static_cast<std::size_t>(
      std::count_if(holders.begin(), holders.end(), [&](const SlotHolder& h) { return h.silent && same_address(h); }));
  if (held >= std::max<std::size_t>(silent_per_address, 1)) return longest_silent(holders, same_address);
  if (!every_slot_taken) return std::nullopt;
  // The longest-silent connection of the address holding the most silent ones; between
  // addresses holding as many, the one silent longest.
  std::unordered_map<std::string_view, std::size_t> silent_by_address;
  for (const SlotHolder& h : holders)
    if (h.silent) ++silent_by_address[h.address];
  std::optional<std::size_t> best;
  std::size_t best_held = 0;
  for (std::size_t i = 0; i < holders.size(); ++i) {
    const SlotHolder& h = holders[i];
    if (!h.silent) continue;
    const std::size_t held_by_its_address = silent_by_address[h.address];
    if (!best || held_by_its_address > best_held ||
        (held_by_its_address == best_held && h.silent_since < holders[*best].silent_since)) {
      best = i;
      best_held = held_by_its_address;
    }
  }
  return best;
}

}  // namespace kew::daemon
