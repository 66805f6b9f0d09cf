#pragma once
// A durable JetStream pull consumer read through pull requests kewd sends itself
// (design §5.9). The C client's own fetch is not used: libnats 3.4.1, Debian 12's,
// writes past its message array when more than half a batch of an earlier, late-answered
// pull request is waiting at the next fetch (nats.c pull request #749, fixed upstream in
// 2024), which a feed backlog after a server outage does; and its acknowledgement reaches
// through the subscription, which a batch still being decoded may outlive. Here every
// answer lands in an inbox subscription this class owns, any number of messages is kept,
// and an acknowledgement is a publication to the message's reply subject.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nats/nats.h>

namespace kew::nats {

class NatsConnection;

class PullConsumer {
 public:
  struct Options {
    std::string subject;  ///< what the consumer reads
    std::string stream;   ///< the stream holding `subject`; empty: the one the server names
    std::string durable;  ///< the consumer's name; it stays on the server between runs
    /// Read from this stream sequence: the consumer is made again from there (from the
    /// stream's first message when the stream ends before it: made anew since).
    std::optional<std::uint64_t> start_sequence;
    std::int64_t ack_wait_ns = 30'000'000'000;  ///< redelivery after this without an ack
  };

  /// Binds the consumer, creating it when absent (acknowledge-all, from the stream's
  /// first message or `start_sequence`). Throws NatsError with the reason when the
  /// server refuses or does not answer.
  PullConsumer(NatsConnection& connection, const Options& options);
  /// Unsubscribes the inbox; the consumer stays on the server for the next run.
  ~PullConsumer();
  PullConsumer(const PullConsumer&) = delete;
  PullConsumer& operator=(const PullConsumer&) = delete;

  /// Appends to `out` what has arrived, at most `max` (≥ 1) messages, waiting up to
  /// `wait_ms` for the first. NATS_OK with at least one message, NATS_TIMEOUT with none,
  /// NATS_NOT_FOUND when the server says the consumer is gone, another status when the
  /// inbox cannot be read. The caller owns the messages.
  natsStatus fetch(std::vector<natsMsg*>& out, int max, std::int64_t wait_ms);

  /// Acknowledges `last` and, the consumer acknowledging all, every message before it.
  /// Safe on any thread, also after this consumer is gone (it needs only the connection).
  static natsStatus acknowledge(natsConnection* connection, natsMsg* last);

  /// How many messages the consumer has not delivered yet, asking the server and waiting
  /// up to `wait_ms` for its answer; NATS_NOT_FOUND when it says the consumer is gone.
  natsStatus undelivered(std::uint64_t& count, std::int64_t wait_ms);

  /// The stream read, as bound.
  const std::string& stream() const { return stream_; }

 private:
  void bind(const Options& options);
  natsStatus request_more(int max, std::int64_t wait_ms);

  NatsConnection& connection_;
  std::string stream_;
  std::string durable_;
  std::string inbox_;        // "<unique inbox>." : each pull request's reply is this plus its number
  natsSubscription* replies_ = nullptr;  // inbox_ + "*"
  std::uint64_t request_ = 0;            // the number of the last pull request sent
  int open_ = 0;                         // messages the last request may still bring
  std::chrono::steady_clock::time_point open_until_{};  // and until when
};

}  // namespace kew::nats
