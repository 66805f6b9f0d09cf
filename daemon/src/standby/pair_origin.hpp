#pragma once
// Where a hot-standby pair's computation begins (design §5.9): the first message of the
// feed stream the pair judges and the numbering it started from. Every instance of the
// pair that judges the feed from this message with this numbering computes the same
// events (the pipeline is deterministic for a record order), so an instance that starts
// or restarts catches up with the active by judging the feed again from here.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace kew::daemon {

struct PairOrigin {
  /// JetStream stream sequence of the first feed message the pair judges (≥ 1).
  std::uint64_t feed_seq = 1;
  /// JetStream stream sequence of the alert stream's first message after the origin:
  /// where an instance begins following what the active published (≥ 1).
  std::uint64_t alerts_seq = 1;
  /// The numbering the pair began with: its first event gets last_seq + 1, its first
  /// alert next_number.
  std::uint64_t last_seq = 0;
  std::uint16_t next_number = 1;
  std::string created_by;  ///< the instance that wrote it (for operators)
  double created_unix_s = 0.0;

  bool operator==(const PairOrigin&) const = default;
};

/// {"feed_seq":…,"alerts_seq":…,"last_seq":…,"next_number":…,"created_by":"…","created_t":…}
std::string to_json(const PairOrigin& origin);
/// The origin of to_json's text; nullopt for anything else (a value written by another
/// program, a truncated one): the caller says so and does not guess.
std::optional<PairOrigin> pair_origin_from_json(std::string_view text);

}  // namespace kew::daemon
