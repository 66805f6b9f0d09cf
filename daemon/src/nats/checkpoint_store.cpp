#include "checkpoint_store.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "stream_setup.hpp"

namespace kew::daemon {

namespace {

constexpr const char* kNameHeader = "Kew-Checkpoint";
constexpr const char* kChunkHeader = "Kew-Chunk";
constexpr const char* kFirstHeader = "Kew-Checkpoint-First";
constexpr std::int64_t kPublishWaitMs = 5000;
constexpr std::int64_t kReadWaitMs = 5000;
// The alert stream has this long to take the events a checkpoint covers.
constexpr auto kPublishedWait = std::chrono::seconds(60);
constexpr jsErrCode kNoMessageFound = static_cast<jsErrCode>(10037);

using Message = std::unique_ptr<natsMsg, decltype(&natsMsg_Destroy)>;
using Subscription = std::unique_ptr<natsSubscription, decltype(&natsSubscription_Destroy)>;

std::string header(natsMsg* message, const char* name) {
  const char* value = nullptr;
  return natsMsgHeader_Get(message, name, &value) == NATS_OK && value ? std::string(value) : std::string();
}

/// "i/n" with 1 ≤ i ≤ n.
bool parse_chunk(const std::string& text, std::uint64_t& i, std::uint64_t& n) {
  char* end = nullptr;
  i = std::strtoull(text.c_str(), &end, 10);
  if (*end != '/') return false;
  n = std::strtoull(end + 1, &end, 10);
  return *end == '\0' && i >= 1 && i <= n;
}

/// Parts 1..n of checkpoint `name`, the first at stream sequence `first_text`, into `bytes`.
bool read_parts(const nats::NatsConnection& connection, const NatsConfig& config, const std::string& name,
                std::uint64_t n, const std::string& first_text, std::string& bytes, std::string& why);

}  // namespace

std::string checkpoint_subject(const NatsConfig& config) { return config.checkpoint_stream + "." + config.lease_key; }

std::optional<PairCheckpoint> read_latest_checkpoint(const nats::NatsConnection& connection,
                                                     const NatsConfig& config, std::string& why) {
  why.clear();
  const std::string subject = checkpoint_subject(config);
  natsMsg* raw = nullptr;
  jsErrCode error = static_cast<jsErrCode>(0);
  const natsStatus got =
      js_GetLastMsg(&raw, connection.jetstream(), config.checkpoint_stream.c_str(), subject.c_str(), nullptr, &error);
  if (got == NATS_NOT_FOUND || error == JSStreamNotFoundErr || error == kNoMessageFound) return std::nullopt;
  if (got != NATS_OK) {
    why = fmt::format("the stream {} did not answer: {}", config.checkpoint_stream, nats::describe(got));
    return std::nullopt;
  }
  const Message last(raw, natsMsg_Destroy);
  const std::string name = header(last.get(), kNameHeader);
  std::uint64_t i = 0, n = 0;
  if (!parse_chunk(header(last.get(), kChunkHeader), i, n) || name.empty()) {
    why = "its last message is not a checkpoint's";
    return std::nullopt;
  }
  if (i != n) {
    why = fmt::format("the latest checkpoint, {}, was cut short at part {} of {}", name, i, n);
    return std::nullopt;
  }
  std::string bytes;
  if (n == 1) {
    bytes.assign(natsMsg_GetData(last.get()), static_cast<std::size_t>(natsMsg_GetDataLength(last.get())));
  } else if (!read_parts(connection, config, name, n, header(last.get(), kFirstHeader), bytes, why)) {
    return std::nullopt;
  }
  std::optional<PairCheckpoint> checkpoint = pair_checkpoint_from_bytes(bytes, why);
  if (!checkpoint) why = fmt::format("{} cannot be read: {}", name, why);
  return checkpoint;
}

namespace {

bool read_parts(const nats::NatsConnection& connection, const NatsConfig& config, const std::string& name,
                std::uint64_t n, const std::string& first_text, std::string& bytes, std::string& why) {
  const std::uint64_t first = std::strtoull(first_text.c_str(), nullptr, 10);
  if (first == 0) {
    why = fmt::format("the last part of {} does not say where its first is", name);
    return false;
  }
  const std::string subject = checkpoint_subject(config);
  jsSubOptions options;
  jsSubOptions_Init(&options);
  options.Stream = config.checkpoint_stream.c_str();
  options.Ordered = true;
  options.Config.DeliverPolicy = js_DeliverByStartSequence;
  options.Config.OptStartSeq = first;
  natsSubscription* sub = nullptr;
  if (js_SubscribeSync(&sub, connection.jetstream(), subject.c_str(), nullptr, &options, nullptr) != NATS_OK) {
    why = fmt::format("the parts of {} cannot be read", name);
    return false;
  }
  const Subscription subscription(sub, natsSubscription_Destroy);
  for (std::uint64_t part = 1; part <= n; ++part) {
    natsMsg* chunk = nullptr;
    if (natsSubscription_NextMsg(&chunk, subscription.get(), kReadWaitMs) != NATS_OK) {
      why = fmt::format("part {} of {} of {} did not come", part, n, name);
      return false;
    }
    const Message held(chunk, natsMsg_Destroy);
    std::uint64_t ci = 0, cn = 0;
    if (header(chunk, kNameHeader) != name || !parse_chunk(header(chunk, kChunkHeader), ci, cn) || ci != part ||
        cn != n) {
      why = fmt::format("part {} of {} of {} is not where it should be", part, n, name);
      return false;
    }
    bytes.append(natsMsg_GetData(chunk), static_cast<std::size_t>(natsMsg_GetDataLength(chunk)));
  }
  return true;
}

}  // namespace

CheckpointPublisher::CheckpointPublisher(const NatsConfig& config, std::shared_ptr<const SpeakingRight> right)
    : config_(config),
      subject_(checkpoint_subject(config)),
      right_(std::move(right)),
      connection_(config.servers, config.name + " checkpoints",
                  [](std::string_view event) { spdlog::info("[nats] checkpoints: {}", event); }),
      failures_("[nats] checkpoints") {
  thread_ = std::thread([this] { run(); });
}

CheckpointPublisher::~CheckpointPublisher() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

bool CheckpointPublisher::write(PairCheckpoint checkpoint, std::future<std::uint64_t> published) {
  {
    const std::lock_guard lock(mutex_);
    if (job_ || stopping_) return false;
    job_.emplace(Job{std::move(checkpoint), std::move(published)});
  }
  changed_.notify_all();
  return true;
}

void CheckpointPublisher::run() {
  for (;;) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return stopping_ || job_; });
    if (stopping_) return;
    lock.unlock();
    carry_out(*job_);  // only this thread resets job_
    lock.lock();
    job_.reset();
  }
}

