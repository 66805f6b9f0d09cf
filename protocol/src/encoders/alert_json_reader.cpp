#include "kew/protocol/encoders/alert_json_reader.hpp"

#include <simdjson.h>

#include <limits>
#include <optional>
#include <string>

namespace kew::protocol {
namespace {

namespace dom = simdjson::dom;

// An ALERTS snapshot of a few thousand alerts is a few MB; anything larger is not ours.
constexpr std::size_t kMaxLineBytes = 16u << 20;

std::string_view trim(std::string_view text) {
  constexpr std::string_view kSpace = " \t\r\n";
  const auto first = text.find_first_not_of(kSpace);
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(kSpace);
  return text.substr(first, last - first + 1);
}

std::string quoted(std::string_view key) {
  std::string text = "\"";
  text.append(key);
  text.push_back('"');
  return text;
}

// Conversions of one JSON value into a kew type; false when the JSON type does not fit.
bool convert(dom::element value, double& out) {
  if (value.is_null()) {
    out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  return value.get_double().get(out) == simdjson::SUCCESS;
}
bool convert(dom::element value, std::uint64_t& out) {
  return value.get_uint64().get(out) == simdjson::SUCCESS;
}
bool convert(dom::element value, std::uint16_t& out) {
  std::uint64_t wide = 0;
  if (!convert(value, wide) || wide > std::numeric_limits<std::uint16_t>::max()) return false;
  out = static_cast<std::uint16_t>(wide);
  return true;
}
bool convert(dom::element value, int& out) {
  std::int64_t wide = 0;
  if (value.get_int64().get(wide) != simdjson::SUCCESS) return false;
  if (wide < std::numeric_limits<int>::min() || wide > std::numeric_limits<int>::max()) {
    return false;
  }
  out = static_cast<int>(wide);
  return true;
}
bool convert(dom::element value, bool& out) {
  return value.get_bool().get(out) == simdjson::SUCCESS;
}
bool convert(dom::element value, std::string& out) {
  std::string_view text;
  if (value.get_string().get(text) != simdjson::SUCCESS) return false;
  out.assign(text);
  return true;
}
bool convert(dom::element value, std::string_view& out) {
  return value.get_string().get(out) == simdjson::SUCCESS;
}
bool convert(dom::element value, dom::object& out) {
  return value.get_object().get(out) == simdjson::SUCCESS;
}
bool convert(dom::element value, dom::array& out) {
  return value.get_array().get(out) == simdjson::SUCCESS;
}

template <typename T>
constexpr std::string_view type_name() {
  if constexpr (std::is_same_v<T, double>) return "a number";
  else if constexpr (std::is_same_v<T, bool>) return "true or false";
  else if constexpr (std::is_same_v<T, dom::object>) return "an object";
  else if constexpr (std::is_same_v<T, dom::array>) return "an array";
  else if constexpr (std::is_same_v<T, std::uint16_t>) return "an integer in [0, 65535]";
  else if constexpr (std::is_same_v<T, std::string> || std::is_same_v<T, std::string_view>)
    return "a string";
  else return "an integer";
}

/// Typed access to the members of one object, with an error text naming the member
/// (and the enclosing member, for "a" and "b") on the first failure.
class Members {
 public:
  Members(dom::object object, std::string& error, std::string_view context = {})
      : object_(object), error_(error), context_(context) {}

  /// False (error set) when the member is missing or of the wrong type.
  template <typename T>
  bool required(std::string_view key, T& out) {
    dom::element value;
    if (object_.at_key(key).get(value) != simdjson::SUCCESS) {
      return fail("missing member " + where(key));
    }
    return take(key, value, out);
  }

  /// True when the member is absent (out untouched); false when it has the wrong type.
  template <typename T>
  bool optional(std::string_view key, T& out) {
    dom::element value;
    if (object_.at_key(key).get(value) != simdjson::SUCCESS) return true;
    return take(key, value, out);
  }

  /// Absent or null → nullopt.
  bool optional(std::string_view key, std::optional<double>& out) {
    dom::element value;
    if (object_.at_key(key).get(value) != simdjson::SUCCESS || value.is_null()) {
      out.reset();
      return true;
    }
    double number = 0.0;
    if (!take(key, value, number)) return false;
    out = number;
    return true;
  }

  bool fail(std::string message) {
    if (error_.empty()) error_ = std::move(message);
    return false;
  }

 private:
  template <typename T>
  bool take(std::string_view key, dom::element value, T& out) {
    if (convert(value, out)) return true;
    return fail("member " + where(key) + " must be " + std::string(type_name<T>()));
  }
  std::string where(std::string_view key) const {
    return context_.empty() ? quoted(key) : quoted(context_) + "." + quoted(key);
  }

  dom::object object_;
  std::string& error_;
  std::string_view context_;
};

// Reads `text` into `out` by the enum's name table; false when it names no value.
template <class Enum, std::size_t N>
bool parse_name(const util::NameTable<Enum, N>& names, std::string_view text, Enum& out) {
  const std::optional<Enum> value = names.parse(text);
  if (value) out = *value;
  return value.has_value();
}

bool read_party(dom::object object, std::string_view name, AlertParty& party,
                std::string& error) {
  Members m(object, error, name);
  return m.required("id", party.id) && m.optional("src", party.source) &&
         m.required("cs", party.callsign) && m.required("lat", party.lat_deg) &&
         m.required("lon", party.lon_deg) && m.required("alt_ft", party.alt_ft) &&
         m.required("gs_kt", party.gs_kt) && m.required("trk_deg", party.trk_deg) &&
         m.required("vr_fpm", party.vr_fpm) && m.optional("tn", party.track_number);
}

bool read_alert(dom::object object, AlertEvent& event, std::string& error) {
  event = AlertEvent{};
  Members m(object, error);
  std::string_view state, severity, reason;
  // Servers before "hypothesis" found every conflict by the linear prediction, and
  // servers before "kind" knew only pairs.
  std::string_view hypothesis = to_string(Hypothesis::Linear);
  std::string_view kind = to_string(AlertKind::Stca);
  dom::object a, b;
  if (!(m.optional("kind", kind) && m.required("id", event.id) && m.optional("number", event.number) &&
        m.required("seq", event.seq) && m.required("state", state) && m.optional("reason", reason) &&
        m.required("severity", severity) && m.required("t", event.t) && m.optional("t_open", event.opened_t) &&
        m.required("a", a) && m.required("t_los_s", event.t_los_s) && m.optional("hypothesis", hypothesis) &&
        m.optional("ack", event.acknowledged))) {
    return false;
  }
  const auto named = [&m](const auto& names, std::string_view member, std::string_view text,
                          auto& out) {
    return parse_name(names, text, out) ||
           m.fail("unknown " + std::string(member) + " " + quoted(text));
  };
  if (!(named(kAlertKindNames, "kind", kind, event.kind) && named(kAlertStateNames, "state", state, event.state) &&
        named(kSeverityNames, "severity", severity, event.severity) &&
        named(kAlertEndReasonNames, "reason", reason, event.end_reason) &&
        named(kHypothesisNames, "hypothesis", hypothesis, event.hypothesis) && read_party(a, "a", event.a, error))) {
    return false;
  }
  if (event.kind == AlertKind::Apw)
    return m.required("volume", event.volume) && m.required("volume_kind", event.volume_kind);
  return m.required("b", b) && m.required("t_cpa_s", event.t_cpa_s) && m.required("cpa_h_m", event.cpa_h_m) &&
         m.required("cpa_v_ft", event.cpa_v_ft) && m.required("sep_h_m", event.sep_h_m) &&
         m.required("sep_v_ft", event.sep_v_ft) && m.optional("region", event.region) &&
         read_party(b, "b", event.b, error);
}

bool read_alive(dom::object object, AliveStatus& alive, std::string& error) {
  alive = AliveStatus{};
  Members m(object, error);
  dom::object rates;
  bool degraded = false;
  std::string health;
  if (!(m.optional("t", alive.last_data_t) && m.required("tracks", alive.tracks) &&
        m.required("alerts", alive.alerts) && m.required("rates", rates) &&
        m.optional("uptime_s", alive.uptime_s) && m.optional("degraded", degraded) &&
        m.optional("health", health))) {
    return false;
  }
  // Servers before "health" sent only "degraded", which meant a stale feed.
  alive.health = degraded ? HealthReason::FeedStale : HealthReason::Healthy;
  if (!health.empty() && !parse_name(kHealthReasonNames, health, alive.health)) {
    return m.fail("unknown health " + quoted(std::string_view(health)));
  }
  Members r(rates, error, "rates");
  return r.required("records_per_s", alive.records_per_s) &&
         r.required("updates_per_s", alive.updates_per_s);
}

bool read_track(dom::object object, TrackReport& track, std::string& error) {
  track = TrackReport{};
  Members m(object, error);
  return m.required("t", track.t) && m.required("id", track.id) &&
         m.optional("src", track.source) && m.optional("cs", track.callsign) &&
         m.required("lat", track.lat_deg) && m.required("lon", track.lon_deg) &&
         m.required("alt_ft", track.alt_ft) && m.optional("gs_kt", track.gs_kt) &&
         m.optional("trk_deg", track.trk_deg) && m.optional("vr_fpm", track.vr_fpm) &&
         m.optional("gnd", track.on_ground);
}

/// A reusable simdjson DOM parser with its padded input buffer.
class JsonObjectParser {
 public:
  explicit JsonObjectParser(std::size_t max_bytes) : max_bytes_(max_bytes), json_(max_bytes) {}

  /// Parses `text` into an object; false with `error` set otherwise.
  bool parse_object(std::string_view text, dom::object& object, std::string& error) {
    if (text.size() > max_bytes_) {
      error = "longer than " + std::to_string(max_bytes_) + " bytes";
      return false;
    }
    padded_.assign(text.begin(), text.end());
    padded_.resize(text.size() + simdjson::SIMDJSON_PADDING, '\0');
    dom::element root;
    if (const auto code = json_.parse(padded_.data(), text.size(), false).get(root);
        code != simdjson::SUCCESS) {
      error = std::string("invalid JSON: ") + simdjson::error_message(code);
      return false;
    }
    if (root.get_object().get(object) != simdjson::SUCCESS) {
      error = "not a JSON object";
      return false;
    }
    return true;
  }

 private:
  std::size_t max_bytes_;
  dom::parser json_;
  std::vector<char> padded_;  // the text followed by simdjson's zero padding
};

}  // namespace

struct AlertStreamReader::Parser : JsonObjectParser {
  Parser() : JsonObjectParser(kMaxLineBytes) {}
};

AlertStreamReader::AlertStreamReader() : parser_(std::make_unique<Parser>()) {}
AlertStreamReader::~AlertStreamReader() = default;

bool AlertStreamReader::read(std::string_view line) {
  error_.clear();
  dom::object object;
  if (!parser_->parse_object(trim(line), object, error_)) return false;
  Members m(object, error_);
  std::string_view cls;
  std::uint64_t seq = 0;
  if (!m.required("class", cls) || !m.required("seq", seq)) return false;

  bool ok = false;
  StreamObjectClass parsed_class = StreamObjectClass::Version;
  if (cls == "ALERT") {
    parsed_class = StreamObjectClass::Alert;
    ok = read_alert(object, alert_, error_);
  } else if (cls == "ALERTS") {
    parsed_class = StreamObjectClass::Alerts;
    dom::array elements;
    ok = m.required("alerts", elements);
    alerts_.clear();
    if (!ok) return false;
    for (dom::element element : elements) {
      if (!ok) break;
      dom::object alert_object;
      if (!convert(element, alert_object)) {
        ok = m.fail("member \"alerts\" must hold objects");
        break;
      }
      ok = read_alert(alert_object, alerts_.emplace_back(), error_);
    }
  } else if (cls == "ALIVE") {
    parsed_class = StreamObjectClass::Alive;
    ok = read_alive(object, alive_, error_);
  } else if (cls == "TRACK") {
    parsed_class = StreamObjectClass::Track;
    ok = read_track(object, track_, error_);
  } else if (cls == "ACK") {
    parsed_class = StreamObjectClass::Ack;
    dom::array ids;
    acknowledging_client_.clear();  // absent from servers before the client was named
    ok = m.required("by", text_) && m.optional("client", acknowledging_client_) && m.required("ids", ids);
    acknowledged_.clear();
    if (!ok) return false;
    for (dom::element element : ids) {
      if (!ok) break;
      std::string_view id;
      if (element.get_string().get(id) != simdjson::SUCCESS) {
        ok = m.fail("member \"ids\" must hold strings");
        break;
      }
      acknowledged_.emplace_back(id);
    }
  } else if (cls == "ERROR") {
    parsed_class = StreamObjectClass::Error;
    ok = m.required("message", text_);
  } else if (cls == "START") {
    parsed_class = StreamObjectClass::Start;
    revision_.clear();
    ok = m.required("run", run_) && m.required("release", text_) && m.optional("revision", revision_) &&
         m.required("t", start_t_);
  } else if (cls == "VERSION") {
    parsed_class = StreamObjectClass::Version;
    revision_.clear();
    ok = m.required("release", text_) && m.optional("revision", revision_) && m.required("proto", proto_);
  } else {
    return m.fail("unknown class " + quoted(cls));
  }
  if (!ok) return false;
  class_ = parsed_class;
  seq_ = seq;
  return true;
}

WatchParseResult parse_watch_request(std::string_view line) {
  WatchParseResult result;
  if (line.size() > kMaxWatchRequestBytes) {
    result.error = "request longer than " + std::to_string(kMaxWatchRequestBytes) + " bytes";
    return result;
  }
  std::string_view text = trim(line);
  if (!text.empty() && text.back() == ';') text = trim(text.substr(0, text.size() - 1));
  constexpr std::string_view kCommand = "?WATCH";
  if (text.substr(0, kCommand.size()) != kCommand) {
    result.error = "unknown command (expected ?WATCH)";
    return result;
  }
  text.remove_prefix(kCommand.size());
  if (text.empty()) {
    result.ok = true;
    return result;
  }
  if (text.front() != '=') {
    result.error = "expected '=' after ?WATCH";
    return result;
  }
  text.remove_prefix(1);

  JsonObjectParser parser(kMaxWatchRequestBytes);
  dom::object object;
  if (!parser.parse_object(text, object, result.error)) return result;
  Members m(object, result.error);
  std::string_view severity_text;
  if (!m.optional("enable", result.request.enable) ||
      !m.optional("tracks", result.request.tracks) ||
      !m.optional("min_severity", severity_text)) {
    return result;
  }
  if (object.at_key("min_severity").error() == simdjson::SUCCESS &&
      !parse_name(kSeverityNames, severity_text, result.request.min_severity)) {
    result.error = "unknown severity " + quoted(severity_text) + " (expected one of " +
                   kSeverityNames.list() + ")";
    return result;
  }
  result.ok = true;
  return result;
}

AckParseResult parse_ack_request(std::string_view body) {
  AckParseResult result;
  if (body.size() > kMaxAckRequestBytes) {
    result.error = "body longer than " + std::to_string(kMaxAckRequestBytes) + " bytes";
    return result;
  }
  JsonObjectParser parser(kMaxAckRequestBytes);
  dom::object object;
  if (!parser.parse_object(body, object, result.error)) return result;
  Members m(object, result.error);
  std::string_view id;
  if (!m.optional("all", result.request.all) || !m.optional("id", id)) return result;
  const bool has_id = object.at_key("id").error() == simdjson::SUCCESS;
  const bool has_all = object.at_key("all").error() == simdjson::SUCCESS;
  if (has_id == has_all || (has_all && !result.request.all) || (has_id && id.empty())) {
    result.error = R"(expected {"id":"<alert id>"} or {"all":true})";
    return result;
  }
  result.request.id = std::string(id);
  result.ok = true;
  return result;
}

}  // namespace kew::protocol
