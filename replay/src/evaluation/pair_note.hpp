#pragma once
// What the pipeline reports about a watched pair (kew/pipeline/pair_observer.hpp), in
// words and units: the detail of a PairNote, as kew-eval --explain prints it.

#include <optional>

#include "kew/pipeline/pair_observer.hpp"
#include "kew/replay/pair_watch.hpp"

namespace kew::replay {

/// The note of where a watched pair stands. `partner_last_seen`: the data time (UTC s)
/// of the partner's last applied record, if any, which dates a NoTrack partner's drop.
PairNote note_of(const PairObservation& observation, std::optional<double> partner_last_seen);

/// The note of a watched track's record that holds its pairs back: one without a
/// velocity yet (AwaitingVelocity) or refused (RecordRefused). Other outcomes hold
/// nothing back: none.
std::optional<PairNote> note_of(const TrackReport& report, const RecordOutcome& outcome);

}  // namespace kew::replay
