#pragma once
// Why a pair did or did not alert (design §4.10): a diagnostic the alert stage fills for
// a few watched pairs of tracks. At every update of either track of a watched pair
// within its time window, the pipeline notes the first stage that kept the pair from
// alerting at that moment, with the figures it decided on. kew-eval --explain watches
// the pairs of missed and late losses and prints what it notes.
//
// Notes are written only for watched pairs, from the alert stage's own view of the
// tracks, so a watch changes no alert and costs nothing when empty.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "kew/util/name_table.hpp"

namespace kew {

/// Where a pair stood at one update, in the order the pipeline decides: the first stage
/// that holds it back (or Alerting). Names are kew-eval's keys.
enum class PairStage : std::uint8_t {
  RecordRefused,     ///< a record of a party was refused (the reason in the detail)
  NoTrack,           ///< a party has no track: no record yet, or dropped (timeout, ended)
  AwaitingVelocity,  ///< a party is known but has no velocity yet (one record)
  NotCandidate,      ///< the pair is in conflict but the candidate search did not give it,
                     ///< or no zone holds both aircraft
  ProbeClear,        ///< the conflict test finds no conflict within the look-ahead
  SameAddress,       ///< one aircraft: both tracks carry one 24-bit address
  SameCode,          ///< one aircraft: one discrete code on coinciding tracks (design §4.5)
  LevelPair,         ///< two level aircraft at adjacent levels
  AdjacentLevelOff,  ///< a climb or descent presumed to level off beside a level aircraft
  Inhibited,         ///< a party in an inhibition volume
  Excluded,          ///< a party may not open an alert (the rule and its value)
  ConfirmPending,    ///< in conflict, fewer than `confirm` evaluations in a row yet
  Alerting,          ///< the pair's alert is open
};
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

class PairWatch {
 public:
  /// Watches the pair of tracks (a_source, a_id) and (b_source, b_id) over [from_t, to_t]
  /// (UTC s); returns its index. A pair may be watched in several windows.
  std::size_t watch(std::string a_source, std::string a_id, std::string b_source, std::string b_id, double from_t,
                    double to_t);

  std::size_t size() const { return pairs_.size(); }
  const WatchedPair& pair(std::size_t index) const { return pairs_[index]; }

  /// Whether any watched pair has the track (source, id) as a party.
  bool watches(std::string_view source, std::string_view id) const;

  /// Calls f(WatchedPair&, partner_source, partner_id) for every watched pair with the
  /// track (source, id) as a party whose window holds t.
  template <class F>
  void for_each_partner(std::string_view source, std::string_view id, double t, F&& f) {
    for (WatchedPair& p : pairs_) {
      if (t < p.from_t || t > p.to_t) continue;
      if (p.a_source == source && p.a_id == id) f(p, std::string_view(p.b_source), std::string_view(p.b_id));
      if (p.b_source == source && p.b_id == id) f(p, std::string_view(p.a_source), std::string_view(p.a_id));
    }
  }

  /// The track (source, id) had a record at t (UTC s) that reached its track.
  void seen(std::string_view source, std::string_view id, double t);
  /// The time of the last record seen() of the track, if any.
  std::optional<double> last_seen(std::string_view source, std::string_view id) const;

  /// Notes `note` for every watched pair with the track (source, id) as a party whose
  /// window holds note.t (records refused, tracks without velocity: what happens before
  /// the alert stage).
  void note_track(std::string_view source, std::string_view id, const PairNote& note);

 private:
  static std::string key(std::string_view source, std::string_view id);

  std::vector<WatchedPair> pairs_;
  std::unordered_set<std::string> parties_;  // key() of every party
  std::unordered_map<std::string, double> last_seen_;
};

/// "source:id", or "id" when the source is empty: how notes and kew-eval name a party.
std::string party_label(std::string_view source, std::string_view id);

}  // namespace kew
