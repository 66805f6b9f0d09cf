#pragma once
// This kewd as one instance of a hot-standby pair (design §5.9): it learns the pair's
// origin, judges the feed from there with the pair's numbering, follows what the active
// publishes, stays in step with it (StandbySync), applies its acknowledgements where they
// happened, and takes over when the lease comes to it: in step, by sending what the
// previous active had not published; out of step, by ending what it cannot continue
// (reason takeover_unsynced) before anything of its own.
//
// Owned by the service; everything here runs on its I/O thread.

#include <chrono>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "../nats/hot_standby.hpp"
#include "../outputs/fan_out.hpp"
#include "kew/daemon/config.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "pair_checkpoint.hpp"
#include "pair_origin.hpp"
#include "standby_sync.hpp"

namespace kew::daemon {

/// The JetStream stream of the pair's feed: the stream of the configuration's one input
/// when it is a durable NATS input with `stream`; "" otherwise (several inputs interleave
/// differently on each instance: no exact catch-up is possible).
std::string pair_feed_stream(const std::vector<InputConfig>& inputs);
/// Whether the pair's feed can be judged from a checkpoint: a pair feed stream whose
/// format decodes each line alone (ndjson, readsb), so that nothing of the decoder's
/// state before the checkpoint matters after it.
bool pair_feed_checkpointable(const std::vector<InputConfig>& inputs);
/// PairMember::Hooks::usable for a service whose pipeline has `config`: a checkpoint's
/// state restored into a pipeline of its own (the service's must stay fresh until the
/// checkpoint is known to fit); `why` says what did not fit.
std::function<bool(const std::string& state, std::string& why)> checkpoint_fits(PipelineConfig config);

class PairMember {
 public:
  /// The service's part: `begin(origin)` resumes the pipeline's numbering at the origin's
  /// and starts the inputs, the feed read from the origin's message; `acknowledged()`
  /// after the active's acknowledgements were applied here (the Modbus panel's state);
  /// `emit(event)` sends an event made outside the pipeline as the pipeline's own.
  /// `begin(start, checkpoint)`: with a checkpoint, its pipeline state is to be restored
  /// instead (and the numbering is the state's); `usable(state, why)`: whether a
  /// checkpoint's state can be restored here (called on another thread; unset: no
  /// checkpoint is read or written).
  struct Hooks {
    std::function<void(const PairOrigin& start, const PairCheckpoint* checkpoint)> begin;
    std::function<void()> acknowledged;
    std::function<void(const AlertEvent&)> emit;
    std::function<bool(const std::string& state, std::string& why)> usable;
  };

  /// `feed_stream`: the JetStream stream of the pair's one durable NATS feed ("" when the
  /// configuration has none: no exact catch-up). `last_seq`, `next_number`: this
  /// instance's own numbering (its state file and alert log), the origin's if it writes
  /// one. Starts the NATS side at once.
  PairMember(boost::asio::io_context& io, const NatsConfig& config, const std::string& feed_stream,
             std::uint64_t last_seq, std::uint16_t next_number, std::shared_ptr<SpeakingRight> right,
             Pipeline& pipeline, FanOut& fan_out, Hooks hooks);
  ~PairMember();

  /// An event this instance computed (after the fan-out had it).
  void own_alert(const AlertEvent& event);
  /// Called every second on the I/O thread: when active and checkpoint_interval_s has
  /// passed since the last one, a checkpoint of the pipeline after feed message
  /// `feed_position` goes to the writer, once everything before `mark()` (the alert
  /// stream's publisher's mark, NatsPublisher::mark_published) is published.
  void checkpoint_if_due(std::optional<std::uint64_t> feed_position,
                         const std::function<std::future<std::uint64_t>()>& mark);
  /// The pair's part of ?STATS "nats": checkpoints written, and whether this instance
  /// began from one.
  void report(protocol::NatsStatistics& statistics) const;
  /// Not active, and not (yet) in step: health standby_syncing.
  bool syncing() const;
  const std::string& instance() const;

 private:
  void on_origin(const PairOrigin& start, const std::shared_ptr<const PairCheckpoint>& checkpoint);
  void take_over(std::uint64_t published);
  void take_over_unsynced(std::uint64_t published);
  void apply_due_acknowledgements();
  /// Tells the lease and the log when the sync state changed.
  void judged();

  Pipeline& pipeline_;
  FanOut& fan_out_;
  Hooks hooks_;
  std::optional<StandbySync> sync_;  // from the origin on
  StandbySync::State told_ = StandbySync::State::Syncing;
  bool stopping_ = false;
  // The pair's origin (a checkpoint names the one it continues) and the checkpoints' pace.
  std::uint64_t origin_feed_seq_ = 0;
  double origin_created_unix_s_ = 0.0;
  double checkpoint_interval_s_;
  std::optional<std::chrono::steady_clock::time_point> last_checkpoint_;
  bool began_from_checkpoint_ = false;
  std::unique_ptr<HotStandby> standby_;
};

}  // namespace kew::daemon
