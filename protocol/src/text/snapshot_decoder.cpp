#include "snapshot_decoder.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace kew::protocol::text {

// The smallest snapshot limit: room for an empty one and a message.
constexpr std::size_t kMinSnapshotBytes = 64;

SnapshotDecoder::SnapshotDecoder(std::string what, std::size_t max_snapshot_bytes, Memory memory)
    : max_bytes_(std::max(max_snapshot_bytes, kMinSnapshotBytes)),
      memory_(memory),
      cutter_(std::move(what), max_bytes_),
      json_(0) {}

void SnapshotDecoder::feed(std::span<const std::byte> bytes, const ReportSink& sink) {
  cutter_.feed(
      bytes, [&](std::string_view snapshot) { decode(snapshot, sink); },
      [&](std::string_view reason, std::string message) { rejections().reject(reason, message); });
}

void SnapshotDecoder::finish(const ReportSink& sink) {
  end_message(sink);
  last_reported_.clear();
  newest_time_ = -std::numeric_limits<double>::infinity();
}

void SnapshotDecoder::end_message(const ReportSink& /*sink*/) {
  const std::uint64_t snapshot = cutter_.object_number();
  if (cutter_.finish())
    rejections().reject("truncated", fmt::format("{} {}: cut by the end of the stream", cutter_.what(), snapshot));
}

void SnapshotDecoder::refuse(std::string_view where, const LineProblem& problem) {
  rejections().reject(problem.reason, fmt::format("{}: {}: {}", where, problem.reason, problem.detail));
}

void SnapshotDecoder::decode(std::string_view text, const ReportSink& sink) {
  ready_.clear();
  const std::optional<double> time =
      decode_snapshot(text, fmt::format("{} {}", cutter_.what(), cutter_.object_number()));
  std::stable_sort(ready_.begin(), ready_.end(), [](const TrackReport& a, const TrackReport& b) { return a.t < b.t; });
  for (const TrackReport& report : ready_) sink(report);
  if (!time) return;
  // A snapshot older than one read before (a history read out of order) forgets nothing.
  newest_time_ = std::max(newest_time_, *time);
  const double forget_before = newest_time_ - memory_.forget_after_s;
  std::erase_if(last_reported_, [forget_before](const auto& e) { return e.second < forget_before; });
}

LineResult SnapshotDecoder::offer(TrackReport& report) {
  std::uint32_t key = 0;
  if (!parse_address(report.id, key_id_, key)) return problem("bad_address", fmt::format("\"{}\"", report.id));
  const auto reported = last_reported_.find(key);
  if (reported != last_reported_.end() && report.t <= reported->second + memory_.same_position_s) return std::nullopt;
  if (LineResult bad = check_report(report)) return bad;
  last_reported_[key] = report.t;
  ready_.push_back(std::move(report));
  return std::nullopt;
}

}  // namespace kew::protocol::text
