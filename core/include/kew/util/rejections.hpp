#pragma once
// Counting and rate-limited reporting of rejected input (design §6.3).
// Every stage that refuses data (decoders, the track table) owns one of these; the
// program that runs the stage decides where the messages go.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "kew/util/checkpoint_io.hpp"

namespace kew {

class Rejections {
 public:
  /// Receives a human-readable message for a rejection that passed the rate limit.
  using Reporter = std::function<void(std::string_view reason, std::string_view message)>;

  /// Messages of one reason are reported for its first `burst` occurrences, then only
  /// for occurrences number 2·burst, 4·burst, 8·burst, ... so a flood stays readable.
  explicit Rejections(std::uint64_t burst = 10) : burst_(burst) {}

  void set_reporter(Reporter reporter) { reporter_ = std::move(reporter); }

  /// Counts one rejection of `reason` (a short stable snake_case key such as
  /// "bad_json" or "lat_out_of_range") and reports `message` when the rate limit allows.
  void reject(std::string_view reason, std::string_view message = {});

  /// Rejections of `reason` so far.
  std::uint64_t count(std::string_view reason) const;
  /// The reason of the latest reject() call ("" before the first): lets a caller that
  /// feeds one stage from several sources count each source's refusals.
  std::string_view last_reason() const { return last_; }
  /// All rejections so far, across reasons.
  std::uint64_t total() const { return total_; }
  /// Reason → count, in reason order (deterministic for statistics output).
  const std::map<std::string, std::uint64_t, std::less<>>& by_reason() const { return counts_; }

  /// Adds another counter's figures into this one (e.g. per-connection decoders into
  /// an input's total).
  void merge(const Rejections& other);

  /// The counts, for a checkpoint (design §5.9); restore() replaces them (the reporter
  /// and its rate limit stay this object's).
  void save(util::CheckpointWriter& out) const;
  void restore(util::CheckpointReader& in);

 private:
  std::uint64_t burst_;
  std::uint64_t total_ = 0;
  std::map<std::string, std::uint64_t, std::less<>> counts_;
  Reporter reporter_;
  std::string last_;  // assigned, so its capacity is reused
};

}  // namespace kew
