#include "nats_publisher.hpp"

#include <algorithm>
#include <cstdlib>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "stream_setup.hpp"

namespace kew::daemon {

namespace {

// What a stopping kewd gives the server to take the last events.
constexpr auto kDrainOnStop = std::chrono::seconds(2);
constexpr auto kRetryPeriod = std::chrono::milliseconds(250);
constexpr std::int64_t kAcknowledgementWaitMs = 2000;
constexpr std::int64_t kLearnWaitMs = 500;  // the stream's last message, asked of its leader

/// A message with the seq header, destroyed with its owner.
class OutgoingMessage {
 public:
  /// `holding`: hot standby's fencing token (0: none).
  OutgoingMessage(const std::string& subject, std::string_view json, std::uint64_t seq, std::uint64_t holding) {
    nats::check(natsMsg_Create(&message_, subject.c_str(), nullptr, json.data(), static_cast<int>(json.size())),
                "NATS message");
    natsMsgHeader_Set(message_, nats::kSeqHeader, std::to_string(seq).c_str());
    if (holding) natsMsgHeader_Set(message_, nats::kLeaseHeader, std::to_string(holding).c_str());
  }
  ~OutgoingMessage() { natsMsg_Destroy(message_); }
  OutgoingMessage(const OutgoingMessage&) = delete;
  OutgoingMessage& operator=(const OutgoingMessage&) = delete;
  natsMsg* get() const { return message_; }

 private:
  natsMsg* message_ = nullptr;
};

}  // namespace

NatsPublisher::NatsPublisher(const NatsConfig& config, std::string run_id, std::shared_ptr<const SpeakingRight> right)
    : config_(config),
      run_id_(std::move(run_id)),
      right_(std::move(right)),
      failures_("[nats]"),
      connection_(config.servers, config.name, [](std::string_view event) { spdlog::info("[nats] {}", event); }) {
  thread_ = std::thread([this] { run(); });
}

NatsPublisher::~NatsPublisher() {
  {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, kDrainOnStop, [this] { return outbox_.empty(); });
    if (!outbox_.empty())
      spdlog::error("[nats] stopping with {} events the server has not taken", outbox_.size());
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void NatsPublisher::publish_alert(std::string_view tail, std::string_view json, std::uint64_t seq) {
  // Hot standby: every instance numbers an event alike, so an event published by two of
  // them (one stepping down with a publication in flight, one taking over) is kept once.
  enqueue(fmt::format("{}.{}", config_.alerts_subject, tail), json, seq,
          config_.hot_standby ? fmt::format("{}-{}", config_.lease_key, seq) : std::string());
}

void NatsPublisher::publish_ack(std::string_view json, std::uint64_t seq) {
  enqueue(config_.acks_subject, json, seq, {});
}

void NatsPublisher::publish_status(std::string_view json, std::uint64_t seq) {
  publish_now(config_.status_subject, json, seq);
}

void NatsPublisher::publish_tracks(std::string_view json, std::uint64_t seq) {
  publish_now(config_.tracks_subject, json, seq);
}

void NatsPublisher::enqueue(std::string subject, std::string_view json, std::uint64_t seq, std::string id) {
  if (!json.empty() && json.back() == '\n') json.remove_suffix(1);
  {
    const std::lock_guard lock(mutex_);
    if (outbox_.size() >= config_.outbox) {
      outbox_.pop_front();
      if (dropped_++ % 1000 == 0)
        spdlog::error("[nats] outbox full ({} events): dropping the oldest ({} dropped so far)", config_.outbox,
                      dropped_.load());
    }
    ++numbered_;
    if (id.empty()) id = fmt::format("{}-{}", run_id_, numbered_);
    outbox_.push_back(Message{std::move(subject), std::string(json), seq, numbered_, std::move(id), nullptr});
  }
  changed_.notify_all();
}

void NatsPublisher::publish_now(const std::string& subject, std::string_view json, std::uint64_t seq) {
  if (!connection_.connected()) return;
  // A status is the active's to give, and only while the lease vouches for it.
  if (right_ && !right_->may_publish()) return;
  if (!json.empty() && json.back() == '\n') json.remove_suffix(1);
  try {
    OutgoingMessage message(subject, json, seq, right_ ? right_->revision() : 0);
    if (natsConnection_PublishMsg(connection_.get(), message.get()) == NATS_OK) ++status_published_;
  } catch (const nats::NatsError&) {
    // Out of memory in the client: a status object is not worth more.
  }
}

bool NatsPublisher::wait(std::chrono::milliseconds period) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, period, [this] { return stopping_; });
  return stopping_;
}

