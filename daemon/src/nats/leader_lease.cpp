#include "leader_lease.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "repeated_failure.hpp"
#include "stream_setup.hpp"

namespace kew::daemon {

namespace {

using Clock = std::chrono::steady_clock;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

LeaderLease::LeaderLease(const NatsConfig& config, std::string instance, Handlers handlers,
                         std::shared_ptr<SpeakingRight> right)
    : config_(config),
      instance_(std::move(instance)),
      handlers_(std::move(handlers)),
      right_(std::move(right)),
      // Every call answered within half the TTL, or given up: a slow server must not
      // keep the thread long past the moment it has to step down (may_speak() covers
      // the rest).
      connection_(
          config.servers, config.name + " lease", [](std::string_view event) { spdlog::info("[nats] lease: {}", event); },
          1.0, config.lease_ttl_s / 2.0, [this](bool up) { on_link(up); }) {
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
  if (bucket_ && active_ && right_->may_publish()) {
    kvStore_Delete(bucket_, config_.lease_key.c_str());
    spdlog::info("[nats] lease {} given up by {}", config_.lease_key, instance_);
  }
  kvStore_Destroy(bucket_);
}

bool LeaderLease::wait(Clock::duration period) {
  std::unique_lock lock(mutex_);
  stop_.wait_for(lock, period, [this] { return stopping_ || bus_back_; });
  bus_back_ = false;
  return stopping_;
}

void LeaderLease::on_link(bool up) {
  if (!up) {
    right_->bus_lost(Clock::now());
    const std::lock_guard lock(mutex_);
    link_lost_ = true;
    return;
  }
  {
    const std::lock_guard lock(mutex_);
    bus_back_ = true;
    if (link_lost_) link_back_at_ = Clock::now();
    link_lost_ = false;
  }
  stop_.notify_all();
}

bool LeaderLease::link_up() {
  if (!connection_.connected()) return false;
  const std::lock_guard lock(mutex_);
  return !link_lost_;
}

bool LeaderLease::yielding_to_a_returning_active() {
  const std::lock_guard lock(mutex_);
  return link_back_at_ && Clock::now() - *link_back_at_ < seconds(config_.lease_ttl_s);
}

LeaderLease::Retake LeaderLease::take_again(std::uint64_t& taken, Clock::time_point& sent) {
  sent = Clock::now();
  const natsStatus s = kvStore_Create(&taken, bucket_, config_.lease_key.c_str(), instance_.data(),
                                      static_cast<int>(instance_.size()));
  if (s == NATS_OK) return Retake::Taken;
  kvEntry* entry = nullptr;
  const natsStatus got = kvStore_Get(&entry, bucket_, config_.lease_key.c_str());
  const bool another = got == NATS_OK && instance_ != kvEntry_ValueString(entry);
  kvEntry_Destroy(entry);
  if (another) return Retake::Another;
  forget_bucket_if_gone(s);
  return Retake::NoAnswer;
}

bool LeaderLease::bind_bucket() {
  if (bucket_) return true;
  if (!connection_.connected()) return false;
  // The key expires lease_ttl_s after its last renewal.
  std::string scaled;
  bucket_ = nats::bind_key_value(connection_.jetstream(), config_.lease_bucket, config_.lease_ttl_s, config_.replicas,
                                 scaled);
  if (!scaled.empty()) spdlog::warn("[nats] lease: {}", scaled);
  return bucket_ != nullptr;
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

bool LeaderLease::free_for_a_ttl() {
  kvEntry* entry = nullptr;
  const natsStatus s = kvStore_Get(&entry, bucket_, config_.lease_key.c_str());
  kvEntry_Destroy(entry);
  if (s != NATS_NOT_FOUND) {
    free_since_.reset();  // held (or the server did not tell)
    return false;
  }
  const Clock::time_point now = Clock::now();
  if (!free_since_) free_since_ = now;
  return now - *free_since_ >= seconds(config_.lease_ttl_s);
}

void LeaderLease::run() {
  RepeatedFailure failures("[nats] lease");
  const Clock::duration period = seconds(config_.lease_ttl_s / 4.0);
  const Clock::duration ttl = seconds(config_.lease_ttl_s);
  const auto speak_until = [&](std::uint64_t held, Clock::time_point sent) { right_->hold(held, sent + ttl - period); };
  std::uint64_t revision = 0;  // the key's, renewed
  std::uint64_t holding = 0;   // the key's when taken
  do {
    if (!bind_bucket()) {
      if (connection_.connected())
        failures.report(fmt::format("cannot open the key-value bucket {}", config_.lease_bucket));
      continue;
    }
    Clock::time_point sent = Clock::now();
    std::uint64_t taken = 0;  // the client zeroes its output on failure: never the revision itself
    if (!active_) {
      const Readiness readiness = handlers_.readiness ? handlers_.readiness() : Readiness::InStep;
      if (readiness == Readiness::NotReady) continue;
      if (!link_up() || yielding_to_a_returning_active()) {
        free_since_.reset();
        continue;
      }
      if (readiness == Readiness::Unsynced) {
        if (!free_for_a_ttl()) continue;
        spdlog::warn("[nats] the lease {} has been free for {} s and this instance is not in step with the pair: "
                     "taking it unsynced",
                     config_.lease_key, config_.lease_ttl_s);
      } else {
        free_since_.reset();
      }
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
      // The fencing token of this holding: the key's revision when it was taken, above
      // every earlier holding's (a bucket's revisions only grow).
      holding = taken;
      renewed_ = sent;
      speak_until(holding, sent);
      if (Clock::now() >= sent + ttl - period) {
        right_->release();
        kvStore_Delete(bucket_, config_.lease_key.c_str());
        continue;  // the calls took so long that the lease may already be another's
      }
      active_ = true;
      failures.recovered("lease taken");
      spdlog::info("[nats] {} holds the lease {}: active (the stream's last seq is {}; fencing token {})",
                   instance_, config_.lease_key, *last, holding);
      handlers_.on_acquired(*last);
      continue;
    }
    if (right_->lapsed()) {
      // The outputs found the holding not vouching (a stall, a slow answer) and shut:
      // renewing it would keep the lease with nobody speaking. Let it expire; an instance
      // in step (this one too) takes it then.
      active_ = false;
      right_->release();
      spdlog::error("[nats] {} gives the lease {} up: its outputs stopped when the last renewal stopped vouching "
                    "for it; standby",
                    instance_, config_.lease_key);
      handlers_.on_lost();
      continue;
    }
    natsStatus s = link_up() ? kvStore_Update(&taken, bucket_, config_.lease_key.c_str(), instance_.data(),
                                              static_cast<int>(instance_.size()), revision)
                             : NATS_CONNECTION_DISCONNECTED;
    const char* lost = nullptr;  // the server's word that the holding is over: why
    if (s != NATS_OK && s != NATS_CONNECTION_DISCONNECTED) {
      // The update may have been stored with its answer lost: then the key still says
      // this instance, at a newer revision.
      kvEntry* entry = nullptr;
      const natsStatus got = kvStore_Get(&entry, bucket_, config_.lease_key.c_str());
      if (got == NATS_OK) {
        if (instance_ == kvEntry_ValueString(entry)) {
          taken = kvEntry_Revision(entry);
          s = taken > revision ? NATS_OK : s;
        } else {
          lost = "another instance holds it";
        }
        kvEntry_Destroy(entry);
      } else if (got == NATS_NOT_FOUND) {
        lost = "it expired";
      }
    }
    if (lost != nullptr && right_->bus_away()) {
      // The key expired on the servers while none answered: unless another instance
      // has taken it since, the same holding goes on under the key taken again (a new,
      // higher fencing token); the servers not answering yet, it stays away.
      switch (take_again(taken, sent)) {
        case Retake::Taken:
          holding = taken;
          s = NATS_OK;
          lost = nullptr;
          spdlog::warn("[nats] {} took the lease {} again when the bus came back (fencing token {})", instance_,
                       config_.lease_key, holding);
          break;
        case Retake::NoAnswer:
          lost = nullptr;
          break;
        case Retake::Another:
          lost = "another instance took it when the bus came back";
          break;
      }
    }
    if (s == NATS_OK) {
      failures.recovered("lease renewed");
      revision = taken;
      renewed_ = sent;
      speak_until(holding, sent);
    } else {
      forget_bucket_if_gone(s);
      // No answer (the key's stream electing a leader, every server away): nobody can
      // take the key meanwhile either, as when the connection itself is lost.
      if (lost == nullptr && (s == NATS_TIMEOUT || s == NATS_NO_RESPONDERS || s == NATS_CONNECTION_DISCONNECTED))
        right_->bus_lost(sent);
      if (lost == nullptr && right_->bus_away()) {
        // Nobody can take the key while no server answers: the outputs that need no bus
        // go on; NATS publication waits for the renewal (SpeakingRight::may_publish).
        failures.report(fmt::format("no NATS server answers ({}): still active for the outputs that need no bus",
                                    nats::describe(s)));
        continue;
      }
      // A stalled process may wake with its clock telling little time has passed (a
      // paused virtual machine): the server's word ends the holding at once.
      if (lost != nullptr || Clock::now() - renewed_ >= ttl - period) {
        // The key expires on the server lease_ttl_s after the last renewal reached it;
        // this instance stops speaking a period earlier, before another can hold it.
        active_ = false;
        right_->release();
        spdlog::error("[nats] {} could not renew the lease {} ({}): standby", instance_, config_.lease_key,
                      lost != nullptr ? lost : nats::describe(s));
        handlers_.on_lost();
      }
    }
  } while (!wait(period));
}

}  // namespace kew::daemon
