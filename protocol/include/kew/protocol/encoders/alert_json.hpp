#pragma once
// JSON objects of the subscriber alert stream (design §5.3): gpsd-style, one object per
// line. Every function appends exactly one line, terminated by '\n', to `out` and
// allocates nothing beyond growing `out`.
//
// Numbers are printed in fixed notation with a fixed number of decimals per field, so
// that the same event always gives the same bytes (design §2.5) and lines stay short:
//   times (t, t_open)            3 decimals (1 ms)
//   lat, lon                     6 decimals (about 0.11 m)
//   metres, seconds, gs_kt, trk  1 decimal
//   feet, ft/min                 0 decimals
//   rates (per second)           1 decimal
// A value that rounds to zero is printed without a minus sign; a value that is not
// finite (NaN, ±inf) is printed as `null`; a magnitude of 10^15 or more (never a physical
// figure) is printed in its shortest exact form with an exponent. Strings go through the project's one JSON
// string escaper, append_json_string() of kew/protocol/ndjson_writer.hpp (any bytes give
// valid JSON; invalid UTF-8 becomes \ufffd). docs/protocol.md lists every field.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "kew/alert/alert_event.hpp"
#include "kew/protocol/ndjson_writer.hpp"  // append_json_string(), for callers of this header too
#include "kew/track/track_report.hpp"

namespace kew::track {
struct Track;
}

