#pragma once
// What became of one record offered to Pipeline::process().

#include <cstdint>

#include "kew/track/refusal.hpp"
#include "kew/track/track_table.hpp"
#include "kew/util/name_table.hpp"

namespace kew {

struct RecordOutcome {
  enum class Kind : std::uint8_t {
    Accepted,          ///< applied: the track has kinematics at the record's time
    AwaitingVelocity,  ///< applied: position stored, no velocity yet
    Held,              ///< ahead of the clock: held by the time guard, applied or refused later
    Refused,           ///< counted in Pipeline::rejections() under `refusal`
  };
  Kind kind = Kind::Refused;
  track::Refusal refusal = track::Refusal::None;  ///< Refused: why
  /// Accepted, AwaitingVelocity: the record's track (it may have ended with the record,
  /// TrackReport::track_end); kNoTrack otherwise.
  track::TrackSlot slot = track::kNoTrack;

  bool applied() const { return kind == Kind::Accepted || kind == Kind::AwaitingVelocity; }
};
inline constexpr util::NameTable<RecordOutcome::Kind, 4> kRecordOutcomeNames({{
    {RecordOutcome::Kind::Accepted, "accepted"},
    {RecordOutcome::Kind::AwaitingVelocity, "awaiting_velocity"},
    {RecordOutcome::Kind::Held, "held"},
    {RecordOutcome::Kind::Refused, "refused"},
}});

}  // namespace kew
