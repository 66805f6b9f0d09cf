#include "kew/daemon/config.hpp"

#include <algorithm>
#include <filesystem>

#include "kew/config/document.hpp"
#include "kew/config/nats_subject.hpp"
#include "notify.hpp"

namespace kew::daemon {

namespace {

using config::TableReader;

void read_service(TableReader& r, ServiceConfig& s) {
  r.address("alert_listen", s.alert_listen);
  r.integer("max_subscribers", s.max_subscribers, 1, 10000);
  r.integer("subscriber_queue", s.subscriber_queue, 16, 10'000'000);
  r.integer("subscriber_queue_bytes", s.subscriber_queue_bytes, 65536, std::int64_t{1} << 36);
  r.number("request_timeout_s", s.request_timeout_s, 0.1, 3600.0);
  r.number("idle_timeout_s", s.idle_timeout_s, 0.1, 86400.0);
  r.number("write_timeout_s", s.write_timeout_s, 0.1, 3600.0);
  r.integer("silent_per_address", s.silent_per_address, 1, 10000);
  r.number("alive_interval_s", s.alive_interval_s, 0.1, 3600.0);
  r.number("tick_interval_s", s.tick_interval_s, 0.05, 60.0);
  r.choice("log_level", s.log_level, kLogLevelNames);
  r.path("alert_log", s.alert_log);
  r.integer("alert_log_max_bytes", s.alert_log_max_bytes, 4096, std::int64_t{1} << 40);
  r.integer("alert_log_keep", s.alert_log_keep, 0, 1000);
  r.choice("alert_log_sync", s.alert_log_sync, kAlertLogSyncNames);
  r.integer("alert_log_queue_bytes", s.alert_log_queue_bytes, 65536, std::int64_t{1} << 40);
  r.path("state_directory", s.state_directory);
  r.path("record_file", s.record_file);
  r.integer("record_file_queue_bytes", s.record_file_queue_bytes, 65536, std::int64_t{1} << 40);
  r.boolean("tracks_stream", s.tracks_stream);
  r.number("max_future_s", s.max_future_s, 0.0, 86400.0);
  r.boolean("allow_remote", s.allow_remote);
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
  r.number("idle_timeout_s", m.idle_timeout_s, 0.1, 3600.0);
  r.integer("silent_per_address", m.silent_per_address, 1, 256);
  r.boolean("allow_remote", m.allow_remote);
  r.ip_list("acknowledge_from", m.acknowledge_from);
}

/// A map tile URL template: http(s)://, with {z}, {x} and {y}, no white space (design §5.8).
void tile_url(TableReader& r, std::string& out) {
  r.string("tile_url", out);
  if (out.empty() || !r.node("tile_url")) return;
  const bool web = out.starts_with("http://") || out.starts_with("https://");
  const bool whole = out.find("{z}") != std::string::npos && out.find("{x}") != std::string::npos &&
                     out.find("{y}") != std::string::npos;
  if (!web || !whole || out.find_first_of(" \t\r\n") != std::string::npos)
    r.fail(r.node("tile_url"), fmt::format("tile_url = \"{}\" must be an http:// or https:// URL template with {{z}}, "
                                           "{{x}} and {{y}} and no white space",
                                           out));
}

void read_http(TableReader& r, HttpConfig& h) {
  r.boolean("enabled", h.enabled);
  r.address("listen", h.listen);
  r.boolean("allow_remote", h.allow_remote);
  r.path("web_root", h.web_root);
  r.path("leaflet_root", h.leaflet_root);
  r.host_name_list("host_names", h.host_names);
  r.integer("max_connections", h.max_connections, 1, 10000);
  r.integer("silent_per_address", h.silent_per_address, 1, 10000);
  r.integer("max_header_bytes", h.max_header_bytes, 1024, 1 << 20);
  r.integer("max_body_bytes", h.max_body_bytes, 64, 1 << 20);
  r.number("request_timeout_s", h.request_timeout_s, 0.1, 3600.0);
  r.number("write_timeout_s", h.write_timeout_s, 0.1, 3600.0);
  r.integer("client_queue_bytes", h.client_queue_bytes, 65536, std::int64_t{1} << 36);
  tile_url(r, h.tile_url);
  r.string("tile_attribution", h.tile_attribution);
}

/// A subject key: dot-separated tokens, none empty, no white space; wildcards ('*', a
/// final '>') where kewd subscribes.
void subject(TableReader& r, std::string_view key, std::string& out, bool wildcards) {
  r.string(key, out);
  if (r.node(key) && !config::valid_nats_subject(out, wildcards))
    r.fail(r.node(key), fmt::format("{} = \"{}\" is not a NATS subject{}", key, out,
                                    wildcards ? "" : " to publish to (no wildcard)"));
}

/// A JetStream stream or consumer name: no '.', '*', '>' or white space.
void stream_name(TableReader& r, std::string_view key, std::string& out) {
  r.string(key, out);
  if (out.find_first_of(".*>/\\ \t") != std::string::npos)
    r.fail(r.node(key),
           fmt::format("{} = \"{}\": a JetStream name has no '.', '*', '>', '/', '\\' or space", key, out));
}

/// `url_key` (one URL, or several comma-separated) or `list_key` (an array), not both.
void server_list(TableReader& r, std::string_view url_key, std::string_view list_key, std::vector<std::string>& out) {
  std::vector<std::string> from_url, from_list;
  r.nats_servers(url_key, from_url);
  r.nats_servers(list_key, from_list);
  if (!from_url.empty() && !from_list.empty())
    r.fail(r.node(list_key), fmt::format("give {} or {}, not both", list_key, url_key));
  if (!from_url.empty()) out = std::move(from_url);
  if (!from_list.empty()) out = std::move(from_list);
}

void read_nats(TableReader& r, NatsConfig& n) {
  server_list(r, "url", "servers", n.servers);
  // JetStream keeps at most five copies of a stream.
  r.integer("replicas", n.replicas, 1, 5);
  r.string("name", n.name);
  subject(r, "alerts_subject", n.alerts_subject, false);
  subject(r, "acks_subject", n.acks_subject, false);
  subject(r, "status_subject", n.status_subject, false);
  subject(r, "tracks_subject", n.tracks_subject, false);
  r.number("tracks_interval_s", n.tracks_interval_s, 0.0, 3600.0);
  stream_name(r, "stream", n.stream);
  r.number("stream_max_age_s", n.stream_max_age_s, 1.0, 10.0 * 365 * 86400);
  r.integer("stream_max_bytes", n.stream_max_bytes, 1 << 20, std::int64_t{1} << 50);
  r.integer("outbox", n.outbox, 16, 100'000'000);
  r.boolean("hot_standby", n.hot_standby);
  stream_name(r, "lease_bucket", n.lease_bucket);
  stream_name(r, "pair_bucket", n.pair_bucket);
  r.number("checkpoint_interval_s", n.checkpoint_interval_s, 0.0, 86400.0);
  stream_name(r, "checkpoint_stream", n.checkpoint_stream);
  r.string("lease_key", n.lease_key);
  if (!config::valid_nats_subject(n.lease_key, false) || n.lease_key.find('.') != std::string::npos)
    r.fail(r.node("lease_key"), fmt::format("lease_key = \"{}\" is not a key (no '.', wildcard or space)", n.lease_key));
  r.number("lease_ttl_s", n.lease_ttl_s, 0.2, 60.0);
  r.string("instance", n.instance);
  r.integer("standby_history", n.standby_history, 16, 10'000'000);
  if (n.hot_standby && n.servers.empty())
    r.fail(r.node("hot_standby"), "hot_standby needs url or servers: the lease is on NATS");
  // A new active learns from the stream what the last one published.
  if (n.hot_standby && n.stream.empty())
    r.fail(r.node("hot_standby"), "hot_standby needs stream: a takeover reads the last event sent from it");
}

// OpenSky's REST API allows one request every 10 s without credentials and every 5 s
// with them (https://openskynetwork.github.io/opensky-api/rest.html, "Limitations").
bool is_opensky_api(std::string_view url) { return url.find("opensky-network.org/api") != std::string_view::npos; }

void read_http_keys(TableReader& r, InputConfig& in) {
  r.number("poll_interval_s", in.poll_interval_s, 0.1, 86400.0);
  r.number("timeout_s", in.timeout_s, 0.1, 3600.0);
  r.integer("max_response_bytes", in.max_response_bytes, 1024, std::int64_t{1} << 30);
  r.http_header_list("headers", in.headers);
  r.string("secret_header", in.secret_header);
  r.path("secret_file", in.secret_file);
  r.path("credentials_file", in.credentials_file);
  r.http_url("token_url", in.token_url);
  r.path("ca_file", in.ca_file);
  if (in.secret_header.empty() != in.secret_file.empty())
    r.fail(r.node(in.secret_header.empty() ? "secret_file" : "secret_header"),
           "secret_header and secret_file come together: the header's name and the file holding its value");
  if (in.transport == Transport::Http && is_opensky_api(in.address)) {
    const double least = in.credentials_file.empty() ? 10.0 : 5.0;
    if (in.poll_interval_s < least)
      r.fail(r.node("poll_interval_s"),
             fmt::format("poll_interval_s = {}: OpenSky's API allows one request every {} s {} credentials",
                         in.poll_interval_s, least, in.credentials_file.empty() ? "without" : "with"));
  }
}

void read_input(TableReader& r, InputConfig& in) {
  r.string("name", in.name);
  r.choice("format", in.format, protocol::kFormatNames);
  r.choice("transport", in.transport, kTransportNames);
  if (in.transport == Transport::File || in.transport == Transport::WatchedFile) r.path("address", in.address);
  else if (in.transport == Transport::Nats) subject(r, "address", in.address, true);
  else if (in.transport == Transport::Http) r.http_url("address", in.address);
  else r.address("address", in.address);
  server_list(r, "nats_url", "nats_servers", in.nats_servers);
  stream_name(r, "durable", in.durable);
  stream_name(r, "stream", in.stream);
  r.number("stream_max_age_s", in.stream_max_age_s, 1.0, 10.0 * 365 * 86400);
  r.string("interface", in.interface);
  r.number("reconnect_min_s", in.reconnect_min_s, 0.01, 3600.0);
  r.number("reconnect_max_s", in.reconnect_max_s, 0.01, 86400.0);
  r.integer("max_connections", in.max_connections, 1, 1024);
  r.number("idle_timeout_s", in.idle_timeout_s, 0.0, 86400.0);
  read_http_keys(r, in);
  r.boolean("pace", in.pace);
  r.number("speed", in.speed, 0.001, 1000.0);
  r.utc_day("asterix_day", in.asterix_day);
  r.boolean("allow_remote", in.allow_remote);
  if (in.allow_remote && in.transport != Transport::Udp && in.transport != Transport::TcpServer)
    r.fail(r.node("allow_remote"), "allow_remote is for inputs that listen (transport udp or tcp-server)");
  // A key the transport never reads is a mistake in the file (a reconnect delay on a
  // file, a pace on a socket): refused at its line, not ignored.
  const auto only_for_these = [&](std::string_view key, std::initializer_list<Transport> transports) {
    if (!r.node(key) || std::find(transports.begin(), transports.end(), in.transport) != transports.end()) return;
    std::string names;
    for (const Transport t : transports) names += (names.empty() ? "" : " and ") + std::string(kTransportNames.name(t));
    r.fail(r.node(key), fmt::format("{} is for transport {} only", key, names));
  };
  const auto only_for = [&](std::string_view key, Transport transport) { only_for_these(key, {transport}); };
  only_for("interface", Transport::Udp);
  only_for_these("reconnect_min_s", {Transport::TcpClient, Transport::Http});
  only_for_these("reconnect_max_s", {Transport::TcpClient, Transport::Http});
  for (const std::string_view key : {"poll_interval_s", "timeout_s", "max_response_bytes", "headers", "secret_header",
                                     "secret_file", "credentials_file", "token_url", "ca_file"})
    only_for(key, Transport::Http);
  only_for("max_connections", Transport::TcpServer);
  only_for("idle_timeout_s", Transport::TcpServer);
  only_for("pace", Transport::File);
  only_for("speed", Transport::File);
  only_for("nats_url", Transport::Nats);
  only_for("nats_servers", Transport::Nats);
  only_for("durable", Transport::Nats);
  only_for("stream", Transport::Nats);
  only_for("stream_max_age_s", Transport::Nats);
  if (!in.stream.empty() && in.durable.empty())
    r.fail(r.node("stream"), "stream names where a durable consumer reads: give durable too");
  if (in.address.empty()) r.fail(nullptr, "an input needs an address (HOST:PORT, a file path or a NATS subject)");
  if (in.format == protocol::Format::AsterixDatagram && in.transport != Transport::Udp)
    r.fail(nullptr, "format asterix-datagram needs transport udp");
}

Config read_config(const config::Document& document) {
  Config c;
  c.origin = document.origin();
  static_cast<config::SharedConfig&>(c) = config::read_shared_config(document);
  document.section("service", [&](TableReader& r) { read_service(r, c.service); });
  document.section("cat004", [&](TableReader& r) { read_cat004(r, c.cat004); });
  document.section("modbus", [&](TableReader& r) { read_modbus(r, c.modbus); });
  document.section("http", [&](TableReader& r) { read_http(r, c.http); });
  document.section("nats", [&](TableReader& r) { read_nats(r, c.nats); });
  document.each_table("input", [&](TableReader& r, std::size_t i) {
    InputConfig input;
    input.name = "input" + std::to_string(i + 1);
    read_input(r, input);
    // Names label the metrics, ?STATS and the log: two inputs of one name would read as one.
    for (std::size_t k = 0; k < c.inputs.size(); ++k)
      if (c.inputs[k].name == input.name)
        r.fail(nullptr, "name \"" + input.name + "\" is the name of input " + std::to_string(k + 1) + " already");
    c.inputs.push_back(std::move(input));
  });
  document.each_table("notify", [&](TableReader& r, std::size_t) {
    NotifyConfig notify;
    read_notify(r, notify);
    for (const NotifyConfig& other : c.notify)
      if (other.name == notify.name) r.fail(nullptr, "name \"" + notify.name + "\" is another notifier's already");
    c.notify.push_back(std::move(notify));
  });
  for (InputConfig& input : c.inputs) {
    if (input.transport != Transport::Nats) continue;
    if (input.nats_servers.empty())
      input.nats_servers = c.nats.servers.empty() ? std::vector<std::string>{std::string(kDefaultNatsUrl)} : c.nats.servers;
    input.stream_replicas = c.nats.replicas;
  }
  return c;
}

}  // namespace

Config parse_config(std::string_view toml_text, std::string_view origin) {
  return read_config(config::Document::parse(toml_text, std::string(origin)));
}

Config load_config(const std::string& path) { return read_config(config::Document::load(path)); }

Config default_config() {
  Config c = read_config(config::Document::parse("", "the built-in configuration"));
  c.origin.clear();
  return c;
}

std::string state_directory(const ServiceConfig& service) {
  if (!service.state_directory.empty()) return service.state_directory;
  // Next to the alert log: a plain run keeps its numbering with its log, and a log
  // moved elsewhere starts afresh with it.
  if (!service.alert_log.empty())
    return std::filesystem::absolute(service.alert_log).parent_path().string();
  return {};
}

}  // namespace kew::daemon