namespace kew::protocol {

/// Why kewd's picture cannot be trusted now (design §6.6); Healthy when it can.
enum class HealthReason : std::uint8_t {
  Healthy,         ///< records are arriving and being accepted
  NoData,          ///< no record accepted since the start
  FeedStale,       ///< no record accepted for a track timeout
  RecordsRefused,  ///< most records of the last seconds were refused
  /// The alert log cannot be written (disk full, I/O error): events wait in memory.
  AlertLogFailing,
  /// Hot standby: this kewd computes alerts and sends none; another one is active.
  Standby,
  /// Hot standby, catching up with the active (or out of step with it): it may not take
  /// over while another instance in step can (design §5.9).
  StandbySyncing,
  /// A feed's server cannot be reached (a durable NATS feed): its tracks stand still.
  FeedUnreachable,
  /// An input lost data before kewd read it (UDP datagrams the kernel dropped, NATS
  /// messages the client dropped) in the last seconds.
  InputDropping,
  /// A notifier ([[notify]]) has failed to deliver for longer than its failing_after_s:
  /// alerts wait in its outbox (design §5.10).
  NotifyFailing,
};
inline constexpr util::NameTable<HealthReason, 10> kHealthReasonNames({{
    {HealthReason::Healthy, "healthy"},
    {HealthReason::NoData, "no_data"},
    {HealthReason::FeedStale, "feed_stale"},
    {HealthReason::RecordsRefused, "records_refused"},
    {HealthReason::InputDropping, "input_dropping"},
    {HealthReason::AlertLogFailing, "alert_log_failing"},
    {HealthReason::Standby, "standby"},
    {HealthReason::StandbySyncing, "standby_syncing"},
    {HealthReason::FeedUnreachable, "feed_unreachable"},
    {HealthReason::NotifyFailing, "notify_failing"},
}});

/// Figures of the once-a-second ALIVE object.
struct AliveStatus {
  /// Data time of the latest record processed, UTC seconds; absent before the first one.
  std::optional<double> last_data_t;
  /// Live tracks now.
  std::uint64_t tracks = 0;
  /// Active alerts now.
  std::uint64_t alerts = 0;
  /// Input records accepted per second, averaged by the caller (>= 0).
  double records_per_s = 0.0;
  /// Track updates applied to the engine per second (>= 0).
  double updates_per_s = 0.0;
  /// Seconds since the service started.
  std::uint64_t uptime_s = 0;
  /// Why the picture cannot be trusted; degraded (Modbus discrete input 5) unless Healthy.
  HealthReason health = HealthReason::Healthy;
  bool degraded() const { return health != HealthReason::Healthy; }
};

/// {"class":"VERSION","seq":…,"release":"MAJOR.MINOR.PATCH","revision":"…","proto":1}
/// (revision: protocol::revision()).
void append_version_json(std::string& out, std::uint64_t seq);

/// The start of one run of kewd (design §4.7): first in the alert log of each run and
/// sent to each subscriber right after VERSION, so that a reader sees every restart.
struct StartInfo {
  /// 32 lower-case hex digits, random for each run.
  std::string_view run;
  /// Wall clock time of the start, UTC seconds.
  double t = 0.0;
};

/// {"class":"START","seq":…,"run":"…","release":"MAJOR.MINOR.PATCH","revision":"…","t":…}; `seq` is the
/// last sequence number before this run (0 for the first run).
void append_start_json(std::string& out, const StartInfo& start, std::uint64_t seq);

/// One ALERT object. `seq` is the stream's sequence number for this line (callers that
/// forward the alert manager's numbering pass `event.seq`).
void append_alert_json(std::string& out, const AlertEvent& event, std::uint64_t seq);

/// {"class":"ALERTS","seq":…,"alerts":[…]}: every element is the complete ALERT object
/// of an active alert's latest event, including its "class" and with the event's own
/// `AlertEvent::seq`, so a client reads elements with the same code as ALERT lines.
void append_alerts_snapshot_json(std::string& out, std::span<const AlertEvent> active,
                                 std::uint64_t seq);
/// Same, for callers that keep their events elsewhere (no copies needed).
void append_alerts_snapshot_json(std::string& out, std::span<const AlertEvent* const> active,
                                 std::uint64_t seq);

/// {"class":"ALERTS","seq":…,"t":…,"alerts":[…]}: the snapshot above with the data time
/// `t` it was taken at (HTTP /api/alerts, design §5.8); elements in the caller's order.
void append_alerts_json(std::string& out, std::span<const AlertEvent> active, std::uint64_t seq, double t);

/// {"class":"ALIVE","seq":…,"t":…|null,"tracks":…,"alerts":…,
///  "rates":{"records_per_s":…,"updates_per_s":…},"uptime_s":…,"degraded":…,"health":…,
///  "release":…,"revision":…}
void append_alive_json(std::string& out, const AliveStatus& status, std::uint64_t seq);

/// The ALIVE object with the pipeline clock and the wall clock (UTC s) added:
/// {"class":"ALIVE",…,"health":…,"data_t":…,"wall_t":…} (HTTP /api/status, design §5.8).
void append_status_json(std::string& out, const AliveStatus& status, std::uint64_t seq, double data_t,
                        double wall_t);

/// An operator acknowledged these active alerts (their later events carry "ack":true).
struct Acknowledgement {
  std::span<const std::string> ids;
  double t = 0.0;               ///< data time
  std::string_view by;          ///< the interface it came through: "modbus"
  /// Who: the client's "HOST:PORT" (IPv6 in brackets) as its socket's peer; "web" is
  /// reserved for the HTTP interface.
  std::string_view client;
};

/// {"class":"ACK","seq":…,"t":…,"by":"modbus","client":"127.0.0.1:50312","ids":["…",…]}
void append_ack_json(std::string& out, const Acknowledgement& ack, std::uint64_t seq);

/// {"class":"ERROR","seq":…,"message":"…"}; `message` may hold any bytes.
void append_error_json(std::string& out, std::string_view message, std::uint64_t seq);

/// {"class":"TRACK","seq":…,"t":…,"id":…,"src":…,"cs":…,"lat":…,"lon":…,"alt_ft":…,
///  "gs_kt":…,"trk_deg":…,"vr_fpm":…}; gs_kt, trk_deg and vr_fpm are left out when the
/// report does not have them, and "gnd":true is added for targets on the ground.
void append_track_json(std::string& out, const TrackReport& report, std::uint64_t seq);

/// A live track of the track table as a TRACK object (HTTP /api/tracks and /ws, design
/// §5.8), without the line end: the members of a report's TRACK (t is the track's last
/// record), then "tn" (track number), "sq" (Mode 3/A, 4 octal digits, when known) and
/// "age_s" (`now` − t).
void append_live_track_json(std::string& out, const track::Track& track, double now, std::uint64_t seq);

/// {"class":"TRACKS","seq":…,"t":…,"tracks":[TRACK,…]}: the live TRACK object of each of
/// `tracks`, in the caller's order, at data time `now` (UTC s) (HTTP /api/tracks, the
/// NATS tracks subject, design §5.8).
void append_tracks_json(std::string& out, std::span<const track::Track* const> tracks, double now,
                        std::uint64_t seq);

/// What a page shows at once, as one JSON array without the line end (HTTP
/// /api/snapshot, design §5.8): the live TRACK object of each of `tracks`, the ALERT
/// object of each of `alerts` (with its own seq), then the ALIVE object.
void append_snapshot_json(std::string& out, std::span<const track::Track* const> tracks,
                          std::span<const AlertEvent> alerts, const AliveStatus& alive, double now,
                          std::uint64_t seq);

}  // namespace kew::protocol
