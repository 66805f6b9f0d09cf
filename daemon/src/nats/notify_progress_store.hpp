#pragma once
// A notifier's progress shared by a hot-standby pair (design §5.10): a value under
// `<lease_key>.notify.<name>` in the pair's bucket (`pair_bucket`, on file, no TTL),
// through a connection of its own, used from the notifier's thread.

#include <string>

#include "../notify/progress_store.hpp"
#include "kew/daemon/config.hpp"
#include "nats_connection.hpp"

namespace kew::daemon {

class NatsProgressStore final : public ProgressStore {
 public:
  NatsProgressStore(const NatsConfig& config, const std::string& notifier);
  ~NatsProgressStore() override;
  NatsProgressStore(const NatsProgressStore&) = delete;
  NatsProgressStore& operator=(const NatsProgressStore&) = delete;

  std::optional<DeliveryProgress> load(std::string& error) override;
  bool save(const DeliveryProgress& progress, std::string& error) override;

 private:
  bool bind(std::string& error);

  NatsConfig config_;
  std::string key_;
  nats::NatsConnection connection_;
  kvStore* bucket_ = nullptr;
};

}  // namespace kew::daemon
