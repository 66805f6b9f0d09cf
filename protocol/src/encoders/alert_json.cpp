#include "kew/protocol/encoders/alert_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

#include "kew/protocol/version.hpp"
#include "kew/track/track_table.hpp"

namespace kew::protocol {
namespace {

// Decimals per kind of figure; docs/protocol.md states the same table.
constexpr int kTimeDecimals = 3;
constexpr int kDegreeDecimals = 6;
constexpr int kMetreSecondDecimals = 1;
constexpr int kSpeedAngleDecimals = 1;
constexpr int kFeetDecimals = 0;
constexpr int kRateDecimals = 1;

void append_fixed(std::string& out, double value, int decimals) {
  if (!std::isfinite(value)) {
    out.append("null");
    return;
  }
  // Far beyond any physical figure, fixed notation would print hundreds of digits, and
  // an integer beyond 64 bits that JSON readers such as simdjson refuse: the shortest
  // exact form ("5.5e+41") keeps the line short and readable.
  constexpr double kLargestFixed = 1e15;
  if (std::abs(value) >= kLargestFixed) {
    fmt::format_to(std::back_inserter(out), "{}", value);
    return;
  }
  const std::size_t start = out.size();
  fmt::format_to(std::back_inserter(out), "{:.{}f}", value, decimals);
  // "-0.0" would make equal figures print differently depending on the side they were
  // rounded from, which breaks byte-stable output.
  if (out[start] == '-' && out.find_first_not_of("0.", start + 1) == std::string::npos) {
    out.erase(start, 1);
  }
}

/// Writes the members of one JSON object in call order, handling the commas.
class ObjectWriter {
 public:
  explicit ObjectWriter(std::string& out) : out_(out) { out_.push_back('{'); }

  void key(std::string_view name) {
    if (!first_) out_.push_back(',');
    first_ = false;
    out_.push_back('"');
    out_.append(name);
    out_.append("\":");
  }
  void text(std::string_view name, std::string_view value) {
    key(name);
    append_json_string(out_, value);
  }
  void fixed(std::string_view name, double value, int decimals) {
    key(name);
    append_fixed(out_, value, decimals);
  }
  void integer(std::string_view name, std::uint64_t value) {
    key(name);
    fmt::format_to(std::back_inserter(out_), "{}", value);
  }
  void boolean(std::string_view name, bool value) {
    key(name);
    out_.append(value ? "true" : "false");
  }
  void null(std::string_view name) {
    key(name);
    out_.append("null");
  }
  void close() { out_.push_back('}'); }

