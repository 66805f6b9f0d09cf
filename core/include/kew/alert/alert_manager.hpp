#pragma once
// Alert lifecycle (design §4.7): a pair's alert opens after `confirm` consecutive
// conflicting evaluations, is updated when its severity or figures change materially,
// and ends after `clear` consecutive clear evaluations or when one of its tracks is
// dropped. Ids are derived from the pair and the opening data time; every emitted event
// gets the next sequence number. Pairs are identified by the track table's slots.
// An area proximity warning (design §4.11) is the alert of a track and a volume,
// identified by the track's slot and the volume's index, under the same rules, numbers
// and sequence.

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "kew/alert/alert_event.hpp"
#include "kew/util/checkpoint_io.hpp"

namespace kew::alert {

using Slot = std::uint32_t;

struct AlertConfig {
  int confirm = 2;  ///< consecutive conflicting evaluations to open (≥ 1)
  /// Consecutive clear evaluations to end (≥ 1). 4, not 2: a pair whose prediction
  /// hovers at the minima otherwise ends and reopens every few seconds (design §8.6).
  int clear = 4;
  double warning_s = 60.0;  ///< t_los at or below this is a warning (s)
  /// An active alert is re-emitted (state "update") when its severity changes or when a
  /// figure moved by at least this much from the last emitted event (t_los compared
  /// after ageing the old one by the elapsed time).
  double update_t_los_s = 5.0;
  double update_cpa_h_m = 185.2;   ///< 0.1 NM
  double update_cpa_v_ft = 100.0;
};

/// The outcome of one pair evaluation, as the manager needs it. The figures decide
/// whether an active alert is re-emitted; they may be approximations of the reported
/// ones (the probe gives plane figures corrected by the projection scale) so that the
/// exact figures are computed only for events actually emitted.
struct Evaluation {
  bool in_conflict = false;
  Severity severity = Severity::None;  ///< meaningful when in_conflict
  double t_los_s = 0.0;
  double cpa_h_m = 0.0;
  double cpa_v_ft = 0.0;
  /// The pair's own confirm and clear counts (a parameter region's, design §4.8); 0: the
  /// manager's configuration.
  int confirm = 0;
  int clear = 0;
  /// Data time of the record behind this evaluation (UTC s): its own time, also when it
  /// came late and is judged at the clock. Evaluations of one observed time are one look
  /// at the pair and count once towards confirm and clear; NaN: the evaluation's time.
  double observed_t = std::numeric_limits<double>::quiet_NaN();
};

/// How the track in a slot is named: the `source` and `id` of its AlertParty. Views stay
/// valid while the slot has a pair in the manager.
struct PartyName {
  std::string_view source;
  std::string_view id;
};

class AlertManager {
 public:
  /// `names(slot)` must give the source and id that `build` (see evaluate) puts in the
  /// party of that slot, as long as the slot has a pending or active pair: the manager
  /// keeps only the numbers of each alert's last event and takes the names from there
  /// for End events and snapshots (a stack alerts ten partners per aircraft; copying the
  /// strings into every alert doubled its size).
  using PartyNames = std::function<PartyName(Slot)>;
  AlertManager(const AlertConfig& config, PartyNames names);

  /// Severity of a conflict from its geometry (loss now / t_los ≤ warning_s / later);
  /// `warning_s` < 0: the configuration's.
  Severity classify(bool lost_now, double t_los_s, double warning_s = -1.0) const;

  /// Records one evaluation of pair {p, q} at data time t. When an event is emitted,
  /// `build(AlertEvent&)` is called first to fill parties and figures (severity, ids,
  /// numbers, state and sequence are the manager's), and the event is appended to `out`.
  template <class Build>
  void evaluate(Slot p, Slot q, const Evaluation& e, double t, Build&& build, std::vector<AlertEvent>& out) {
    judge(pair_key(p, q), e, t, build, out);
  }
  /// Records one evaluation of the track in `slot` against volume `volume` (< 2^31): as
  /// evaluate(), for the alert of kind Apw, whose `build` fills a, the figures and the
  /// volume's name and kind.
  template <class Build>
  void evaluate_area(Slot slot, std::uint32_t volume, const Evaluation& e, double t, Build&& build,
                     std::vector<AlertEvent>& out) {
    judge(area_key(slot, volume), e, t, build, out);
  }

  /// Ends every alert of the track in `slot`, its pairs' then its volumes' (reason
  /// TrackDropped), and forgets them.
  void drop_track(Slot slot, double t, std::vector<AlertEvent>& out);
  /// Ends every alert about volume `volume` (reason TrackDropped: a volume that follows
  /// an aircraft goes with its track) and forgets them.
  void drop_volume(std::uint32_t volume, double t, std::vector<AlertEvent>& out);

