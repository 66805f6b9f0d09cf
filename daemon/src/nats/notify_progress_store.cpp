#include "notify_progress_store.hpp"

#include <spdlog/spdlog.h>

namespace kew::daemon {

NatsProgressStore::NatsProgressStore(const NatsConfig& config, const std::string& notifier)
    : config_(config),
      key_(config.lease_key + ".notify." + notifier),
      connection_(config.servers, config.name + " notify " + notifier,
                  [notifier](std::string_view event) { spdlog::info("[nats] notify {}: {}", notifier, event); }) {}

NatsProgressStore::~NatsProgressStore() { kvStore_Destroy(bucket_); }

bool NatsProgressStore::bind(std::string& error) {
  if (bucket_) return true;
  if (!connection_.connected()) {
    error = "no NATS server answers";
    return false;
  }
  std::string scaled;
  bucket_ = nats::bind_key_value(connection_.jetstream(), config_.pair_bucket, 0.0, config_.replicas, scaled);
  if (!scaled.empty()) spdlog::warn("[nats] notify: {}", scaled);
  if (!bucket_) error = "the bucket " + config_.pair_bucket + " cannot be bound";
  return bucket_ != nullptr;
}

std::optional<DeliveryProgress> NatsProgressStore::load(std::string& error) {
  if (!bind(error)) return std::nullopt;
  kvEntry* entry = nullptr;
  const natsStatus got = kvStore_Get(&entry, bucket_, key_.c_str());
  if (got == NATS_NOT_FOUND) return DeliveryProgress{};
  if (got != NATS_OK) {
    error = nats::describe(got);
    if (got == NATS_NO_RESPONDERS) {
      kvStore_Destroy(bucket_);
      bucket_ = nullptr;
    }
    return std::nullopt;
  }
  const std::string text(kvEntry_ValueString(entry));
  kvEntry_Destroy(entry);
  std::optional<DeliveryProgress> progress = DeliveryProgress::from_json(text);
  if (!progress) error = config_.pair_bucket + "." + key_ + " is unreadable: " + text;
  return progress;
}

bool NatsProgressStore::save(const DeliveryProgress& progress, std::string& error) {
  if (!bind(error)) return false;
  std::uint64_t revision = 0;
  const std::string text = progress.to_json();
  const natsStatus put = kvStore_PutString(&revision, bucket_, key_.c_str(), text.c_str());
  if (put == NATS_OK) return true;
  error = nats::describe(put);
  return false;
}

}  // namespace kew::daemon