void CheckpointPublisher::carry_out(Job& job) {
  PairCheckpoint& checkpoint = job.checkpoint;
  const auto deadline = std::chrono::steady_clock::now() + kPublishedWait;
  while (job.published.wait_for(std::chrono::milliseconds(200)) != std::future_status::ready) {
    {
      const std::lock_guard lock(mutex_);
      if (stopping_) return;
    }
    if (std::chrono::steady_clock::now() > deadline) {
      spdlog::warn("[nats] checkpoint at feed message {} abandoned: its events were not published within {} s",
                   checkpoint.feed_seq, kPublishedWait.count());
      return;
    }
  }
  try {
    checkpoint.alerts_seq = job.published.get() + 1;
  } catch (const std::future_error&) {
    spdlog::warn("[nats] checkpoint at feed message {} abandoned: its events will not be published by this instance",
                 checkpoint.feed_seq);
    return;
  }
  if (!ensure_stream()) return;
  const std::optional<std::uint64_t> first = publish(checkpoint);
  if (!first) return;
  purge_before(*first);
  ++written_;
  failures_.recovered("writing again");
  spdlog::info("[nats] checkpoint written to {}: feed message {}, seq {}, alert stream message {}, {} bytes of state",
               subject_, checkpoint.feed_seq, checkpoint.last_seq, checkpoint.alerts_seq, checkpoint.pipeline.size());
}

