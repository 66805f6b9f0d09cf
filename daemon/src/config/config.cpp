#include "kew/daemon/config.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

namespace kew::daemon {

namespace {

constexpr double kNauticalMile = 1852.0;
constexpr double kFoot = 0.3048;

// Reads the keys of one TOML table, checking types and ranges, and at the end refuses
// every key that was not asked for.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string_view origin, std::string name)
      : table_(table), origin_(origin), name_(std::move(name)) {}

  [[noreturn]] void fail(const toml::node* node, std::string_view message) const {
    std::string where(origin_);
    if (node && node->source().begin.line > 0) where += fmt::format(":{}", node->source().begin.line);
    throw ConfigError(fmt::format("{}: [{}] {}", where, name_, message));
  }

  const toml::node* take(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  void number(std::string_view key, double& out, double lo, double hi) {
    const toml::node* node = take(key);
    if (!node) return;
    double v;
    if (const auto* i = node->as_integer()) v = static_cast<double>(i->get());
    else if (const auto* f = node->as_floating_point()) v = f->get();
    else fail(node, fmt::format("{} must be a number", key));
    if (!(v >= lo && v <= hi)) fail(node, fmt::format("{} = {} is outside [{}, {}]", key, v, lo, hi));
    out = v;
  }

  template <class Int>
  void integer(std::string_view key, Int& out, std::int64_t lo, std::int64_t hi) {
    const toml::node* node = take(key);
    if (!node) return;
    const auto* i = node->as_integer();
    if (!i) fail(node, fmt::format("{} must be an integer", key));
    if (i->get() < lo || i->get() > hi) fail(node, fmt::format("{} = {} is outside [{}, {}]", key, i->get(), lo, hi));
    out = static_cast<Int>(i->get());
  }

  void boolean(std::string_view key, bool& out) {
    const toml::node* node = take(key);
    if (!node) return;
    const auto* b = node->as_boolean();
    if (!b) fail(node, fmt::format("{} must be true or false", key));
    out = b->get();
  }

  void string(std::string_view key, std::string& out) {
    const toml::node* node = take(key);
    if (!node) return;
    const auto* s = node->as_string();
    if (!s) fail(node, fmt::format("{} must be a string", key));
    out = s->get();
  }

  /// A string key that must be one of a set of names, parsed by `parse`.
  template <class T, class Parse>
  void choice(std::string_view key, T& out, Parse parse, std::string_view allowed) {
    std::string text;
    const toml::node* node = table_.get(key);
    string(key, text);
    if (!node) return;
    if (!parse(text, out)) fail(node, fmt::format("{} = \"{}\": expected one of {}", key, text, allowed));
  }

  void address(std::string_view key, std::string& out) {
    const toml::node* node = table_.get(key);
    string(key, out);
    std::string host;
    std::uint16_t port = 0;
    if (node && !split_host_port(out, host, port)) fail(node, fmt::format("{} = \"{}\" is not HOST:PORT", key, out));
  }

  void finish() const {
    for (const auto& [key, node] : table_)
      if (!used_.count(std::string(key.str())))
        fail(&node, fmt::format("unknown key \"{}\"", key.str()));
  }

 private:
  const toml::table& table_;
  std::string_view origin_;
  std::string name_;
  std::set<std::string> used_;
};

bool parse_transport(std::string_view text, Transport& out) {
  for (Transport t : {Transport::Udp, Transport::TcpClient, Transport::TcpServer, Transport::File}) {
    if (text == to_string(t)) {
      out = t;
      return true;
    }
  }
  return false;
}

bool parse_tolerance_mode(std::string_view text, kinetic::ToleranceMode& out) {
  if (text == "absolute") out = kinetic::ToleranceMode::Absolute;
  else if (text == "relative") out = kinetic::ToleranceMode::Relative;
  else return false;
  return true;
}

bool parse_log_level(std::string_view text, std::string& out) {
  for (std::string_view level : {"trace", "debug", "info", "warn", "error", "critical", "off"}) {
    if (text == level) {
      out = std::string(text);
      return true;
    }
  }
  return false;
}

const toml::table* subtable(const toml::table& root, std::string_view key, std::string_view origin) {
  const toml::node* node = root.get(key);
  if (!node) return nullptr;
  if (!node->is_table())
    throw ConfigError(fmt::format("{}:{}: {} must be a table", origin, node->source().begin.line, key));
  return node->as_table();
}

template <class F>
void each_table_of_array(const toml::table& root, std::string_view key, std::string_view origin, F&& f) {
  const toml::node* node = root.get(key);
  if (!node) return;
  const toml::array* array = node->as_array();
  if (!array || !array->is_array_of_tables())
    throw ConfigError(fmt::format("{}:{}: {} must be written as [[{}]] tables", origin, node->source().begin.line,
                                  key, key));
  std::size_t index = 0;
  for (const toml::node& element : *array) f(*element.as_table(), index++);
}

void read_service(TableReader& r, ServiceConfig& s) {
  r.address("alert_listen", s.alert_listen);
  r.integer("max_subscribers", s.max_subscribers, 1, 10000);
  r.integer("subscriber_queue", s.subscriber_queue, 16, 10'000'000);
  r.number("alive_interval_s", s.alive_interval_s, 0.1, 3600.0);
  r.number("tick_interval_s", s.tick_interval_s, 0.05, 60.0);
  r.choice("log_level", s.log_level, parse_log_level, "trace, debug, info, warn, error, critical, off");
  r.string("alert_log", s.alert_log);
  r.integer("alert_log_max_bytes", s.alert_log_max_bytes, 4096, std::int64_t{1} << 40);
  r.integer("alert_log_keep", s.alert_log_keep, 0, 1000);
  r.string("record_file", s.record_file);
  r.boolean("tracks_stream", s.tracks_stream);
}

void read_projection(TableReader& r, PipelineConfig& p) {
  double lat = NAN, lon = NAN;
  r.number("reference_lat", lat, -90.0, 90.0);
  r.number("reference_lon", lon, -180.0, 180.0);
  if (std::isnan(lat) != std::isnan(lon)) r.fail(nullptr, "reference_lat and reference_lon go together");
  if (!std::isnan(lat)) p.reference = geo::GeodeticPosition{lat, lon};
  double radius_km = p.coverage_radius_m / 1000.0;
  r.number("coverage_radius_km", radius_km, 1.0, 3000.0);
  p.coverage_radius_m = radius_km * 1000.0;
}

void read_tracks(TableReader& r, track::TrackTableConfig& t) {
  r.number("timeout_s", t.track_timeout_s, 1.0, 3600.0);
  r.number("max_ground_speed_kt", t.max_ground_speed_kt, 1.0, 5000.0);
  r.number("max_vertical_rate_fpm", t.max_vertical_rate_fpm, 1.0, 100000.0);
  r.number("min_altitude_ft", t.min_altitude_ft, -5000.0, 200000.0);
  r.number("max_altitude_ft", t.max_altitude_ft, -5000.0, 200000.0);
  if (t.min_altitude_ft >= t.max_altitude_ft) r.fail(nullptr, "min_altitude_ft must be below max_altitude_ft");
  r.boolean("exclude_on_ground", t.exclude_on_ground);
  r.integer("max_tracks", t.max_tracks, 1, 10'000'000);
  r.number("max_lateness_s", t.max_lateness_s, 0.0, 3600.0);
  r.number("max_derivation_gap_s", t.max_derivation_gap_s, 0.1, 3600.0);
}

void read_kinetic(TableReader& r, kinetic::KineticConfig& k) {
  r.number("tolerance", k.tolerance, 0.0, 1e6);
  r.choice("tolerance_mode", k.tolerance_mode, parse_tolerance_mode, "absolute, relative");
  double horizon = std::isinf(k.horizon_s) ? 0.0 : k.horizon_s;
  r.number("horizon_s", horizon, 0.0, 1e9);
  k.horizon_s = horizon == 0.0 ? kinetic::kNever : horizon;
  r.boolean("reduce_redundant_events", k.reduce_redundant_events);
}

void read_probe(TableReader& r, PipelineConfig& p) {
  r.choice("mode", p.probe_mode, [](std::string_view text, probe::ProbeMode& out) {
    return probe::parse_probe_mode(std::string(text).c_str(), out);
  }, "exact, edges, brute");
  double horizontal_nm = p.minima.horizontal_m / kNauticalMile;
  double vertical_ft = p.minima.vertical_m / kFoot;
  r.number("horizontal_nm", horizontal_nm, 0.1, 100.0);
  r.number("vertical_ft", vertical_ft, 1.0, 100000.0);
  r.number("lookahead_s", p.minima.lookahead_s, 0.0, 3600.0);
  p.minima.horizontal_m = horizontal_nm * kNauticalMile;
  p.minima.vertical_m = vertical_ft * kFoot;
}

void read_alerts(TableReader& r, alert::AlertConfig& a) {
  r.integer("confirm", a.confirm, 1, 1000);
  r.integer("clear", a.clear, 1, 1000);
  r.number("warning_s", a.warning_s, 0.0, 3600.0);
  r.number("update_t_los_s", a.update_t_los_s, 0.0, 3600.0);
  r.number("update_cpa_h_m", a.update_cpa_h_m, 0.0, 1e6);
  r.number("update_cpa_v_ft", a.update_cpa_v_ft, 0.0, 1e5);
}

void read_cat004(TableReader& r, Cat004Config& c) {
  r.boolean("enabled", c.enabled);
  r.address("destination", c.destination);
  r.string("interface", c.interface);
  r.integer("ttl", c.ttl, 0, 255);
  r.integer("sac", c.sac, 0, 255);
  r.integer("sic", c.sic, 0, 255);
  r.number("alive_interval_s", c.alive_interval_s, 0.1, 3600.0);
}

void read_modbus(TableReader& r, ModbusConfig& m) {
  r.boolean("enabled", m.enabled);
  r.address("listen", m.listen);
  r.integer("unit_id", m.unit_id, 0, 247);
  r.integer("table_entries", m.table_entries, 0, 64);
  r.boolean("read_only", m.read_only);
  r.integer("max_connections", m.max_connections, 1, 256);
}

void read_decoding(TableReader& r, protocol::DecoderOptions& d) {
  r.number("sbs_utc_offset_s", d.sbs_utc_offset_s, -86400.0, 86400.0);
  r.integer("max_line_bytes", d.max_line_bytes, 256, 1 << 20);
}

void read_radar(TableReader& r, protocol::RadarSite& site) {
  site.lat_deg = NAN;
  site.lon_deg = NAN;
  r.integer("sac", site.sac, 0, 255);
  r.integer("sic", site.sic, 0, 255);
  r.number("lat", site.lat_deg, -90.0, 90.0);
  r.number("lon", site.lon_deg, -180.0, 180.0);
  r.number("height_m", site.height_m, -500.0, 10000.0);
  if (std::isnan(site.lat_deg) || std::isnan(site.lon_deg)) r.fail(nullptr, "a radar needs lat and lon");
}

void read_input(TableReader& r, InputConfig& in) {
  r.string("name", in.name);
  r.choice("format", in.format, protocol::parse_format,
           "auto, ndjson, sbs, opensky-csv, opensky-json, readsb, asterix-raw, asterix-ff, asterix-pcap, "
           "asterix-datagram");
  r.choice("transport", in.transport, parse_transport, "udp, tcp-client, tcp-server, file");
  r.string("address", in.address);
  r.string("interface", in.interface);
  r.number("reconnect_min_s", in.reconnect_min_s, 0.01, 3600.0);
  r.number("reconnect_max_s", in.reconnect_max_s, 0.01, 86400.0);
  r.integer("max_connections", in.max_connections, 1, 1024);
  r.boolean("pace", in.pace);
  r.number("speed", in.speed, 0.001, 1000.0);
  r.string("asterix_day", in.asterix_day);
  if (in.address.empty()) r.fail(nullptr, "an input needs an address (HOST:PORT or a file path)");
  std::string host;
  std::uint16_t port = 0;
  if (in.transport != Transport::File && !split_host_port(in.address, host, port))
    r.fail(nullptr, fmt::format("address \"{}\" is not HOST:PORT", in.address));
  double day = 0;
  if (!in.asterix_day.empty() && !parse_utc_day(in.asterix_day, day))
    r.fail(nullptr, fmt::format("asterix_day \"{}\" is not YYYY-MM-DD", in.asterix_day));
  if (in.format == protocol::Format::AsterixDatagram && in.transport != Transport::Udp)
    r.fail(nullptr, "format asterix-datagram needs transport udp");
}

}  // namespace

std::string_view to_string(Transport t) {
  switch (t) {
    case Transport::TcpClient: return "tcp-client";
    case Transport::TcpServer: return "tcp-server";
    case Transport::File: return "file";
    case Transport::Udp: break;
  }
  return "udp";
}

bool split_host_port(std::string_view address, std::string& host, std::uint16_t& port) {
  std::string_view h, p;
  if (!address.empty() && address.front() == '[') {
    const auto close = address.find(']');
    if (close == std::string_view::npos || close + 1 >= address.size() || address[close + 1] != ':') return false;
    h = address.substr(1, close - 1);
    p = address.substr(close + 2);
  } else {
    const auto colon = address.rfind(':');
    if (colon == std::string_view::npos) return false;
    h = address.substr(0, colon);
    p = address.substr(colon + 1);
    if (h.find(':') != std::string_view::npos) return false;  // bare IPv6 needs brackets
  }
  if (h.empty() || p.empty() || p.size() > 5) return false;
  unsigned value = 0;
  for (char c : p) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + static_cast<unsigned>(c - '0');
  }
  if (value > 65535) return false;
  host = std::string(h);
  port = static_cast<std::uint16_t>(value);
  return true;
}

