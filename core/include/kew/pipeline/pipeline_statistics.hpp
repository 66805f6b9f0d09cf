#pragma once
// The pipeline's counters (?STATS, kew-replay --stats-json, /metrics).

#include <cstdint>

namespace kew {

struct PipelineStatistics {
  std::uint64_t records = 0;            ///< records offered to process()
  std::uint64_t accepted = 0;           ///< records the track table accepted
  std::uint64_t awaiting_velocity = 0;  ///< accepted records of tracks without velocity yet
  std::uint64_t tracks_dropped = 0;     ///< tracks dropped (timeout, end of track, restart)
  std::uint64_t tracks_ended = 0;       ///< tracks the source ended (TrackReport::track_end)
  std::uint64_t runs_restarted = 0;     ///< young runs restarted elsewhere in time or space
  /// Tracks restarted because a record of the same id carried another 24-bit address (a
  /// reused track number: two addresses are never one aircraft).
  std::uint64_t tracks_restarted = 0;
  std::uint64_t probes = 0;             ///< probe runs (one per applied update)
  std::uint64_t candidates = 0;         ///< pairs evaluated, Σ over probes
  std::uint64_t zones_created = 0;      ///< zones that came into existence (traffic arrived)
  std::uint64_t zones_retired = 0;      ///< zones whose last member left
  double last_data_time = 0.0;          ///< the pipeline clock (UTC s); 0 before any record
};

}  // namespace kew
