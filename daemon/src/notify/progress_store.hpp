#pragma once
// Where a notifier shares how far its deliveries have come with the other instance of a
// hot-standby pair (design §5.10): the active writes its progress after each delivery,
// the standby reads it to forget what was delivered, and an instance taking over reads
// it before its first delivery, so no event is delivered twice across a takeover.

#include <optional>
#include <string>

#include "delivery_progress.hpp"

namespace kew::daemon {

class ProgressStore {
 public:
  virtual ~ProgressStore() = default;
  /// The progress last saved by any instance (an empty one when none was); nullopt, with
  /// `error` saying why, when the store cannot be read now. Blocks at most a few seconds.
  virtual std::optional<DeliveryProgress> load(std::string& error) = 0;
  /// Saves `progress`; false, with `error`, when the store cannot take it now.
  virtual bool save(const DeliveryProgress& progress, std::string& error) = 0;
};

}  // namespace kew::daemon