bool parse_utc_day(std::string_view text, double& out) {
  int y = 0, m = 0, d = 0;
  if (text.size() != 10 || text[4] != '-' || text[7] != '-') return false;
  for (std::size_t i : {0u, 1u, 2u, 3u, 5u, 6u, 8u, 9u})
    if (text[i] < '0' || text[i] > '9') return false;
  const auto digits = [&](std::size_t at, std::size_t n) {
    int v = 0;
    for (std::size_t i = at; i < at + n; ++i) v = v * 10 + (text[i] - '0');
    return v;
  };
  y = digits(0, 4);
  m = digits(5, 2);
  d = digits(8, 2);
  if (m < 1 || m > 12 || d < 1 || d > 31) return false;
  // Days from civil (proleptic Gregorian) to the Unix epoch.
  const int yy = y - (m <= 2);
  const int era = (yy >= 0 ? yy : yy - 399) / 400;
  const int yoe = yy - era * 400;
  const int doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  const long days = static_cast<long>(era) * 146097 + doe - 719468;
  out = static_cast<double>(days) * 86400.0;
  return true;
}

Config parse_config(std::string_view toml_text, std::string_view origin) {
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}:{}:{}: {}", origin, e.source().begin.line, e.source().begin.column,
                                  e.description()));
  }
  Config config;
  static const std::set<std::string> sections = {"service", "projection", "tracks", "kinetic", "probe", "alerts",
                                                 "cat004", "modbus", "decoding", "radar", "input"};
  for (const auto& [key, node] : root)
    if (!sections.count(std::string(key.str())))
      throw ConfigError(fmt::format("{}:{}: unknown section or key \"{}\"", origin, node.source().begin.line,
                                    key.str()));

  const auto section = [&](std::string_view name, auto&& read) {
    if (const toml::table* t = subtable(root, name, origin)) {
      TableReader reader(*t, origin, std::string(name));
      read(reader);
      reader.finish();
    }
  };
  section("service", [&](TableReader& r) { read_service(r, config.service); });
  section("projection", [&](TableReader& r) { read_projection(r, config.pipeline); });
  section("tracks", [&](TableReader& r) { read_tracks(r, config.pipeline.tracks); });
  section("kinetic", [&](TableReader& r) { read_kinetic(r, config.pipeline.kinetic); });
  section("probe", [&](TableReader& r) { read_probe(r, config.pipeline); });
  section("alerts", [&](TableReader& r) { read_alerts(r, config.pipeline.alerts); });
  section("cat004", [&](TableReader& r) { read_cat004(r, config.cat004); });
  section("modbus", [&](TableReader& r) { read_modbus(r, config.modbus); });
  section("decoding", [&](TableReader& r) { read_decoding(r, config.decoding); });
  each_table_of_array(root, "radar", origin, [&](const toml::table& t, std::size_t i) {
    TableReader reader(t, origin, fmt::format("radar {}", i + 1));
    protocol::RadarSite site{};
    read_radar(reader, site);
    reader.finish();
    config.decoding.asterix.radars.push_back(site);
  });
  each_table_of_array(root, "input", origin, [&](const toml::table& t, std::size_t i) {
    TableReader reader(t, origin, fmt::format("input {}", i + 1));
    InputConfig input;
    input.name = fmt::format("input{}", i + 1);
    read_input(reader, input);
    reader.finish();
    config.inputs.push_back(std::move(input));
  });
  return config;
}

Config load_config(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw ConfigError(fmt::format("{}: cannot open", path));
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw ConfigError(fmt::format("{}: read error", path));
  return parse_config(text.str(), path);
}

}  // namespace kew::daemon
