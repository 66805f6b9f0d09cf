#pragma once
// What the alert manager emits and every sink encodes (design §4.7, §5.3–5.5).

#include <cstdint>
#include <string>
#include <string_view>

#include "kew/util/name_table.hpp"

namespace kew {

/// Ordered: a higher value is more urgent. Numeric values are the Modbus "highest
/// severity" register (design §5.5).
enum class Severity : std::uint8_t {
  None = 0,     ///< no conflict within the look-ahead
  Caution = 1,  ///< loss of separation predicted within T
  Warning = 2,  ///< loss of separation predicted within 60 s
  Loss = 3,     ///< separation is lost now
};

enum class AlertState : std::uint8_t { New, Update, End };

/// Which safety net raised an alert (design §4.7, §4.11).
enum class AlertKind : std::uint8_t {
  Stca,  ///< short-term conflict alert: aircraft a and aircraft b
  Apw,   ///< area proximity warning: aircraft a and a volume (b is empty)
};
/// The names of an ALERT's `kind`.
inline constexpr util::NameTable<AlertKind, 2> kAlertKindNames({{
    {AlertKind::Stca, "stca"},
    {AlertKind::Apw, "apw"},
}});
constexpr std::string_view to_string(AlertKind k) { return kAlertKindNames.name(k); }

/// Why an alert ended (End events only).
enum class AlertEndReason : std::uint8_t {
  None,         ///< not an End event
  Cleared,      ///< `clear` consecutive clear evaluations
  TrackDropped, ///< one of the two tracks was dropped (timeout, removal)
  /// Still open in the alert log when kewd stopped (crash, kill or stop): ended by the
  /// next run before any alert of its own (design §4.7), never emitted by the manager.
  Restart,
  /// Open on the previous active of a hot-standby pair when an instance that was not in
  /// step with it took over (design §5.9): the new active cannot continue it, so it ends
  /// it before any event of its own; never emitted by the manager.
  TakeoverUnsynced,
};

/// Which prediction found the pair's conflict (design §4.4): the alert says why it exists.
enum class Hypothesis : std::uint8_t {
  Linear,     ///< both aircraft in straight lines at constant rates
  LevelOff,   ///< a climb or descent stopping at its selected altitude (vertical intent)
  Turn,       ///< a turning aircraft continuing its turn (the turn hypothesis)
  Proximity,  ///< separation is lost now, whatever the prediction
};
/// The names of an ALERT's `hypothesis`.
inline constexpr util::NameTable<Hypothesis, 4> kHypothesisNames({{
    {Hypothesis::Linear, "linear"},
    {Hypothesis::LevelOff, "level_off"},
    {Hypothesis::Turn, "turn"},
    {Hypothesis::Proximity, "proximity"},
}});
constexpr std::string_view to_string(Hypothesis h) { return kHypothesisNames.name(h); }

/// The names of severities in the alert stream, ?WATCH and kew-watch.
inline constexpr util::NameTable<Severity, 4> kSeverityNames({{
    {Severity::None, "none"},
    {Severity::Caution, "caution"},
    {Severity::Warning, "warning"},
    {Severity::Loss, "loss"},
}});
constexpr std::string_view to_string(Severity s) { return kSeverityNames.name(s); }
/// The names of an ALERT's `state`.
inline constexpr util::NameTable<AlertState, 3> kAlertStateNames({{
    {AlertState::New, "new"},
    {AlertState::Update, "update"},
    {AlertState::End, "end"},
}});
constexpr std::string_view to_string(AlertState s) { return kAlertStateNames.name(s); }
/// The names of an End event's `reason` ("" for None: not an End event).
inline constexpr util::NameTable<AlertEndReason, 5> kAlertEndReasonNames({{
    {AlertEndReason::None, ""},
    {AlertEndReason::Cleared, "cleared"},
    {AlertEndReason::TrackDropped, "track_dropped"},
    {AlertEndReason::Restart, "restart"},
    {AlertEndReason::TakeoverUnsynced, "takeover_unsynced"},
}});
constexpr std::string_view to_string(AlertEndReason r) { return kAlertEndReasonNames.name(r); }

/// One aircraft of a pair as last reported (not predicted), in the canonical units.
struct AlertParty {
  std::string id;        ///< track id as in TrackReport::id
  std::string source;    ///< TrackReport::source
  std::string callsign;  ///< empty when unknown
  /// 16-bit system track number kew assigned to the track (CAT004 I004/170, Modbus).
  std::uint16_t track_number = 0;
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_ft = 0.0;
  double gs_kt = 0.0;
  double trk_deg = 0.0;  ///< [0, 360)
  double vr_fpm = 0.0;
};

struct AlertEvent {
  /// Deterministic id derived from the pair and the opening data time (hex text).
  std::string id;
  /// 16-bit alert number (CAT004 I004/040, Modbus table); stable for the alert's life.
  std::uint16_t number = 0;
  /// Per-stream sequence number, assigned by the alert manager in emission order (from 1,
  /// or on from AlertManager::resume()).
  std::uint64_t seq = 0;
  AlertKind kind = AlertKind::Stca;
  AlertState state = AlertState::New;
  AlertEndReason end_reason = AlertEndReason::None;
  Severity severity = Severity::None;
  /// Data time of the evaluation that produced the event, UTC seconds.
  double t = 0.0;
  /// Data time the alert opened, UTC seconds.
  double opened_t = 0.0;
  /// Stca: the pair ordered by (source, id), a < b. Apw: the aircraft in a, b empty.
  AlertParty a;
  AlertParty b;
  /// Time from t to the loss of separation, or (Apw) to the entry into the volume; 0
  /// when lost now (inside the volume).
  double t_los_s = 0.0;
  double t_cpa_s = 0.0;   ///< time to closest horizontal approach within [0, T]
  double cpa_h_m = 0.0;   ///< horizontal distance at CPA, geodesic-corrected, metres
  double cpa_v_ft = 0.0;  ///< vertical distance at CPA, feet (>= 0)
  double sep_h_m = 0.0;   ///< current horizontal separation, geodesic, metres
  double sep_v_ft = 0.0;  ///< current vertical separation, feet (>= 0)
  /// The prediction that found the conflict at this evaluation.
  Hypothesis hypothesis = Hypothesis::Linear;
  /// Name of the [[region]] whose parameters judged the pair; empty: the defaults and
  /// every Apw alert.
  std::string region;
  /// Apw: the volume's name and kind (volume::kVolumeKindNames); empty for Stca. The
  /// pair figures (t_cpa_s, cpa_*, sep_*) are 0 for Apw.
  std::string volume;
  std::string volume_kind;
  /// Acknowledged by an operator (Modbus coil 0) before this event was emitted.
  bool acknowledged = false;
};

}  // namespace kew
