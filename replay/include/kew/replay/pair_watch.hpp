#pragma once
// Why a pair did or did not alert (design §4.10), in words: a PairObserver of a few
// watched pairs of tracks, each within its time window. At every update of either track
// of a watched pair, it notes the first stage that kept the pair from alerting at that
// moment, with the figures the pipeline decided on, in words and units. kew-eval
// --explain watches the pairs of missed and late losses and prints what it notes.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "kew/pipeline/pair_observer.hpp"
#include "kew/util/name_table.hpp"

namespace kew::replay {

/// kew-eval's keys of the stages.
inline constexpr util::NameTable<PairStage, 13> kPairStageNames({{
    {PairStage::RecordRefused, "record_refused"},
    {PairStage::NoTrack, "no_track"},
    {PairStage::AwaitingVelocity, "awaiting_velocity"},
    {PairStage::NotCandidate, "not_candidate"},
    {PairStage::ProbeClear, "probe_clear"},
    {PairStage::SameAddress, "one_aircraft_address"},
    {PairStage::SameCode, "one_aircraft_code"},
    {PairStage::LevelPair, "level_pair"},
    {PairStage::AdjacentLevelOff, "adjacent_level_off"},
    {PairStage::Inhibited, "inhibited"},
    {PairStage::Excluded, "excluded"},
    {PairStage::ConfirmPending, "confirm_pending"},
    {PairStage::Alerting, "alerting"},
}});

/// One moment of a watched pair.
struct PairNote {
  double t = 0.0;        ///< data time of the update (UTC s)
  std::string updated;   ///< the party whose record it was ("source:id", or "id")
  PairStage stage = PairStage::NoTrack;
  /// The party the stage is about (refused, no track, no velocity, excluded); empty
  /// when it is about the pair.
  std::string subject;
  std::string detail;    ///< the figures the stage decided on, in words and units
};

/// A pair of tracks to watch from `from_t` to `to_t` (UTC s, inclusive), and what was
/// noted about it, in the order noted (data time order within a run).
struct WatchedPair {
  std::string a_source, a_id, b_source, b_id;
  double from_t = 0.0, to_t = 0.0;
  std::vector<PairNote> notes;
};

class PairWatch final : public PairObserver {
 public:
  /// Watches the pair of tracks (a_source, a_id) and (b_source, b_id) over [from_t, to_t]
  /// (UTC s); returns its index. A pair may be watched in several windows.
  std::size_t watch(std::string a_source, std::string a_id, std::string b_source, std::string b_id, double from_t,
                    double to_t);

  std::size_t size() const { return pairs_.size(); }
  const WatchedPair& pair(std::size_t index) const { return pairs_[index]; }

  bool watches(std::string_view source, std::string_view id) const override;
  std::vector<alert::PartyName> partners(std::string_view source, std::string_view id, double t) const override;
  /// Applied records date a party's last record; one without a velocity yet, and a
  /// refused one, are noted for every watched pair of the party whose window holds it.
  void record(const TrackReport& report, const RecordOutcome& outcome) override;
  /// Notes the observation, in words, for every watched pair of its two tracks whose
  /// window holds it.
  void pair_judged(const PairObservation& observation) override;

 private:
  static std::string key(std::string_view source, std::string_view id);
  /// The time of the last applied record of the track, if any.
  std::optional<double> last_seen(std::string_view source, std::string_view id) const;
  /// Notes `note` for every watched pair with the track (source, id) as a party whose
  /// window holds note.t.
  void note_track(std::string_view source, std::string_view id, const PairNote& note);

  std::vector<WatchedPair> pairs_;
  std::unordered_set<std::string> parties_;  // key() of every party
  std::unordered_map<std::string, double> last_seen_;
};

/// "source:id", or "id" when the source is empty: how notes and kew-eval name a party.
std::string party_label(std::string_view source, std::string_view id);

}  // namespace kew::replay