void NatsPublisher::run() {
  // The stream first, before any event: a subscriber may start reading it before kewd
  // has anything to say.
  bool stream_ready = config_.stream.empty();
  for (;;) {
    if (!stream_ready) {
      stream_ready = ensure_stream();
      if (!stream_ready && wait(kRetryPeriod)) return;
      continue;
    }
    Message message;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return stopping_ || !outbox_.empty(); });
      if (stopping_) return;
      message = outbox_.front();
    }
    if (message.mark) {
      if (reach(message)) {
        const std::lock_guard lock(mutex_);
        if (!outbox_.empty() && outbox_.front().number == message.number) outbox_.pop_front();
      } else if (wait(kRetryPeriod)) {
        return;
      }
      continue;
    }
    const Sent sent = send(message);
    if (sent == Sent::Taken) {
      ++published_;
      {
        const std::lock_guard lock(mutex_);
        // Dropped meanwhile by a full outbox? Then the front is another message.
        if (!outbox_.empty() && outbox_.front().number == message.number) outbox_.pop_front();
      }
      changed_.notify_all();
      failures_.recovered("publishing again");
      continue;
    }
    if (sent == Sent::Fenced) {
      // Another instance holds the lease and has published: what waits here is its to send.
      discard_outbox();
      continue;
    }
    ++retries_;
    // Without its stream nothing would ever take the head of the outbox: create it again.
    if (sent == Sent::NoStream) stream_ready = false;
    if (wait(kRetryPeriod)) return;
  }
}

bool NatsPublisher::ensure_stream() {
  if (!connection_.connected()) return false;
  const std::string alerts = config_.alerts_subject + ".>";
  const nats::StreamSetup setup = nats::ensure_stream(
      connection_.jetstream(),
      {config_.stream, {alerts, config_.acks_subject}, config_.stream_max_age_s,
       static_cast<std::int64_t>(config_.stream_max_bytes), config_.replicas},
      nats::IfExists::Update);  // kept from an earlier run: its limits and replicas follow this configuration
  if (!setup.ready) {
    failures_.report(setup.note + " (events wait in the outbox)");
    return false;
  }
  if (!setup.note.empty()) failures_.report(setup.note);
  spdlog::info("[nats] alerts kept in the JetStream stream {} ({}, {}; {} replicas)", config_.stream, alerts,
               config_.acks_subject, config_.replicas);
  return true;
}

std::future<std::uint64_t> NatsPublisher::mark_published() {
  auto mark = std::make_shared<std::promise<std::uint64_t>>();
  std::future<std::uint64_t> reached = mark->get_future();
  {
    const std::lock_guard lock(mutex_);
    ++numbered_;
    outbox_.push_back(Message{{}, {}, 0, numbered_, {}, std::move(mark)});
  }
  changed_.notify_all();
  return reached;
}

bool NatsPublisher::reach(const Message& mark) {
  if (!right_) {
    mark.mark->set_value(0);
    return true;
  }
  // The stream's last message as this holding knows it: everything before the mark is
  // at or below it, and only this holding's later publications come after it.
  if (!right_->may_publish()) return false;
  if (known_holding_ != right_->revision()) {
    const Follows follows = learn_last_message();
    if (follows == Follows::Fenced) {
      discard_outbox();
      return false;
    }
    if (follows == Follows::Unknown) return false;
  }
  mark.mark->set_value(last_message_);
  return true;
}

NatsPublisher::Follows NatsPublisher::learn_last_message() {
  // Asked again soon rather than waited for long: right after a new stream leader is
  // elected a question put to the old one is never answered, and the client's own wait
  // (5 s) would hold publication back that long.
  jsOptions options;
  jsOptions_Init(&options);
  options.Wait = kLearnWaitMs;
  jsStreamInfo* info = nullptr;
  if (js_GetStreamInfo(&info, connection_.jetstream(), config_.stream.c_str(), &options, nullptr) != NATS_OK)
    return Follows::Unknown;
  const std::uint64_t last = info->State.LastSeq;
  jsStreamInfo_Destroy(info);
  if (last > 0) {
    natsMsg* message = nullptr;
    if (js_GetMsg(&message, connection_.jetstream(), config_.stream.c_str(), last, &options, nullptr) != NATS_OK)
      return Follows::Unknown;
    const char* value = nullptr;
    const std::uint64_t token =
        natsMsgHeader_Get(message, nats::kLeaseHeader, &value) == NATS_OK ? std::strtoull(value, nullptr, 10) : 0;
    natsMsg_Destroy(message);
    if (token > right_->revision()) return Follows::Fenced;
  }
  last_message_ = last;
  known_holding_ = right_->revision();
  return Follows::Known;
}

