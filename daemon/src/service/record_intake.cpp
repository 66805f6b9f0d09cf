#include "record_intake.hpp"

#include <boost/asio/post.hpp>

#include "test_hooks.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/util/clocks.hpp"

namespace kew::daemon {

RecordIntake::RecordIntake(boost::asio::io_context& io, Pipeline& pipeline, const ServiceConfig& config, bool replay,
                           std::size_t inputs)
    : io_(io), pipeline_(pipeline), max_future_s_(config.max_future_s), replay_(replay), figures_(inputs) {
  if (!config.record_file.empty())
    record_file_ = std::make_unique<LineFile>(config.record_file, 0, 0, false, config.record_file_queue_bytes);
}

RecordOutcome RecordIntake::take(const TrackReport& report, std::size_t input) {
  const auto arrival = std::chrono::steady_clock::now();
  if (record_file_) {
    line_.clear();
    protocol::append_ndjson(line_, report);
    line_ += '\n';  // a recording is NDJSON: one record per line, as kew-replay reads it
    record_file_->append(line_);
  }
  // No record may carry the clock past the wall clock (a host synchronised by NTP is the
  // best time kewd has; recordings played into a live input are in the past). A replay
  // has no such ceiling: its clock is the recording's, and the pipeline's time guard
  // still holds a lone record dated ahead of the others, as in kew-replay.
  const double wall = util::unix_now_s();
  if (!replay_) pipeline_.set_time_ceiling(wall + max_future_s_);
  InputFigures& figures = figures_[input];
  figures.last_record_unix_s = wall;
  // Events come out when the batch runs: at once for the first records after a batch
  // (prompt_records), when this record fills it, or right after the handler that
  // delivered the records (a datagram, a read, a replay step) returns.
  if (!batch_arrival_) batch_arrival_ = arrival;
  running_since_ = batch_arrival_;
  const RecordOutcome outcome = pipeline_.process(report);
  running_since_.reset();
  if (!pipeline_.batch_waiting()) batch_arrival_.reset();
  if (!flush_posted_) {
    flush_posted_ = true;
    boost::asio::post(io_, [this] { flush(); });
  }
  if (outcome.kind == RecordOutcome::Kind::Refused)
    figures.pipeline_refused.reject(track::kRefusalNames.name(outcome.refusal));
  return outcome;
}

void RecordIntake::flush() {
  test_hooks::maybe_stall_pipeline();
  ++flushes_;
  flush_posted_ = false;
  // The record-to-alert latency of a batch counts from its first record's arrival.
  running_since_ = batch_arrival_;
  pipeline_.flush();
  running_since_.reset();
  batch_arrival_.reset();
}

void RecordIntake::report(protocol::ServiceStatistics& statistics) const {
  if (!record_file_) return;
  statistics.record_file_queued_bytes = record_file_->pending_bytes();
  statistics.record_file_dropped = record_file_->dropped_lines();
}

void RecordIntake::alert_emitted() {
  if (running_since_)
    latency_.observe(std::chrono::duration<double>(std::chrono::steady_clock::now() - *running_since_).count());
}

bool RecordIntake::progressing() {
  if (flush_posted_ && flushes_ == flushes_at_last_check_) return false;
  flushes_at_last_check_ = flushes_;
  return true;
}

}  // namespace kew::daemon
