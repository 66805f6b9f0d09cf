#include "pair_follower.hpp"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "checkpoint_store.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/util/clocks.hpp"
#include "repeated_failure.hpp"

namespace kew::daemon {

namespace {

constexpr std::int64_t kWaitMs = 200;  // a read waits this long, then looks at stopping_
constexpr auto kRetryPeriod = std::chrono::milliseconds(500);

using Subscription = std::unique_ptr<natsSubscription, decltype(&natsSubscription_Destroy)>;

}  // namespace

PairFollower::PairFollower(const NatsConfig& config, std::string feed_stream, std::string instance,
                           std::uint64_t last_seq, std::uint16_t next_number, Handlers handlers)
    : config_(config),
      feed_stream_(std::move(feed_stream)),
      instance_(std::move(instance)),
      last_seq_(last_seq),
      next_number_(next_number),
      handlers_(std::move(handlers)),
      connection_(config.servers, config.name + " pair",
                  [](std::string_view event) { spdlog::info("[nats] pair: {}", event); }) {
  thread_ = std::thread([this] { run(); });
}

PairFollower::~PairFollower() {
  stopping_ = true;
  thread_.join();
  kvStore_Destroy(bucket_);
}

bool PairFollower::sleep_unless_stopping() {
  std::this_thread::sleep_for(kRetryPeriod);
  return !stopping_;
}

void PairFollower::run() {
  RepeatedFailure failures("[nats] pair");
  std::optional<PairOrigin> found;
  while (!stopping_) {
    found = origin();
    if (found) break;
    if (connection_.connected()) failures.report(fmt::format("cannot read or write the pair's origin in {}",
                                                             config_.pair_bucket));
    if (!sleep_unless_stopping()) return;
  }
  if (!found) return;
  failures.recovered("origin read");
  PairOrigin start = *found;
  std::shared_ptr<const PairCheckpoint> checkpoint = handlers_.usable ? latest_checkpoint(start) : nullptr;
  if (checkpoint) {
    start.feed_seq = checkpoint->feed_seq + 1;
    start.alerts_seq = checkpoint->alerts_seq;
    start.last_seq = checkpoint->last_seq;
  }
  handlers_.on_origin(start, checkpoint);
  follow(start);
}

std::shared_ptr<const PairCheckpoint> PairFollower::latest_checkpoint(const PairOrigin& origin) {
  constexpr int kTries = 5;
  std::string why;
  for (int attempt = 0; attempt < kTries && !stopping_; ++attempt) {
    std::optional<PairCheckpoint> found = read_latest_checkpoint(connection_, config_, why);
    if (found) {
      if (found->origin_feed_seq != origin.feed_seq ||
          std::abs(found->origin_created_unix_s - origin.created_unix_s) > 0.01) {
        spdlog::warn("[nats] the latest checkpoint (written by {}) continues another pair's origin: judging the feed "
                     "from this pair's origin",
                     found->written_by);
        return nullptr;
      }
      if (!handlers_.usable(found->pipeline, why)) {
        spdlog::error("[nats] the latest checkpoint (written by {}) cannot be loaded: {}; judging the feed from the "
                      "pair's origin",
                      found->written_by, why);
        return nullptr;
      }
      spdlog::info("[nats] the pair's latest checkpoint (written by {}): feed message {}, alert stream message {}, "
                   "seq {}, {} bytes of state",
                   found->written_by, found->feed_seq, found->alerts_seq, found->last_seq, found->pipeline.size());
      return std::make_shared<const PairCheckpoint>(std::move(*found));
    }
    if (why.empty()) return nullptr;  // none written yet
    if (!sleep_unless_stopping()) return nullptr;
  }
  if (!why.empty()) spdlog::error("[nats] no checkpoint loaded ({}): judging the feed from the pair's origin", why);
  return nullptr;
}

bool PairFollower::bind_bucket() {
  if (bucket_) return true;
  if (!connection_.connected()) return false;
  // Without a TTL: the pair's origin lasts as long as the pair.
  std::string scaled;
  bucket_ = nats::bind_key_value(connection_.jetstream(), config_.pair_bucket, 0.0, config_.replicas, scaled);
  if (!scaled.empty()) spdlog::warn("[nats] pair: {}", scaled);
  return bucket_ != nullptr;
}

std::optional<PairFollower::StreamBounds> PairFollower::bounds(const std::string& stream) {
  // No durable feed (a feed on UDP or TCP to each instance): nothing to start it from.
  if (stream.empty()) return StreamBounds{};
  jsStreamInfo* info = nullptr;
  jsErrCode error = static_cast<jsErrCode>(0);
  const natsStatus s = js_GetStreamInfo(&info, connection_.jetstream(), stream.c_str(), nullptr, &error);
  if (s == NATS_NOT_FOUND || error == JSStreamNotFoundErr) return StreamBounds{};
  if (s != NATS_OK) return std::nullopt;
  const StreamBounds b{info->State.FirstSeq, info->State.LastSeq};
  jsStreamInfo_Destroy(info);
  return b;
}

std::optional<PairOrigin> PairFollower::new_origin() {
  const std::optional<StreamBounds> feed = bounds(feed_stream_);
  const std::optional<StreamBounds> alerts = bounds(config_.stream);
  if (!feed || !alerts) return std::nullopt;
  PairOrigin origin;
  // The feed as a durable consumer that delivers all of it would read it: from its first
  // message, or from the next one when it holds none.
  origin.feed_seq = feed->last >= feed->first && feed->last > 0 ? std::max<std::uint64_t>(feed->first, 1)
                                                                 : feed->last + 1;
  origin.alerts_seq = alerts->last + 1;
  std::uint64_t published = 0;
  if (alerts->last > 0) {
    try {
      published = nats::kept_seq(connection_.jetstream(), config_.stream, alerts->last);
    } catch (const nats::NatsError&) {
      return std::nullopt;
    }
  }
  // Above whatever the stream holds: seq never goes back along it.
  origin.last_seq = std::max(last_seq_, published);
  origin.next_number = next_number_;
  origin.created_by = instance_;
  origin.created_unix_s = util::unix_now_s();
  return origin;
}

std::optional<PairOrigin> PairFollower::origin() {
  if (!bind_bucket()) return std::nullopt;
  const char* key = config_.lease_key.c_str();
  kvEntry* entry = nullptr;
  const natsStatus got = kvStore_Get(&entry, bucket_, key);
  if (got == NATS_OK) {
    const std::string text(kvEntry_ValueString(entry));
    kvEntry_Destroy(entry);
    std::optional<PairOrigin> origin = pair_origin_from_json(text);
    if (!origin) spdlog::error("[nats] the pair's origin {}.{} is unreadable: {}", config_.pair_bucket, key, text);
    else spdlog::info("[nats] the pair's origin (written by {}): feed message {}, alert stream message {}, seq {}",
                      origin->created_by, origin->feed_seq, origin->alerts_seq, origin->last_seq);
    return origin;
  }
  if (got != NATS_NOT_FOUND) return std::nullopt;
  const std::optional<PairOrigin> origin = new_origin();
  if (!origin) return std::nullopt;
  const std::string text = to_json(*origin);
  std::uint64_t revision = 0;
  if (kvStore_Create(&revision, bucket_, key, text.data(), static_cast<int>(text.size())) != NATS_OK)
    return std::nullopt;  // another instance wrote it first: read that one at the next try
  spdlog::info("[nats] {} begins the pair: feed message {}, alert stream message {}, seq {}", instance_,
               origin->feed_seq, origin->alerts_seq, origin->last_seq);
  return origin;
}

void PairFollower::follow(const PairOrigin& origin) {
  RepeatedFailure failures("[nats] pair: the alert stream");
  protocol::AlertStreamReader reader;
  std::uint64_t next = origin.alerts_seq;  // the next stream message wanted
  std::optional<std::uint64_t> target;     // the stream's last message when following began
  std::uint64_t last_seq = origin.last_seq;
  while (!stopping_) {
    if (!target) {
      const std::optional<StreamBounds> b = bounds(config_.stream);
      if (!b) {
        if (!sleep_unless_stopping()) return;
        continue;
      }
      target = b->last;
      if (*target < next) handlers_.on_read_up_to(last_seq);
    }
    jsSubOptions options;
    jsSubOptions_Init(&options);
    options.Stream = config_.stream.c_str();
    options.Ordered = true;  // in stream order, gaps refilled by the client
    options.Config.DeliverPolicy = js_DeliverByStartSequence;
    options.Config.OptStartSeq = next;
    natsSubscription* raw = nullptr;
    if (js_SubscribeSync(&raw, connection_.jetstream(), ">", nullptr, &options, nullptr) != NATS_OK) {
      if (connection_.connected()) failures.report("cannot follow it");
      if (!sleep_unless_stopping()) return;
      continue;
    }
    const Subscription subscription(raw, natsSubscription_Destroy);
    failures.recovered("following it");
    while (!stopping_) {
      natsMsg* message = nullptr;
      const natsStatus s = natsSubscription_NextMsg(&message, subscription.get(), kWaitMs);
      if (s == NATS_TIMEOUT || s == NATS_SLOW_CONSUMER) continue;
      if (s != NATS_OK) break;  // subscribe again after the last message taken
      jsMsgMetaData* meta = nullptr;
      std::uint64_t stream_seq = next;
      if (natsMsg_GetMetaData(&meta, message) == NATS_OK) {
        stream_seq = meta->Sequence.Stream;
        jsMsgMetaData_Destroy(meta);
      }
      const std::string_view line(natsMsg_GetData(message), static_cast<std::size_t>(natsMsg_GetDataLength(message)));
      const bool read = reader.read(line);
      natsMsg_Destroy(message);
      next = stream_seq + 1;
      if (!read) {
        failures.report(fmt::format("message {} unreadable: {}", stream_seq, reader.error()));
      } else if (reader.object_class() == protocol::StreamObjectClass::Alert) {
        last_seq = reader.seq();
        handlers_.on_alert(reader.alert());
      } else if (reader.object_class() == protocol::StreamObjectClass::Ack) {
        last_seq = reader.seq();
        handlers_.on_acknowledgement(reader.seq(), reader.acknowledged());
      }
      if (stream_seq == *target) handlers_.on_read_up_to(last_seq);
    }
    if (!sleep_unless_stopping()) return;
  }
}

}  // namespace kew::daemon
