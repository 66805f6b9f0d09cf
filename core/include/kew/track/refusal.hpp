#pragma once
// Why the track stage refuses a record (design §4.3): one enum, one name table. The names
// are the keys counted in Rejections, printed in ?STATS and /metrics and read by kew-eval.

#include <cstdint>

#include "kew/util/name_table.hpp"

namespace kew::track {

enum class Refusal : std::uint8_t {
  None,                  ///< not refused
  EmptyId,               ///< the record names no track
  IdTooLong,             ///< id or source longer than max_id_bytes
  TimeNotFinite,
  PositionNotFinite,
  LatitudeOutOfRange,
  LongitudeOutOfRange,
  AltitudeMissing,
  AltitudeNotFinite,
  AltitudeOutOfRange,    ///< outside [min_altitude_ft, max_altitude_ft]
  OnGround,              ///< on the ground, and exclude_on_ground
  TooLate,               ///< older than the clock less max_lateness_s
  OutOfOrder,            ///< older than its track's last record
  DuplicateTime,         ///< the same time as its track's last record
  TrackLimit,            ///< a new track beyond max_tracks
  OutsideCoverage,       ///< beyond the coverage limit or the plane
  FutureTime,            ///< later than the time ceiling, or a jump nothing confirmed
};
inline constexpr util::NameTable<Refusal, 17> kRefusalNames({{
    {Refusal::None, "none"},
    {Refusal::EmptyId, "empty_id"},
    {Refusal::IdTooLong, "id_too_long"},
    {Refusal::TimeNotFinite, "time_not_finite"},
    {Refusal::PositionNotFinite, "position_not_finite"},
    {Refusal::LatitudeOutOfRange, "latitude_out_of_range"},
    {Refusal::LongitudeOutOfRange, "longitude_out_of_range"},
    {Refusal::AltitudeMissing, "altitude_missing"},
    {Refusal::AltitudeNotFinite, "altitude_not_finite"},
    {Refusal::AltitudeOutOfRange, "altitude_out_of_range"},
    {Refusal::OnGround, "on_ground"},
    {Refusal::TooLate, "too_late"},
    {Refusal::OutOfOrder, "out_of_order"},
    {Refusal::DuplicateTime, "duplicate_time"},
    {Refusal::TrackLimit, "track_limit"},
    {Refusal::OutsideCoverage, "outside_coverage"},
    {Refusal::FutureTime, "future_time"},
}});

}  // namespace kew::track
