#include "leader_lease.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "repeated_failure.hpp"
#include "stream_replicas.hpp"

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
      // Every call answered within half the TTL, or given up: a slow server must not
      // keep the thread long past the moment it has to step down (may_speak() covers
      // the rest).
      connection_(config.servers, config.name + " lease",
                  [](std::string_view event) { spdlog::info("[nats] lease: {}", event); }, 1.0,
                  config.lease_ttl_s / 2.0) {
  thread_ = std::thread([this] { run(); });
}

LeaderLease::~LeaderLease() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  stop_.notify_all();
  thread_.join();
  // The standby need not wait for the TTL; but a lease that may have passed to another
  // instance is not this one's to delete.
  if (bucket_ && active_ && may_speak()) {
    kvStore_Delete(bucket_, config_.lease_key.c_str());
    spdlog::info("[nats] lease {} given up by {}", config_.lease_key, instance_);
  }
  kvStore_Destroy(bucket_);
}

bool LeaderLease::may_speak() const {
  const auto now = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
  return active_ && now < speak_until_ns_.load();
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
  // On file: a server restart keeps the bucket (a memory one would be gone with it).
  kv.StorageType = js_FileStorage;
  kv.Replicas = config_.replicas;
  if (js_CreateKeyValue(&bucket_, connection_.jetstream(), &kv) == NATS_OK) return true;
  // Made by another instance (or an earlier run) with its own settings; its replicas
  // follow [nats] replicas.
  if (js_KeyValue(&bucket_, connection_.jetstream(), config_.lease_bucket.c_str()) != NATS_OK) return false;
  const std::string scaled = nats::ensure_replicas(connection_.jetstream(), nats::bucket_stream(config_.lease_bucket),
                                                   config_.replicas);
  if (!scaled.empty()) spdlog::warn("[nats] lease: {}", scaled);
  return true;
}

void LeaderLease::forget_bucket_if_gone(natsStatus status) {
  if (status != NATS_NO_RESPONDERS && status != NATS_NOT_FOUND) return;
  kvStore_Destroy(bucket_);
  bucket_ = nullptr;
}

std::optional<std::uint64_t> LeaderLease::last_published_seq() {
  if (config_.stream.empty()) return 0;
  jsStreamInfo* info = nullptr;
  if (js_GetStreamInfo(&info, connection_.jetstream(), config_.stream.c_str(), nullptr, nullptr) != NATS_OK)
    return std::nullopt;
  const std::uint64_t last = info->State.LastSeq;
  jsStreamInfo_Destroy(info);
  if (last == 0) return 0;
  try {
    return nats::kept_seq(connection_.jetstream(), config_.stream, last);
  } catch (const nats::NatsError&) {
    return std::nullopt;
  }
}

void LeaderLease::run() {
  RepeatedFailure failures("[nats] lease");
  const Clock::duration period = seconds(config_.lease_ttl_s / 4.0);
  const Clock::duration ttl = seconds(config_.lease_ttl_s);
  const auto speak_until = [&](Clock::time_point sent) {
    speak_until_ns_ =
        std::chrono::duration_cast<std::chrono::nanoseconds>((sent + ttl - period).time_since_epoch()).count();
  };
  std::uint64_t revision = 0;
  do {
    if (!bind_bucket()) {
      if (connection_.connected())
        failures.report(fmt::format("cannot open the key-value bucket {}", config_.lease_bucket));
      continue;
    }
    const Clock::time_point sent = Clock::now();
    std::uint64_t taken = 0;  // the client zeroes its output on failure: never the revision itself
    if (!active_) {
      const natsStatus s = kvStore_Create(&taken, bucket_, config_.lease_key.c_str(), instance_.data(),
                                          static_cast<int>(instance_.size()));
      if (s != NATS_OK) {
        forget_bucket_if_gone(s);
        continue;  // held by another instance, or no server: try again next period
      }
      const std::optional<std::uint64_t> last = last_published_seq();
      if (!last) {
        // Without the floor a takeover would send again what the last active sent.
        kvStore_Delete(bucket_, config_.lease_key.c_str());
        failures.report("took the lease but could not read the stream's last seq: let go, trying again");
        continue;
      }
      revision = taken;
      renewed_ = sent;
      speak_until(sent);
      if (Clock::now() >= sent + ttl - period) {
        kvStore_Delete(bucket_, config_.lease_key.c_str());
        continue;  // the calls took so long that the lease may already be another's
      }
      active_ = true;
      failures.recovered("lease taken");
      spdlog::info("[nats] {} holds the lease {}: active (the stream's last seq is {})", instance_,
                   config_.lease_key, *last);
      handlers_.on_acquired(*last);
      continue;
    }
    natsStatus s = kvStore_Update(&taken, bucket_, config_.lease_key.c_str(), instance_.data(),
                                  static_cast<int>(instance_.size()), revision);
    if (s != NATS_OK) {
      // The update may have been stored with its answer lost: then the key still says
      // this instance, at a newer revision.
      kvEntry* entry = nullptr;
      if (kvStore_Get(&entry, bucket_, config_.lease_key.c_str()) == NATS_OK) {
        if (instance_ == kvEntry_ValueString(entry)) {
          taken = kvEntry_Revision(entry);
          s = taken > revision ? NATS_OK : s;
        }
        kvEntry_Destroy(entry);
      }
    }
    if (s == NATS_OK) {
      revision = taken;
      renewed_ = sent;
      speak_until(sent);
    } else {
      forget_bucket_if_gone(s);
      if (Clock::now() - renewed_ >= ttl - period) {
        // The key expires on the server lease_ttl_s after the last renewal reached it;
        // this instance stops speaking a period earlier, before another can hold it.
        active_ = false;
        spdlog::error("[nats] {} could not renew the lease {} ({}): standby", instance_, config_.lease_key,
                      nats::describe(s));
        handlers_.on_lost();
      }
    }
  } while (!wait(period));
}

}  // namespace kew::daemon
