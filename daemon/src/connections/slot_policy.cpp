#include "slot_policy.hpp"

#include <algorithm>

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
  return longest_silent(holders, [](const SlotHolder&) { return true; });
}

}  // namespace kew::daemon
