#include "nats_input.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <boost/asio/post.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nats_connection.hpp"
#include "pull_consumer.hpp"
#include "repeated_failure.hpp"
#include "stream_setup.hpp"

namespace kew::daemon {

namespace {

namespace asio = boost::asio;
using nats::NatsConnection;
using nats::PullConsumer;

constexpr int kFetchBatch = 256;            // messages per JetStream pull
constexpr std::int64_t kWaitMs = 200;       // a read waits this long, then looks at stopping_
constexpr int kBatchesInFlight = 2;         // posted to the I/O thread and not yet taken
constexpr auto kRetryPeriod = std::chrono::seconds(1);
// How long the server may take to say what a durable consumer still holds: a server that
// does not answer within it counts as unreachable (design §4.1, §5.9).
constexpr std::int64_t kAskWaitMs = 500;

/// Messages owned until decoded; the last one of a JetStream batch is acknowledged then
/// (acknowledge-all: it acknowledges the batch).
struct MessageBatch {
  std::vector<natsMsg*> messages;
  MessageBatch() = default;
  MessageBatch(const MessageBatch&) = delete;
  MessageBatch& operator=(const MessageBatch&) = delete;
  ~MessageBatch() {
    for (natsMsg* m : messages) natsMsg_Destroy(m);
  }
};

class NatsInput final : public Input {
 public:
  NatsInput(asio::io_context& io, InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : Input(std::move(config), std::move(options), std::move(handler)),
        io_(io),
        connection_(config_.nats_servers, "kewd input " + config_.name,
                    [name = config_.name](std::string_view event) { spdlog::info("input {}: {}", name, event); }),
        failures_("input " + config_.name) {
    decoder_ = make_stream_decoder();
  }
  ~NatsInput() override { halt(); }

  void start() override {
    reader_ = std::thread([this] { read(); });
  }
  bool read_from_stream_sequence(std::uint64_t sequence) override {
    if (!jetstream() || config_.stream.empty()) return false;
    start_sequence_ = sequence;
    return true;
  }
  std::optional<std::uint64_t> delivered_stream_sequence() const override { return delivered_sequence_; }
  void stop() override {
    halt();
    stopped_ = true;
    if (decoder_) retire(*decoder_);
  }

 private:
  bool jetstream() const { return !config_.durable.empty(); }

  void halt() {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    taken_.notify_all();
    if (reader_.joinable()) reader_.join();
  }

  void add_open_stream_rejections(Rejections& out) const override {
    if (decoder_ && !stopped_) out.merge(decoder_->rejections());
  }
  void add_live_figures(protocol::InputStatistics& s) const override {
    s.connections = connection_.connects();
    s.messages_dropped = dropped_.load();
  }

  bool stopping() {
    const std::lock_guard lock(mutex_);
    return stopping_;
  }
  void pause() {
    std::unique_lock lock(mutex_);
    taken_.wait_for(lock, kRetryPeriod, [this] { return stopping_; });
  }

  // The reader thread: subscribes (again and again until it can), then reads.
  void read() {
    while (!stopping()) {
      if (!subscription_ && !consumer_) {
        if (!subscribe()) {
          tell(SourceState::Unreachable);
          pause();
        }
        continue;
      }
      auto batch = std::make_shared<MessageBatch>();
      const natsStatus status =
          consumer_ ? consumer_->fetch(batch->messages, kFetchBatch, kWaitMs) : next(subscription_, *batch);
      const bool delivered = !batch->messages.empty();
      const std::optional<SourceState> after = delivered ? pending_after(*batch) : std::nullopt;
      if (delivered) post(std::move(batch));
      // Posted after the batch: the I/O thread applies its records first.
      if (after) tell(*after);
      if (status == NATS_OK || status == NATS_TIMEOUT) {
        failures_.recovered("reading again");
        if (!delivered) tell(ask_source());
        continue;
      }
      if (status == NATS_SLOW_CONSUMER) {
        std::int64_t dropped = 0;
        if (subscription_) natsSubscription_GetDropped(subscription_, &dropped);
        dropped_.store(static_cast<std::uint64_t>(dropped));
        failures_.report(fmt::format("kewd fell behind {}: {} messages dropped so far", config_.address, dropped));
        continue;
      }
      // Disconnected: the client reconnects and the subscription carries on after it.
      if (!connection_.connected()) {
        tell(SourceState::Unreachable);
        pause();
        continue;
      }
      if (consumer_ && status == NATS_NOT_FOUND) {
        make_consumer_again();
        continue;
      }
      failures_.report(fmt::format("reading {}: {}", config_.address, nats::describe(status)));
      if (status == NATS_INVALID_SUBSCRIPTION || status == NATS_CONNECTION_CLOSED) {
        unsubscribe();
        tell(SourceState::Unreachable);
      } else {
        tell(ask_source());
      }
      pause();
    }
    unsubscribe();
  }

  // Deleted on the server (by an operator, or with its stream): the next pass makes it
  // again from the message after the last one taken, so nothing is read twice or skipped.
  void make_consumer_again() {
    failures_.report(fmt::format("the JetStream consumer {} is gone: making it again {}", config_.durable,
                                 taken_sequence_ ? fmt::format("from message {}", taken_sequence_ + 1)
                                                 : std::string("from the stream's first message")));
    if (taken_sequence_) start_sequence_ = taken_sequence_ + 1;
    consumer_.reset();
  }

  // Destroyed, not unsubscribed: a durable consumer stays on the server for the next run.
  void unsubscribe() {
    natsSubscription_Destroy(subscription_);
    subscription_ = nullptr;
    consumer_.reset();
  }

  bool subscribe() {
    if (!jetstream()) {
      const natsStatus s = natsConnection_SubscribeSync(&subscription_, connection_.get(), config_.address.c_str());
      if (s != NATS_OK) {
        subscription_ = nullptr;
        failures_.report(fmt::format("cannot subscribe to {}: {}", config_.address, nats::describe(s)));
        return false;
      }
      spdlog::info("input {}: subscribed to {}", config_.name, config_.address);
      return true;
    }
    if (!connection_.connected()) return false;
    if (!config_.stream.empty() && !ensure_stream()) return false;
    PullConsumer::Options options;
    options.subject = config_.address;
    options.stream = config_.stream;
    options.durable = config_.durable;
    options.start_sequence = start_sequence_;
    try {
      consumer_ = std::make_unique<PullConsumer>(connection_, options);
    } catch (const nats::NatsError& e) {
      failures_.report(fmt::format("cannot read {} through the JetStream consumer {}: {}", config_.address,
                                   config_.durable, e.what()));
      return false;
    }
    if (start_sequence_)
      spdlog::info("input {}: reading {} through the JetStream consumer {} from message {} of {}", config_.name,
                   config_.address, config_.durable, *start_sequence_, consumer_->stream());
    else
      spdlog::info("input {}: reading {} through the JetStream consumer {}", config_.name, config_.address,
                   config_.durable);
    start_sequence_.reset();  // a later subscription resumes where this consumer is
    return true;
  }

  // Made when missing; one made by an earlier run or the operator keeps its subjects
  // and limits, its replicas follow [nats] replicas.
  bool ensure_stream() {
    const nats::StreamSetup setup = nats::ensure_stream(
        connection_.jetstream(),
        {config_.stream, {config_.address}, config_.stream_max_age_s, -1, config_.stream_replicas},
        nats::IfExists::Keep);
    if (!setup.ready) {
      failures_.report(setup.note);
      return false;
    }
    if (setup.created)
      spdlog::info("input {}: created the JetStream stream {} for {} ({} replicas)", config_.name, config_.stream,
                   config_.address, config_.stream_replicas);
    else if (!setup.note.empty())
      spdlog::warn("input {}: {}", config_.name, setup.note);
    return true;
  }

  // What a durable consumer's source holds for kewd, for the live tick (design §4.1): only
  // a JetStream consumer knows; a plain subscription never tells. Changes are posted to
  // the I/O thread, in order with the batches.
  void tell(SourceState state) {
    if (!jetstream() || told_ == state) return;
    if (told_ == SourceState::Unreachable)
      spdlog::info("input {}: the NATS server answers again: the live tick resumes once {} is caught up",
                   config_.name, config_.durable);
    else if (told_ && state == SourceState::Unreachable)
      spdlog::warn("input {}: the NATS server cannot be reached: the data clock holds at the last record's time "
                   "(the stream keeps what is published meanwhile)",
                   config_.name);
    told_ = state;
    asio::post(io_, [this, state] {
      if (!stopped_ && source_handler_) source_handler_(state);
    });
  }

  // The server's count, in the last message of a batch, of the messages still to come.
  // Also notes the batch's last stream sequence, from which a consumer found gone is made again.
  std::optional<SourceState> pending_after(const MessageBatch& batch) {
    jsMsgMetaData* meta = nullptr;
    if (natsMsg_GetMetaData(&meta, batch.messages.back()) != NATS_OK) return std::nullopt;
    taken_sequence_ = meta->Sequence.Stream;
    const bool behind = meta->NumPending > 0;
    jsMsgMetaData_Destroy(meta);
    return behind ? SourceState::Behind : SourceState::CaughtUp;
  }

  // After a read that brought nothing: the server's count of what the consumer has not yet
  // delivered, which also tells whether the server answers at all (a stopped server keeps
  // the connection open and answers nothing).
  SourceState ask_source() {
    if (!consumer_) return SourceState::CaughtUp;
    std::uint64_t undelivered = 0;
    const natsStatus s = consumer_->undelivered(undelivered, kAskWaitMs);
    if (s == NATS_NOT_FOUND && connection_.connected()) {
      // Nothing more held for kewd under that name: made again after the last message taken.
      make_consumer_again();
      return SourceState::CaughtUp;
    }
    if (s != NATS_OK) return SourceState::Unreachable;
    return undelivered > 0 ? SourceState::Behind : SourceState::CaughtUp;
  }

  // One message (waiting for it), then whatever has already arrived behind it.
  static natsStatus next(natsSubscription* subscription, MessageBatch& batch) {
    natsMsg* message = nullptr;
    natsStatus s = natsSubscription_NextMsg(&message, subscription, kWaitMs);
    if (s != NATS_OK) return s;
    batch.messages.push_back(message);
    int pending = 0;
    natsSubscription_GetPending(subscription, &pending, nullptr);
    for (int i = 0; i < std::min(pending, kFetchBatch - 1); ++i) {
      s = natsSubscription_NextMsg(&message, subscription, 0);
      if (s != NATS_OK) return NATS_OK;
      batch.messages.push_back(message);
    }
    return NATS_OK;
  }

  // Hands a batch to the I/O thread, then waits while it is behind: what kewd has not yet
  // taken stays with the client (its pending limit) and the server (JetStream).
  void post(std::shared_ptr<MessageBatch> batch) {
    std::unique_lock lock(mutex_);
    ++in_flight_;
    asio::post(io_, [this, batch = std::move(batch)] { take(*batch); });
    taken_.wait(lock, [this] { return stopping_ || in_flight_ < kBatchesInFlight; });
  }

  // On the I/O thread.
  void take(MessageBatch& batch) {
    if (!stopped_) {
      for (natsMsg* m : batch.messages)
        feed_message(*decoder_, natsMsg_GetData(m), static_cast<std::size_t>(natsMsg_GetDataLength(m)));
      // Acknowledged once decoded: the records are the pipeline's now.
      if (jetstream() && !batch.messages.empty()) {
        PullConsumer::acknowledge(connection_.get(), batch.messages.back());
        jsMsgMetaData* meta = nullptr;
        if (natsMsg_GetMetaData(&meta, batch.messages.back()) == NATS_OK) {
          delivered_sequence_ = meta->Sequence.Stream;
          jsMsgMetaData_Destroy(meta);
        }
      }
    }
    {
      const std::lock_guard lock(mutex_);
      --in_flight_;
    }
    taken_.notify_all();
  }

  asio::io_context& io_;
  NatsConnection connection_;
  std::unique_ptr<protocol::Decoder> decoder_;
  std::thread reader_;
  natsSubscription* subscription_ = nullptr;  // reader thread: a plain subscription
  std::unique_ptr<PullConsumer> consumer_;    // reader thread: a durable JetStream consumer
  std::mutex mutex_;
  std::condition_variable taken_;
  int in_flight_ = 0;       // guarded by mutex_
  bool stopping_ = false;   // guarded by mutex_
  bool stopped_ = false;    // I/O thread
  std::optional<std::uint64_t> delivered_sequence_;  // I/O thread
  std::atomic<std::uint64_t> dropped_{0};
  RepeatedFailure failures_;  // reader thread
  std::optional<std::uint64_t> start_sequence_;  // set before start(), then the reader thread's
  std::uint64_t taken_sequence_ = 0;  // reader thread: the stream sequence of the last message taken
  std::optional<SourceState> told_;  // reader thread: the last state posted; none yet
};

}  // namespace

std::unique_ptr<Input> make_nats_input(asio::io_context& io, const InputConfig& config,
                                       const protocol::DecoderOptions& options, Input::ReportHandler handler) {
  return std::make_unique<NatsInput>(io, config, options, std::move(handler));
}

}  // namespace kew::daemon