 private:
  std::string& out_;
  bool first_ = true;
};

/// The members an ALERT's aircraft and a TRACK share, in the same order and precision.
template <typename Aircraft>
void write_identity_and_position(ObjectWriter& o, const Aircraft& aircraft) {
  o.text("id", aircraft.id);
  o.text("src", aircraft.source);
  o.text("cs", aircraft.callsign);
  o.fixed("lat", aircraft.lat_deg, kDegreeDecimals);
  o.fixed("lon", aircraft.lon_deg, kDegreeDecimals);
  o.fixed("alt_ft", aircraft.alt_ft, kFeetDecimals);
}

void append_party(std::string& out, const AlertParty& party) {
  ObjectWriter o(out);
  write_identity_and_position(o, party);
  o.fixed("gs_kt", party.gs_kt, kSpeedAngleDecimals);
  o.fixed("trk_deg", party.trk_deg, kSpeedAngleDecimals);
  o.fixed("vr_fpm", party.vr_fpm, kFeetDecimals);
  o.integer("tn", party.track_number);
  o.close();
}

/// The ALERT object without the line end, shared by ALERT lines and ALERTS elements.
void append_alert_object(std::string& out, const AlertEvent& e, std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "ALERT");
  o.text("kind", to_string(e.kind));
  o.text("id", e.id);
  o.integer("number", e.number);
  o.integer("seq", seq);
  o.text("state", to_string(e.state));
  if (e.state == AlertState::End) o.text("reason", to_string(e.end_reason));
  o.text("severity", to_string(e.severity));
  o.fixed("t", e.t, kTimeDecimals);
  o.fixed("t_open", e.opened_t, kTimeDecimals);
  o.key("a");
  append_party(out, e.a);
  if (e.kind == AlertKind::Apw) {
    // An area proximity warning: one aircraft and a volume, no pair figures.
    o.text("volume", e.volume);
    o.text("volume_kind", e.volume_kind);
    o.fixed("t_los_s", e.t_los_s, kMetreSecondDecimals);
    o.text("hypothesis", to_string(e.hypothesis));
    o.boolean("ack", e.acknowledged);
    o.close();
    return;
  }
  o.key("b");
  append_party(out, e.b);
  o.fixed("t_los_s", e.t_los_s, kMetreSecondDecimals);
  o.fixed("t_cpa_s", e.t_cpa_s, kMetreSecondDecimals);
  o.fixed("cpa_h_m", e.cpa_h_m, kMetreSecondDecimals);
  o.fixed("cpa_v_ft", e.cpa_v_ft, kFeetDecimals);
  o.fixed("sep_h_m", e.sep_h_m, kMetreSecondDecimals);
  o.fixed("sep_v_ft", e.sep_v_ft, kFeetDecimals);
  o.text("hypothesis", to_string(e.hypothesis));
  o.text("region", e.region);
  o.boolean("ack", e.acknowledged);
  o.close();
}

template <typename Element, typename Deref>
void append_snapshot(std::string& out, std::span<Element> active, std::uint64_t seq,
                     Deref deref, std::optional<double> t = std::nullopt) {
  ObjectWriter o(out);
  o.text("class", "ALERTS");
  o.integer("seq", seq);
  if (t) o.fixed("t", *t, kTimeDecimals);
  o.key("alerts");
  out.push_back('[');
  bool first = true;
  for (const auto& element : active) {
    if (!first) out.push_back(',');
    first = false;
    const AlertEvent& event = deref(element);
    append_alert_object(out, event, event.seq);
  }
  out.push_back(']');
  o.close();
  out.push_back('\n');
}

}  // namespace

void append_version_json(std::string& out, std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "VERSION");
  o.integer("seq", seq);
  o.text("release", release());
  o.text("revision", revision());
  o.integer("proto", static_cast<std::uint64_t>(kAlertStreamProtocol));
  o.close();
  out.push_back('\n');
}

void append_start_json(std::string& out, const StartInfo& start, std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "START");
  o.integer("seq", seq);
  o.text("run", start.run);
  o.text("release", release());
  o.text("revision", revision());
  o.fixed("t", start.t, kTimeDecimals);
  o.close();
  out.push_back('\n');
}

void append_alert_json(std::string& out, const AlertEvent& event, std::uint64_t seq) {
  append_alert_object(out, event, seq);
  out.push_back('\n');
}

void append_alerts_snapshot_json(std::string& out, std::span<const AlertEvent> active,
                                 std::uint64_t seq) {
  append_snapshot(out, active, seq, [](const AlertEvent& e) -> const AlertEvent& { return e; });
}

void append_alerts_snapshot_json(std::string& out, std::span<const AlertEvent* const> active,
                                 std::uint64_t seq) {
  append_snapshot(out, active, seq,
                  [](const AlertEvent* e) -> const AlertEvent& { return *e; });
}

namespace {

/// The members of ALIVE; the caller closes the object.
void write_alive_members(ObjectWriter& o, std::string& out, const AliveStatus& status, std::uint64_t seq) {
  o.text("class", "ALIVE");
  o.integer("seq", seq);
  if (status.last_data_t) {
    o.fixed("t", *status.last_data_t, kTimeDecimals);
  } else {
    o.null("t");
  }
  o.integer("tracks", status.tracks);
  o.integer("alerts", status.alerts);
  o.key("rates");
  {
    ObjectWriter rates(out);
    rates.fixed("records_per_s", status.records_per_s, kRateDecimals);
    rates.fixed("updates_per_s", status.updates_per_s, kRateDecimals);
    rates.close();
  }
  o.integer("uptime_s", status.uptime_s);
  o.boolean("degraded", status.degraded());
  o.text("health", kHealthReasonNames.name(status.health));
  o.text("release", release());
  o.text("revision", revision());
}

}  // namespace

