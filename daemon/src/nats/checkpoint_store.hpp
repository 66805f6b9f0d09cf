#pragma once
// Where a hot-standby pair keeps its checkpoints (design §5.9): the JetStream stream
// [nats] checkpoint_stream, subject <checkpoint_stream>.<lease_key>, one checkpoint as
// consecutive messages of at most kChunkBytes (a NATS message is limited to the server's
// max_payload, 1 MiB by default), each with the headers Kew-Checkpoint (the checkpoint's
// name) and Kew-Chunk ("i/n"), the last one also Kew-Checkpoint-First (the stream
// sequence of its first). Once a checkpoint is whole in the stream, the older ones are
// purged; one cut short by its writer's death is never loaded.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "../standby/pair_checkpoint.hpp"
#include "kew/daemon/config.hpp"
#include "nats_connection.hpp"
#include "repeated_failure.hpp"
#include "speaking_right.hpp"

namespace kew::daemon {

/// The checkpoints' subject of a pair's configuration.
std::string checkpoint_subject(const NatsConfig& config);

/// The latest whole checkpoint of the pair, through `connection`. Nullopt when there is
/// none, or when it cannot be read: then `why` says so (empty: simply none).
std::optional<PairCheckpoint> read_latest_checkpoint(const nats::NatsConnection& connection,
                                                     const NatsConfig& config, std::string& why);

/// The active's writer of checkpoints, on a thread and a connection of its own.
class CheckpointPublisher {
 public:
  static constexpr std::size_t kChunkBytes = 256u << 10;

  /// Connects in the background. `right`: the lease's right to speak, asked before each
  /// message (a checkpoint is the active's to write). Throws nats::NatsError for a
  /// malformed url.
  CheckpointPublisher(const NatsConfig& config, std::shared_ptr<const SpeakingRight> right);
  ~CheckpointPublisher();
  CheckpointPublisher(const CheckpointPublisher&) = delete;
  CheckpointPublisher& operator=(const CheckpointPublisher&) = delete;

  /// Writes `checkpoint` once `published` tells the alert stream's last message after
  /// every event and acknowledgement of its state (NatsPublisher::mark_published): its
  /// alerts_seq is the next one. False, and nothing done, while an earlier one is still
  /// being written. A checkpoint whose events are never all published (the lease lost,
  /// the outbox discarded) is abandoned, logged.
  bool write(PairCheckpoint checkpoint, std::future<std::uint64_t> published);

  std::uint64_t written() const { return written_.load(); }

 private:
  struct Job {
    PairCheckpoint checkpoint;
    std::future<std::uint64_t> published;
  };
  void run();
  void carry_out(Job& job);
  bool ensure_stream();
  /// Publishes the checkpoint's messages; the stream sequence of the first, or nullopt.
  std::optional<std::uint64_t> publish(const PairCheckpoint& checkpoint);
  void purge_before(std::uint64_t first);

  NatsConfig config_;
  std::string subject_;
  std::shared_ptr<const SpeakingRight> right_;
  nats::NatsConnection connection_;
  RepeatedFailure failures_;  // the thread's
  bool stream_ready_ = false;  // the thread's
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<Job> job_;  // guarded by mutex_: waiting or being carried out
  bool stopping_ = false;   // guarded by mutex_
  std::atomic<std::uint64_t> written_{0};
  std::thread thread_;
};

}  // namespace kew::daemon
