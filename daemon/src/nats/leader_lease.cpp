#include "leader_lease.hpp"

#include <cstdlib>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "repeated_failure.hpp"

namespace kew::daemon {

namespace {

using Clock = std::chrono::steady_clock;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

LeaderLease::LeaderLease(const NatsConfig& config, std::string instance, Handlers handlers)
    : config_(config),
      instance_(std::move(instance)),
      handlers_(std::move(handlers)),
      connection_(config.url, config.name + " lease",
                  [](std::string_view event) { spdlog::info("[nats] lease: {}", event); }) {
  thread_ = std::thread([this] { run(); });
}

LeaderLease::~LeaderLease() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  stop_.notify_all();
  thread_.join();
  if (bucket_ && active_) {
    // The standby need not wait for the TTL.
    kvStore_Delete(bucket_, config_.lease_key.c_str());
    spdlog::info("[nats] lease {} given up by {}", config_.lease_key, instance_);
  }
  kvStore_Destroy(bucket_);
}

bool LeaderLease::wait(Clock::duration period) {
  std::unique_lock lock(mutex_);
  stop_.wait_for(lock, period, [this] { return stopping_; });
  return stopping_;
}

bool LeaderLease::bind_bucket() {
  if (bucket_) return true;
  if (!connection_.connected()) return false;
  kvConfig kv;
  kvConfig_Init(&kv);
  kv.Bucket = config_.lease_bucket.c_str();
  kv.History = 1;
  kv.TTL = static_cast<std::int64_t>(config_.lease_ttl_s * 1e9);
  kv.StorageType = js_MemoryStorage;  // a lease outlives no server restart: it is renewed anyway
  if (js_CreateKeyValue(&bucket_, connection_.jetstream(), &kv) == NATS_OK) return true;
  // Made by another instance (or an earlier run) with its own settings.
  return js_KeyValue(&bucket_, connection_.jetstream(), config_.lease_bucket.c_str()) == NATS_OK;
}

std::uint64_t LeaderLease::last_published_seq() {
  if (config_.stream.empty()) return 0;
  jsStreamInfo* info = nullptr;
  if (js_GetStreamInfo(&info, connection_.jetstream(), config_.stream.c_str(), nullptr, nullptr) != NATS_OK) return 0;
  const std::uint64_t last = info->State.LastSeq;
  jsStreamInfo_Destroy(info);
  if (last == 0) return 0;
  natsMsg* message = nullptr;
  if (js_GetMsg(&message, connection_.jetstream(), config_.stream.c_str(), last, nullptr, nullptr) != NATS_OK) return 0;
  const char* value = nullptr;
  std::uint64_t seq = 0;
  if (natsMsgHeader_Get(message, nats::kSeqHeader, &value) == NATS_OK) seq = std::strtoull(value, nullptr, 10);
  natsMsg_Destroy(message);
  return seq;
}

void LeaderLease::run() {
  RepeatedFailure failures("[nats] lease");
  const Clock::duration period = seconds(config_.lease_ttl_s / 4.0);
  const Clock::duration ttl = seconds(config_.lease_ttl_s);
  std::uint64_t revision = 0;
  Clock::time_point renewed{};
  do {
    if (!bind_bucket()) {
      if (connection_.connected())
        failures.report(fmt::format("cannot open the key-value bucket {}", config_.lease_bucket));
    } else if (!active_) {
      const natsStatus s = kvStore_Create(&revision, bucket_, config_.lease_key.c_str(), instance_.data(),
                                          static_cast<int>(instance_.size()));
      if (s == NATS_OK) {
        renewed = Clock::now();
        const std::uint64_t last = last_published_seq();
        active_ = true;
        spdlog::info("[nats] {} holds the lease {}: active (the stream's last seq is {})", instance_,
                     config_.lease_key, last);
        handlers_.on_acquired(last);
      }
    } else {
      const natsStatus s = kvStore_Update(&revision, bucket_, config_.lease_key.c_str(), instance_.data(),
                                          static_cast<int>(instance_.size()), revision);
      if (s == NATS_OK) {
        renewed = Clock::now();
      } else if (Clock::now() - renewed >= ttl - period) {
        // The key expires on the server lease_ttl_s after the last renewal reached it;
        // this instance stops speaking a check earlier, before another can hold it.
        active_ = false;
        spdlog::error("[nats] {} could not renew the lease {} for {} s ({}): standby", instance_, config_.lease_key,
                      config_.lease_ttl_s, nats::describe(s));
        handlers_.on_lost();
      }
    }
  } while (!wait(period));
}

}  // namespace kew::daemon