void append_alerts_json(std::string& out, std::span<const AlertEvent> active, std::uint64_t seq, double t) {
  append_snapshot(out, active, seq, [](const AlertEvent& e) -> const AlertEvent& { return e; }, t);
}

void append_alive_json(std::string& out, const AliveStatus& status, std::uint64_t seq) {
  ObjectWriter o(out);
  write_alive_members(o, out, status, seq);
  o.close();
  out.push_back('\n');
}

void append_status_json(std::string& out, const AliveStatus& status, std::uint64_t seq, double data_t,
                        double wall_t) {
  ObjectWriter o(out);
  write_alive_members(o, out, status, seq);
  o.fixed("data_t", data_t, kTimeDecimals);
  o.fixed("wall_t", wall_t, kTimeDecimals);
  o.close();
  out.push_back('\n');
}

void append_ack_json(std::string& out, const Acknowledgement& ack, std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "ACK");
  o.integer("seq", seq);
  o.fixed("t", ack.t, 3);
  o.text("by", ack.by);
  o.text("client", ack.client);
  o.key("ids");
  out.push_back('[');
  for (std::size_t i = 0; i < ack.ids.size(); ++i) {
    if (i) out.push_back(',');
    append_json_string(out, ack.ids[i]);
  }
  out.push_back(']');
  o.close();
  out.push_back('\n');
}

void append_error_json(std::string& out, std::string_view message, std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "ERROR");
  o.integer("seq", seq);
  o.text("message", message);
  o.close();
  out.push_back('\n');
}

void append_track_json(std::string& out, const TrackReport& report, std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "TRACK");
  o.integer("seq", seq);
  o.fixed("t", report.t, kTimeDecimals);
  write_identity_and_position(o, report);
  if (report.gs_kt) o.fixed("gs_kt", *report.gs_kt, kSpeedAngleDecimals);
  if (report.trk_deg) o.fixed("trk_deg", *report.trk_deg, kSpeedAngleDecimals);
  if (report.vr_fpm) o.fixed("vr_fpm", *report.vr_fpm, kFeetDecimals);
  if (report.on_ground) o.boolean("gnd", true);
  o.close();
  out.push_back('\n');
}

void append_live_track_json(std::string& out, const track::Track& track, double now, std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "TRACK");
  o.integer("seq", seq);
  o.fixed("t", track.t, kTimeDecimals);
  write_identity_and_position(o, track);
  o.fixed("gs_kt", track.gs_kt, kSpeedAngleDecimals);
  o.fixed("trk_deg", track.trk_deg, kSpeedAngleDecimals);
  o.fixed("vr_fpm", track.vr_fpm, kFeetDecimals);
  o.integer("tn", track.number);
  if (track.mode3a) {
    o.key("sq");
    fmt::format_to(std::back_inserter(out), "\"{:04o}\"", *track.mode3a);
  }
  o.fixed("age_s", now - track.t, kMetreSecondDecimals);
  o.close();
}

void append_tracks_json(std::string& out, std::span<const track::Track* const> tracks, double now,
                        std::uint64_t seq) {
  ObjectWriter o(out);
  o.text("class", "TRACKS");
  o.integer("seq", seq);
  o.fixed("t", now, kTimeDecimals);
  o.key("tracks");
  out.push_back('[');
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (i) out.push_back(',');
    append_live_track_json(out, *tracks[i], now, seq);
  }
  out.push_back(']');
  o.close();
  out.push_back('\n');
}

void append_snapshot_json(std::string& out, std::span<const track::Track* const> tracks,
                          std::span<const AlertEvent> alerts, const AliveStatus& alive, double now,
                          std::uint64_t seq) {
  out.push_back('[');
  for (const track::Track* track : tracks) {
    append_live_track_json(out, *track, now, seq);
    out.push_back(',');
  }
  for (const AlertEvent& event : alerts) {
    append_alert_object(out, event, event.seq);
    out.push_back(',');
  }
  ObjectWriter o(out);
  write_alive_members(o, out, alive, seq);
  o.close();
  out.push_back(']');
}

}  // namespace kew::protocol