  /// Slots paired with `slot` in some state (pending confirmation or active), appended
  /// to `out`. The probe evaluates them even when the candidate search does not return
  /// them, so pending and active pairs always see their clear evaluations.
  void partners_of(Slot slot, std::vector<Slot>& out) const;
  /// The same for the volumes of the track in `slot`.
  void volumes_of(Slot slot, std::vector<std::uint32_t>& out) const;

  /// Whether pair {p, q} has an open alert (rules that only stop alerts from opening
  /// leave an open one to its own end).
  bool is_active(Slot p, Slot q) const { return is_active_key(pair_key(p, q)); }
  /// Whether the track in `slot` has an open alert about volume `volume`.
  bool is_area_active(Slot slot, std::uint32_t volume) const { return is_active_key(area_key(slot, volume)); }

 private:
  template <class Build>
  void judge(std::uint64_t key, const Evaluation& e, double t, Build&& build, std::vector<AlertEvent>& out) {
    auto it = pairs_.find(key);
    if (!e.in_conflict) {
      if (it != pairs_.end()) record_clear(it, t, look_time(e, t), e.clear > 0 ? e.clear : config_.clear, out);
      return;
    }
    if (it == pairs_.end()) it = create(key);
    PairState& s = it->second;
    s.clears_in_row = 0;
    if (counts(s, look_time(e, t)) && s.conflicts_in_row < 0x7fffffff) ++s.conflicts_in_row;
    if (!s.active && s.conflicts_in_row < (e.confirm > 0 ? e.confirm : config_.confirm)) return;
    if (s.active && !changed(s, e, t)) return;
    AlertEvent event;
    build(event);
    event.severity = e.severity;
    event.t = t;
    s.decided = {e.t_los_s, e.cpa_h_m, e.cpa_v_ft};
    if (!s.active) open(s, std::move(event), out);
    else update(s, std::move(event), out);
  }
  bool is_active_key(std::uint64_t key) const {
    const auto it = pairs_.find(key);
    return it != pairs_.end() && it->second.active;
  }

 public:

  /// Forgets the active alert `id` without an event: nobody outside knows it (a
  /// hot-standby instance out of step computed it, and it takes over unsynced). The pair
  /// starts afresh: if it stays in conflict, a new alert opens after `confirm`
  /// evaluations. False when no active alert has that id.
  bool forget(std::string_view id);

  /// Active alerts (their last emitted event), ordered by opening sequence.
  std::vector<AlertEvent> snapshot() const;
  std::size_t active_count() const { return active_; }
  /// Highest severity among active alerts (None when there is none).
  Severity highest_severity() const;

  /// Marks every active alert acknowledged (Modbus coil 0) and returns the ids of those
  /// that were not yet, in alert-number order. An alert whose severity later rises
  /// becomes unacknowledged again.
  std::vector<std::string> acknowledge_all();
  /// Marks the active alert `id` acknowledged (the map's button); returns {id} when it
  /// was active and not yet acknowledged, else nothing.
  std::vector<std::string> acknowledge(std::string_view id);
  std::size_t unacknowledged_count() const;

  struct Counters {
    std::uint64_t opened = 0, updated = 0, ended = 0;
  };
  const Counters& counters() const { return counters_; }
  std::uint64_t last_seq() const { return seq_; }
  /// The number the next alert to open will get.
  std::uint16_t next_number() const { return next_number_; }

  /// Continues a numbering begun elsewhere (kewd after a restart, design §4.7): the next
  /// event gets `last_seq` + 1 and the next alert opened `next_number` (0 reads as 1).
  /// Call before the first evaluation, or after events emitted outside the manager (a
  /// hot-standby takeover's); without it, seq and number start at 1, as kew-replay's
  /// deterministic output needs.
  void resume(std::uint64_t last_seq, std::uint16_t next_number) {
    seq_ = last_seq;
    next_number_ = next_number == 0 ? 1 : next_number;
  }
  const AlertConfig& config() const { return config_; }

  /// The manager's whole state, for a checkpoint (design §5.9): restore() into a manager
  /// made with the same AlertConfig and party names continues exactly as this one would.
  void save(util::CheckpointWriter& out) const;
  /// Replaces this manager's state by one save() wrote. Throws util::CheckpointError when
  /// it cannot be read; the manager is then left empty, numbering from the start.
  void restore(util::CheckpointReader& in);

