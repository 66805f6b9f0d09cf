#pragma once
// kewd's publisher on NATS ([nats], design §5.9). Alert events and acknowledgements go
// to an outbox that one thread empties in order into the JetStream stream, each
// publication acknowledged by the server and tried again (with the same message id, so
// JetStream keeps it once) until it is: a server that goes away and comes back loses
// none of them. ALIVE and TRACKS objects are published as they come and not kept.
// Every message carries the stream's JSON object (without its newline) and the header
// nats::kSeqHeader. In hot standby each also carries the holding's fencing token
// (nats::kLeaseHeader), nothing is published while the lease cannot vouch for this
// instance, and each kept event asserts the stream's last message it follows, so that a
// stalled instance that wakes after another took over cannot add to the stream.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "kew/daemon/config.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "nats_connection.hpp"
#include "repeated_failure.hpp"
#include "speaking_right.hpp"

namespace kew::daemon {

class NatsPublisher {
 public:
  /// Connects (in the background when no server answers yet) and starts the outbox's
  /// thread. `run_id` makes message ids unique to this run; `right` is hot standby's
  /// right to speak (null without it). Throws nats::NatsError for a malformed url.
  NatsPublisher(const NatsConfig& config, std::string run_id, std::shared_ptr<const SpeakingRight> right = nullptr);
  /// Gives the outbox up to `kDrainOnStop` to empty, then stops.
  ~NatsPublisher();
  NatsPublisher(const NatsPublisher&) = delete;
  NatsPublisher& operator=(const NatsPublisher&) = delete;

  /// An ALERT object (its seq) to <alerts_subject>.<tail>, kept: `tail` is a zone's
  /// subject token, or apw.<zone> for an area warning (alert_subject_tail).
  void publish_alert(std::string_view tail, std::string_view json, std::uint64_t seq);
  /// An ACK object: to acks_subject, kept.
  void publish_ack(std::string_view json, std::uint64_t seq);
  /// An ALIVE object to status_subject, or a TRACKS snapshot to tracks_subject: now, or
  /// never when the server is away.
  void publish_status(std::string_view json, std::uint64_t seq);
  void publish_tracks(std::string_view json, std::uint64_t seq);

  /// Hot standby's checkpoint (design §5.9): a mark behind everything queued so far. The
  /// future becomes the alert stream's last message sequence once all of it is in the
  /// stream (0 without hot standby); broken when it never will be (the outbox discarded
  /// or full).
  std::future<std::uint64_t> mark_published();

  /// Forgets the events not yet published (a hot-standby instance that lost its lease:
  /// they are the next active's).
  void discard_outbox();

  protocol::NatsStatistics statistics() const;

 private:
  struct Message {
    std::string subject;
    std::string json;
    std::uint64_t seq = 0;
    std::uint64_t number = 0;  // this run's count of kept messages
    std::string id;            // JetStream's message id: a retry or a second publisher's copy is kept once
    /// A mark_published() mark, not a message: told the stream's last sequence.
    std::shared_ptr<std::promise<std::uint64_t>> mark;
  };
  /// The outbox has reached a mark: true once it is told (and leaves the outbox).
  bool reach(const Message& mark);
  /// `id` empty: this run's own (run id and count).
  void enqueue(std::string subject, std::string_view json, std::uint64_t seq, std::string id);
  void publish_now(const std::string& subject, std::string_view json, std::uint64_t seq);
  void run();
  bool ensure_stream();
  /// What became of one publication.
  enum class Sent { Taken, Refused, NoStream, Fenced };
  /// NoStream: nothing on the server takes the subject (the stream was deleted, or a
  /// restarted server lost it), so ensure_stream() must run again before a retry.
  Sent send(const Message& message);
  /// Hot standby: the stream's last message, which the next publication asserts it
  /// follows, read again for a new holding or after another publisher's message; false
  /// when the server did not tell. Fenced: that message carries a later holding's token.
  enum class Follows { Known, Unknown, Fenced };
  Follows learn_last_message();
  /// Whether the server says the alert stream does not exist. A publication nobody
  /// answered (no responders) means that, or only that the stream has no leader for the
  /// moment (its replicas electing one after a node died): only the first is made again.
  bool stream_is_gone();
  /// Waits `period` or until stopping; true when stopping.
  bool wait(std::chrono::milliseconds period);

  NatsConfig config_;
  std::string run_id_;
  std::shared_ptr<const SpeakingRight> right_;
  // Outbox thread, hot standby: the holding the last message known belongs to, and it.
  std::uint64_t known_holding_ = 0;
  std::uint64_t last_message_ = 0;
  RepeatedFailure failures_;  // outbox thread
  nats::NatsConnection connection_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Message> outbox_;     // guarded by mutex_
  std::uint64_t numbered_ = 0;     // guarded by mutex_
  bool stopping_ = false;          // guarded by mutex_
  std::atomic<std::uint64_t> published_{0}, retries_{0}, dropped_{0}, status_published_{0}, fenced_{0};
  std::thread thread_;
};

}  // namespace kew::daemon
