#include "pair_member.hpp"

#include <algorithm>

#include <spdlog/spdlog.h>

#include "kew/util/clocks.hpp"

namespace kew::daemon {

std::string pair_feed_stream(const std::vector<InputConfig>& inputs) {
  if (inputs.size() != 1) return {};
  const InputConfig& feed = inputs.front();
  return feed.transport == Transport::Nats && !feed.durable.empty() ? feed.stream : std::string();
}

bool pair_feed_checkpointable(const std::vector<InputConfig>& inputs) {
  if (pair_feed_stream(inputs).empty()) return false;
  const protocol::Format format = inputs.front().format;
  return format == protocol::Format::Ndjson || format == protocol::Format::ReadsbJson;
}

std::function<bool(const std::string& state, std::string& why)> checkpoint_fits(PipelineConfig config) {
  return [config = std::move(config)](const std::string& state, std::string& why) {
    try {
      Pipeline trial(config);
      trial.restore(state);
      return true;
    } catch (const std::exception& e) {
      why = e.what();
      return false;
    }
  };
}

PairMember::PairMember(boost::asio::io_context& io, const NatsConfig& config, const std::string& feed_stream,
                       std::uint64_t last_seq, std::uint16_t next_number, std::shared_ptr<SpeakingRight> right,
                       Pipeline& pipeline, FanOut& fan_out, Hooks hooks)
    : pipeline_(pipeline),
      fan_out_(fan_out),
      hooks_(std::move(hooks)),
      checkpoint_interval_s_(config.checkpoint_interval_s) {
  if (feed_stream.empty())
    spdlog::warn("hot standby without one durable NATS feed ([[input]] transport \"nats\" with durable and stream, "
                 "and no other input): an instance that starts after the active cannot catch up with it exactly");
  HotStandby::Handlers handlers;
  handlers.on_origin = [this](const PairOrigin& start, std::shared_ptr<const PairCheckpoint> checkpoint) {
    on_origin(start, checkpoint);
  };
  handlers.usable = hooks_.usable;
  handlers.on_acquired = [this](std::uint64_t published) { take_over(published); };
  handlers.on_lost = [this] { fan_out_.step_down(); };
  handlers.on_active_alert = [this](const AlertEvent& event) {
    if (!sync_) return;
    sync_->active_alert(event);
    judged();
  };
  handlers.on_active_acknowledgement = [this](std::uint64_t seq, std::vector<std::string> ids) {
    if (!sync_) return;
    sync_->active_acknowledgement(seq, std::move(ids));
    apply_due_acknowledgements();
  };
  handlers.on_stream_read_up_to = [this](std::uint64_t seq) {
    if (!sync_) return;
    sync_->stream_read_up_to(seq);
    judged();
  };
  standby_ = std::make_unique<HotStandby>(io, config, feed_stream, last_seq, next_number, std::move(handlers),
                                          std::move(right));
}

PairMember::~PairMember() {
  stopping_ = true;
  standby_.reset();
}

bool PairMember::syncing() const { return !fan_out_.active() && !(sync_ && sync_->in_step()); }

const std::string& PairMember::instance() const { return standby_->instance(); }

void PairMember::on_origin(const PairOrigin& start, const std::shared_ptr<const PairCheckpoint>& checkpoint) {
  if (stopping_ || sync_) return;
  origin_feed_seq_ = checkpoint ? checkpoint->origin_feed_seq : start.feed_seq;
  origin_created_unix_s_ = start.created_unix_s;
  began_from_checkpoint_ = checkpoint != nullptr;
  sync_.emplace(start.last_seq);
  hooks_.begin(start, checkpoint.get());
  // The active's alerts open at the checkpoint are in its state, not in the stream read.
  if (checkpoint) sync_->seed_open(pipeline_.alerts().snapshot());
  standby_->set_origin_known();
  judged();
}

void PairMember::report(protocol::NatsStatistics& statistics) const {
  statistics.checkpoints_written = standby_->checkpoints_written();
  statistics.began_from_checkpoint = began_from_checkpoint_;
}

void PairMember::checkpoint_if_due(std::optional<std::uint64_t> feed_position,
                                   const std::function<std::future<std::uint64_t>()>& mark) {
  if (checkpoint_interval_s_ <= 0 || !hooks_.usable || !sync_ || !fan_out_.active() || !feed_position) return;
  const auto now = std::chrono::steady_clock::now();
  if (last_checkpoint_ && now - *last_checkpoint_ < std::chrono::duration<double>(checkpoint_interval_s_)) return;
  // Nullopt while the time guard holds records: a second later, most likely not.
  std::optional<std::string> state = pipeline_.checkpoint();
  if (!state) return;
  PairCheckpoint checkpoint;
  checkpoint.origin_feed_seq = origin_feed_seq_;
  checkpoint.origin_created_unix_s = origin_created_unix_s_;
  checkpoint.feed_seq = *feed_position;
  checkpoint.last_seq = pipeline_.alerts().last_seq();
  checkpoint.written_by = instance();
  checkpoint.written_unix_s = util::unix_now_s();
  checkpoint.pipeline = std::move(*state);
  if (standby_->write_checkpoint(std::move(checkpoint), mark())) last_checkpoint_ = now;
}

void PairMember::own_alert(const AlertEvent& event) {
  if (!sync_) return;
  sync_->own_alert(event);
  apply_due_acknowledgements();
  judged();
}

void PairMember::apply_due_acknowledgements() {
  std::size_t applied = 0;
  for (const std::vector<std::string>& ids : sync_->due_acknowledgements()) {
    if (fan_out_.active()) continue;  // its own, applied when they were made
    for (const std::string& id : ids) applied += pipeline_.alerts().acknowledge(id).size();
  }
  if (!applied) return;
  spdlog::info("standby: {} alerts acknowledged on the active", applied);
  if (hooks_.acknowledged) hooks_.acknowledged();
}

void PairMember::judged() {
  const StandbySync::State now = sync_->state();
  if (now == told_) return;
  told_ = now;
  standby_->set_in_step(now == StandbySync::State::InStep);
  if (now == StandbySync::State::InStep)
    spdlog::info("{}: in step with the active at seq {}: may take over", instance(), sync_->own_seq());
  else if (now == StandbySync::State::OutOfStep)
    spdlog::error("{}: out of step with the active: {}; it takes over only when no instance in step is left",
                  instance(), sync_->departure());
}

void PairMember::take_over(std::uint64_t published) {
  if (stopping_ || fan_out_.active()) return;
  if (!sync_ || !sync_->in_step()) {
    take_over_unsynced(published);
    return;
  }
  const std::size_t sent = fan_out_.take_over(published, pipeline_.alerts().snapshot(), pipeline_.alerts().last_seq());
  spdlog::warn("active now (hot standby {}): the previous active published up to seq {}; {} later events sent, "
               "{} alerts open",
               instance(), published, sent, pipeline_.alerts().active_count());
}

void PairMember::take_over_unsynced(std::uint64_t published) {
  // Nothing this instance kept continues the stream: its numbering starts above both.
  alert::AlertManager& alerts = pipeline_.alerts();
  std::uint64_t seq = std::max(published, alerts.last_seq());
  const std::vector<AlertEvent> theirs = sync_ ? sync_->open_on_active() : std::vector<AlertEvent>{};
  std::vector<std::string> only_mine;
  for (const AlertEvent& mine : alerts.snapshot()) only_mine.push_back(mine.id);
  std::vector<AlertEvent> to_end;
  for (const AlertEvent& event : theirs) {
    const auto same = std::find(only_mine.begin(), only_mine.end(), event.id);
    // The same alert (its id names the pair and its opening) is continued.
    if (same != only_mine.end()) only_mine.erase(same);
    else to_end.push_back(event);
  }
  // Alerts only this instance had were never sent: their next event would be an update
  // nobody saw open. They open again, under new ids, if their pairs stay in conflict.
  std::size_t forgotten = 0;
  for (const std::string& id : only_mine) forgotten += alerts.forget(id) ? 1 : 0;
  fan_out_.take_over(seq, alerts.snapshot(), seq);
  for (AlertEvent event : to_end) {
    event.state = AlertState::End;
    event.end_reason = AlertEndReason::TakeoverUnsynced;
    event.seq = ++seq;
    hooks_.emit(event);
  }
  alerts.resume(seq, alerts.next_number());
  const std::size_t ended = to_end.size();
  spdlog::error("active now (hot standby {}), unsynced: the previous active published up to seq {}; {} of its "
                "alerts ended (takeover_unsynced), {} of this instance's own not sent (they open again if their "
                "conflicts last)",
                instance(), published, ended, forgotten);
}

}  // namespace kew::daemon
