#pragma once
// How far a notifier's deliveries have come (design §5.10): every event up to `through`,
// and the events above it in `also` (a coalesced message carries later events of its
// alert while earlier events of others still wait). Kept in the notifier's outbox file
// for a restart, and under hot standby in the pair's bucket for the next active.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kew::daemon {

struct DeliveryProgress {
  std::uint64_t through = 0;
  std::vector<std::uint64_t> also;  ///< ascending, each above `through`

  bool covers(std::uint64_t seq) const;
  /// {"through":N,"also":[…]}
  std::string to_json() const;
  /// nullopt when `text` is not such an object.
  static std::optional<DeliveryProgress> from_json(std::string_view text);
  /// What both say was delivered (another instance's progress and this one's).
  void merge(const DeliveryProgress& other);
};

}  // namespace kew::daemon