NatsPublisher::Sent NatsPublisher::send(const Message& message) {
  natsStatus s = NATS_OK;
  jsErrCode error = static_cast<jsErrCode>(0);
  const std::uint64_t holding = right_ ? right_->revision() : 0;
  try {
    OutgoingMessage outgoing(message.subject, message.json, message.seq, holding);
    if (config_.stream.empty()) {
      s = natsConnection_PublishMsg(connection_.get(), outgoing.get());
    } else {
      jsPubOptions options;
      jsPubOptions_Init(&options);
      options.MsgId = message.id.c_str();
      options.MaxWait = kAcknowledgementWaitMs;
      if (right_) {
        // Hot standby: only while the lease vouches for this instance, and only after the
        // message this holding knows to be the stream's last (JetStream refuses it when
        // another publisher has added one since).
        if (!right_->may_publish()) return Sent::Refused;
        if (known_holding_ != holding) {
          const Follows follows = learn_last_message();
          if (follows == Follows::Fenced) return Sent::Fenced;
          if (follows == Follows::Unknown) return Sent::Refused;
        }
        options.ExpectLastSeq = last_message_;
      }
      jsPubAck* ack = nullptr;
      s = js_PublishMsg(&ack, connection_.jetstream(), outgoing.get(), &options, &error);
      if (s == NATS_OK && ack && right_) last_message_ = std::max(last_message_, ack->Sequence);
      jsPubAck_Destroy(ack);
    }
  } catch (const nats::NatsError& e) {
    s = e.status();
  }
  if (s == NATS_OK) return Sent::Taken;
  if (right_ && error == JSStreamWrongLastSequenceErr) {
    // Another publisher added to the stream: a later holding's token fences this one;
    // an earlier one's (a stalled active's last words) is followed.
    ++fenced_;
    known_holding_ = 0;
    if (learn_last_message() == Follows::Fenced) {
      spdlog::error("[nats] fenced: an instance holding the lease after this one has published to {}; "
                    "this instance publishes nothing more of its outbox",
                    config_.stream);
      return Sent::Fenced;
    }
    return Sent::Refused;
  }
  const bool no_stream =
      !config_.stream.empty() && (error == JSStreamNotFoundErr || (s == NATS_NO_RESPONDERS && stream_is_gone()));
  failures_.report(fmt::format("{} not taken by the server: {}{} ({})", message.subject, nats::describe(s),
                               error ? fmt::format(" (JetStream error {})", static_cast<int>(error)) : "",
                               no_stream ? "no stream takes it: creating the stream again"
                                         : "tried again until it is"));
  return no_stream ? Sent::NoStream : Sent::Refused;
}

bool NatsPublisher::stream_is_gone() {
  jsOptions options;
  jsOptions_Init(&options);
  options.Wait = kAcknowledgementWaitMs;
  jsStreamInfo* info = nullptr;
  jsErrCode error = static_cast<jsErrCode>(0);
  js_GetStreamInfo(&info, connection_.jetstream(), config_.stream.c_str(), &options, &error);
  jsStreamInfo_Destroy(info);
  return error == JSStreamNotFoundErr;
}

void NatsPublisher::discard_outbox() {
  std::size_t discarded = 0;
  {
    const std::lock_guard lock(mutex_);
    discarded = outbox_.size();
    // The front may be in flight: published or not, it is no longer this kewd's.
    outbox_.clear();
  }
  changed_.notify_all();
  if (discarded) spdlog::warn("[nats] {} unpublished events discarded (standby now)", discarded);
}

protocol::NatsStatistics NatsPublisher::statistics() const {
  protocol::NatsStatistics s;
  s.connected = connection_.connected();
  s.disconnects = connection_.disconnects();
  s.published = published_.load();
  s.retries = retries_.load();
  s.dropped = dropped_.load();
  s.status_published = status_published_.load();
  s.fenced = fenced_.load();
  s.bus_away = right_ && right_->bus_away();
  const std::lock_guard lock(mutex_);
  s.queued = outbox_.size();
  return s;
}

}  // namespace kew::daemon