bool CheckpointPublisher::ensure_stream() {
  if (stream_ready_) return true;
  const nats::StreamSetup setup =
      nats::ensure_stream(connection_.jetstream(),
                          {config_.checkpoint_stream, {config_.checkpoint_stream + ".>"}, 0, -1, config_.replicas},
                          nats::IfExists::Keep);
  if (!setup.ready) {
    failures_.report(setup.note + "; no checkpoint written");
    return false;
  }
  if (!setup.note.empty()) spdlog::warn("[nats] checkpoints: {}", setup.note);
  stream_ready_ = true;
  return true;
}

std::optional<std::uint64_t> CheckpointPublisher::publish(const PairCheckpoint& checkpoint) {
  const std::string bytes = to_bytes(checkpoint);
  const std::string name = fmt::format("{}-{}", checkpoint.written_by, checkpoint.feed_seq);
  const std::size_t parts = std::max<std::size_t>(1, (bytes.size() + kChunkBytes - 1) / kChunkBytes);
  std::uint64_t first = 0;
  for (std::size_t part = 1; part <= parts; ++part) {
    // A checkpoint is the active's: an instance whose lease may have lapsed writes no more.
    if (right_ && !right_->may_publish()) {
      spdlog::warn("[nats] checkpoint {} abandoned at part {} of {}: this instance may not speak", name, part, parts);
      return std::nullopt;
    }
    const std::string_view data = std::string_view(bytes).substr((part - 1) * kChunkBytes, kChunkBytes);
    natsMsg* raw = nullptr;
    if (natsMsg_Create(&raw, subject_.c_str(), nullptr, data.data(), static_cast<int>(data.size())) != NATS_OK) {
      failures_.report("cannot make a checkpoint message (out of memory?)");
      return std::nullopt;
    }
    const Message message(raw, natsMsg_Destroy);
    natsMsgHeader_Set(raw, kNameHeader, name.c_str());
    natsMsgHeader_Set(raw, kChunkHeader, fmt::format("{}/{}", part, parts).c_str());
    if (part == parts && part > 1) natsMsgHeader_Set(raw, kFirstHeader, std::to_string(first).c_str());
    jsPubOptions options;
    jsPubOptions_Init(&options);
    options.MaxWait = kPublishWaitMs;
    jsPubAck* ack = nullptr;
    jsErrCode error = static_cast<jsErrCode>(0);
    const natsStatus s = js_PublishMsg(&ack, connection_.jetstream(), raw, &options, &error);
    const std::uint64_t sequence = s == NATS_OK && ack ? ack->Sequence : 0;
    jsPubAck_Destroy(ack);
    if (sequence == 0) {
      failures_.report(fmt::format("checkpoint {} not taken at part {} of {}: {}{}", name, part, parts,
                                   nats::describe(s),
                                   error ? fmt::format(" (JetStream error {})", static_cast<int>(error)) : ""));
      if (s == NATS_NOT_FOUND || error == JSStreamNotFoundErr || s == NATS_NO_RESPONDERS) stream_ready_ = false;
      return std::nullopt;
    }
    if (part == 1) first = sequence;
  }
  return first;
}

void CheckpointPublisher::purge_before(std::uint64_t first) {
  jsOptions options;
  jsOptions_Init(&options);
  options.Stream.Purge.Subject = subject_.c_str();
  options.Stream.Purge.Sequence = first;
  jsErrCode error = static_cast<jsErrCode>(0);
  const natsStatus s = js_PurgeStream(connection_.jetstream(), config_.checkpoint_stream.c_str(), &options, &error);
  if (s != NATS_OK)
    spdlog::warn("[nats] the checkpoints before stream message {} stay in {}: {}", first, config_.checkpoint_stream,
                 nats::describe(s));
}

}  // namespace kew::daemon