 private:
  /// What an active alert keeps of one party of its last event: the numbers and the
  /// callsign (it may change during a track's life), not the source and id.
  struct PartyFigures {
    double lat_deg = 0.0, lon_deg = 0.0, alt_ft = 0.0, gs_kt = 0.0, trk_deg = 0.0, vr_fpm = 0.0;
    std::string callsign;
    std::uint16_t track_number = 0;
  };
  /// An active alert's last emitted event without the parties' names.
  struct LastEvent {
    std::uint64_t id_hash = 0;  // AlertEvent::id in hex
    std::uint64_t seq = 0;
    double t = 0.0, opened_t = 0.0;
    double t_los_s = 0.0, t_cpa_s = 0.0, cpa_h_m = 0.0, cpa_v_ft = 0.0, sep_h_m = 0.0, sep_v_ft = 0.0;
    PartyFigures lo, hi;  // parties of the lower and the higher slot
    std::uint16_t number = 0;
    AlertState state = AlertState::New;
    Severity severity = Severity::None;
    Hypothesis hypothesis = Hypothesis::Linear;
    std::string region;
    std::string volume, volume_kind;  // Apw
    bool acknowledged = false;
    bool lo_is_a = true;  // the lower slot's track is AlertEvent::a
  };
  /// The figures of the evaluation behind the last event, which decide re-emission
  /// (its severity and time are the last event's).
  struct DecidedFigures {
    double t_los_s = 0.0, cpa_h_m = 0.0, cpa_v_ft = 0.0;
  };
  /// A pair of tracks (lo < hi, slots), or a track and a volume (area: lo the track's
  /// slot, hi the volume's index).
  struct PairState {
    Slot lo = 0, hi = 0;
    bool area = false;
    int conflicts_in_row = 0;
    int clears_in_row = 0;
    /// Observed time of the pair's last counted evaluation: evaluations of one observed
    /// time (both parties' records of one radar scan or system-track frame) count once.
    double counted_t = -1e300;
    bool active = false;
    std::uint64_t opened_seq = 0;
    LastEvent last;  // while active
    DecidedFigures decided;
  };
  using Pairs = std::unordered_map<std::uint64_t, PairState>;

  static std::uint64_t pair_key(Slot p, Slot q) {
    const Slot lo = p < q ? p : q, hi = p < q ? q : p;
    return (std::uint64_t{lo} << 32) | hi;
  }
  /// An area's key has the top bit set (a pair's lower slot is below 2^31), then the
  /// track's slot and the volume's index in the low 31 bits.
  static constexpr std::uint64_t kAreaBit = std::uint64_t{1} << 63;
  static std::uint64_t area_key(Slot slot, std::uint32_t volume) {
    return kAreaBit | (std::uint64_t{slot} << 31) | (volume & 0x7fffffffu);
  }
  static PairState state_of_key(std::uint64_t key);
  /// The observed time an evaluation counts under (Evaluation::observed_t, else t).
  static double look_time(const Evaluation& e, double t) { return e.observed_t == e.observed_t ? e.observed_t : t; }
  /// Whether an evaluation of observed time t counts towards confirm or clear: the first
  /// of each observed time does (design §4.7); it is remembered.
  static bool counts(PairState& s, double t) {
    if (t <= s.counted_t) return false;
    s.counted_t = t;
    return true;
  }
  Pairs::iterator create(std::uint64_t key);
  void forget(Pairs::iterator it);
  /// Ends (TrackDropped) and forgets the alerts of `keys`, in key order.
  void end_and_forget(std::vector<std::uint64_t>& keys, double t, std::vector<AlertEvent>& out);
  void record_clear(Pairs::iterator it, double t, double look_t, int clear, std::vector<AlertEvent>& out);
  bool changed(const PairState& s, const Evaluation& e, double t) const;
  void open(PairState& s, AlertEvent&& event, std::vector<AlertEvent>& out);
  void update(PairState& s, AlertEvent&& event, std::vector<AlertEvent>& out);
  /// Emits the End event; the caller forgets the pair right after.
  void end(PairState& s, double t, AlertEndReason reason, std::vector<AlertEvent>& out);
  void emit(PairState& s, AlertEvent event, std::vector<AlertEvent>& out);
  void remember(PairState& s, const AlertEvent& event);
  AlertEvent recall(const PairState& s) const;

  AlertConfig config_;
  PartyNames names_;
  Pairs pairs_;
  std::unordered_map<Slot, std::vector<Slot>> partners_;
  std::unordered_map<Slot, std::vector<std::uint32_t>> volumes_;  // a track's areas
  std::uint64_t seq_ = 0;
  std::uint16_t next_number_ = 1;
  std::size_t active_ = 0;
  Counters counters_;
};

/// The deterministic alert id: 16 hex digits of a 64-bit FNV-1a hash of both parties'
/// source and id and the opening data time.
std::string make_alert_id(const AlertParty& a, const AlertParty& b, double opened_t);
/// The hash behind make_alert_id, and its text.
std::uint64_t alert_id_hash(const AlertParty& a, const AlertParty& b, double opened_t);
/// An Apw alert's: the aircraft's source and id, the volume's name and the opening time.
std::uint64_t area_alert_id_hash(const AlertParty& a, const std::string& volume, double opened_t);
std::string format_alert_id(std::uint64_t hash);

}  // namespace kew::alert
