#pragma once
// How records reach the pipeline in kewd (design §3.4): each is written to the record
// file, bounded by the wall clock (live mode), processed, and its batch run right after
// the handler that delivered it; a refusal is counted against the record's input, and the
// record-to-alert latency is measured from the arrival of its batch's first record.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>

#include "../http/metrics.hpp"
#include "line_file.hpp"
#include "kew/daemon/config.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"

namespace kew::daemon {

class RecordIntake {
 public:
  /// Per input: what /metrics says of it beyond its own statistics.
  struct InputFigures {
    Rejections pipeline_refused;  ///< the pipeline's refusals of its records
    std::optional<double> last_record_unix_s;
  };

  /// Opens `config.record_file` when set (throws std::exception when it cannot).
  /// `replay`: no wall-clock ceiling on data times (kewd --replay). `io` and `pipeline`
  /// outlive this.
  RecordIntake(boost::asio::io_context& io, Pipeline& pipeline, const ServiceConfig& config, bool replay,
               std::size_t inputs);

  /// A record decoded by input `input` (< inputs): what became of it.
  RecordOutcome take(const TrackReport& report, std::size_t input);
  /// Runs the pipeline's pending batch (posted after the handler that took its records;
  /// at shutdown).
  void flush();
  /// An alert event came out of the pipeline now: its latency, when a batch is running.
  void alert_emitted();
  /// The watchdog's question: no batch waits, or one ran since the last call.
  bool progressing();

  void flush_record_file() {
    if (record_file_) record_file_->flush();
  }
  /// The record file's part of ?STATS (with a record file).
  void report(protocol::ServiceStatistics& statistics) const;
  /// The record file's path, "" without one.
  std::string record_file_path() const { return record_file_ ? record_file_->path() : std::string(); }
  const InputFigures& figures(std::size_t input) const { return figures_[input]; }
  const http::LatencyHistogram& latency() const { return latency_; }

 private:
  boost::asio::io_context& io_;
  Pipeline& pipeline_;
  double max_future_s_;
  bool replay_;
  std::unique_ptr<LineFile> record_file_;
  std::vector<InputFigures> figures_;
  http::LatencyHistogram latency_;
  // The arrival of the first record of the pending batch; while a batch runs, the
  // arrival its alert events are measured from.
  std::optional<std::chrono::steady_clock::time_point> batch_arrival_;
  std::optional<std::chrono::steady_clock::time_point> running_since_;
  bool flush_posted_ = false;
  /// Batches run, and how many had run at the last progressing() call.
  std::uint64_t flushes_ = 0, flushes_at_last_check_ = 0;
  std::string line_;  // scratch
};

}  // namespace kew::daemon
