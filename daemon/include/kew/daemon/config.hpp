#pragma once
// kewd's configuration (design §5.7): the tables every tool shares (config::SharedConfig,
// read by kew_config) and kewd's own [service], [cat004], [modbus], [http], [[input]] and
// [[notify]] tables, read here. Every key, its unit and its default is documented in deploy/kew.toml.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "kew/config/config_error.hpp"
#include "kew/config/shared_config.hpp"
#include "kew/daemon/notify_config.hpp"
#include "kew/protocol/formats.hpp"
#include "kew/util/name_table.hpp"

namespace kew::daemon {

enum class Transport { Udp, TcpClient, TcpServer, File, Nats, WatchedFile, Http };
/// The names of `transport = ...`.
inline constexpr util::NameTable<Transport, 7> kTransportNames({{
    {Transport::Udp, "udp"},
    {Transport::TcpClient, "tcp-client"},
    {Transport::TcpServer, "tcp-server"},
    {Transport::File, "file"},
    {Transport::Nats, "nats"},
    {Transport::WatchedFile, "watched-file"},
    {Transport::Http, "http"},
}});
constexpr std::string_view to_string(Transport t) { return kTransportNames.name(t); }

enum class LogLevel { Trace, Debug, Info, Warn, Error, Critical, Off };
/// The names of `log_level = ...` and `kewd --log-level`.
inline constexpr util::NameTable<LogLevel, 7> kLogLevelNames({{
    {LogLevel::Trace, "trace"},
    {LogLevel::Debug, "debug"},
    {LogLevel::Info, "info"},
    {LogLevel::Warn, "warn"},
    {LogLevel::Error, "error"},
    {LogLevel::Critical, "critical"},
    {LogLevel::Off, "off"},
}});
constexpr std::string_view to_string(LogLevel level) { return kLogLevelNames.name(level); }

/// When the alert log is forced to the disk (fdatasync; design §6.6).
enum class AlertLogSync { None, Interval, Every };
inline constexpr util::NameTable<AlertLogSync, 3> kAlertLogSyncNames({{
    {AlertLogSync::None, "none"},          // the kernel writes back when it likes
    {AlertLogSync::Interval, "interval"},  // at most once a second, when written
    {AlertLogSync::Every, "every"},        // after each event (and acknowledgement)
}});

/// One `[[input]]` table.
struct InputConfig {
  std::string name;                 ///< for logs and statistics; default "input<N>"
  protocol::Format format = protocol::Format::Auto;
  Transport transport = Transport::Udp;
  /// udp: "HOST:PORT" to bind (HOST may be a multicast group, joined on `interface`);
  /// tcp-client: "HOST:PORT" to connect to; tcp-server: "HOST:PORT" to listen on;
  /// file: a path (read once, as fast as the pipeline takes it, unless `pace`);
  /// nats: the subject to subscribe to (wildcards allowed), one message = one datagram;
  /// watched-file: a path; http: the URL polled (http:// or https://).
  std::string address;
  std::string interface = "0.0.0.0";  ///< multicast: local interface address
  double reconnect_min_s = 1.0;       ///< tcp-client, http: backoff, doubling up to max
  double reconnect_max_s = 30.0;
  std::size_t max_connections = 4;    ///< tcp-server
  /// tcp-server: a feed connection that sends no byte for this long is closed (0: never).
  double idle_timeout_s = 60.0;
  /// http: one request every poll_interval_s while the server answers (from the start
  /// of one to the start of the next); each answer is one message of `format`.
  double poll_interval_s = 1.0;
  double timeout_s = 10.0;  ///< http: a request's connection and transfer together
  /// http: a larger answer (after decompression) is refused and counted; also bounded
  /// by the decoder's message limit ([decoding] max_snapshot_bytes).
  std::size_t max_response_bytes = 32u << 20;
  std::vector<std::string> headers;  ///< http: sent with every request, "Name: value"
  /// http: the header named secret_header carries secret_file's text (an API key).
  std::string secret_header;
  std::string secret_file;
  /// http: credentials_file holds OpenSky's credentials.json (OAuth2 client credentials,
  /// a token from token_url) or one line "user:password" (HTTP basic).
  std::string credentials_file;
  std::string token_url;  ///< http: "" = OpenSky's token endpoint
  std::string ca_file;    ///< http: PEM certificates trusted besides the system's
  bool pace = false;                  ///< file: replay paced like the recording
  double speed = 1.0;                 ///< file with pace: multiple of recorded speed
  /// Data day for ASTERIX time of day (UTC midnight, "YYYY-MM-DD"); empty: today (live)
  /// or the pcap timestamps (files).
  std::string asterix_day;
  /// udp, tcp-server: `address` may be a wildcard, an interface or a multicast group
  /// (a real radar's feed); otherwise it must be loopback unless kewd runs --listen-any.
  bool allow_remote = false;
  /// nats: the servers of one NATS cluster, "nats://HOST:PORT" each (keys nats_servers,
  /// or nats_url: one URL or several comma-separated); the client connects to any and
  /// reconnects to any. Default: [nats]'s servers, else kDefaultNatsUrl.
  std::vector<std::string> nats_servers;
  /// nats: a JetStream durable consumer of this name reads the subject, so that a
  /// restarted kewd resumes after the last message it took; "" = a plain subscription
  /// (messages sent while kewd is away are not seen).
  std::string durable;
  /// nats with durable: the JetStream stream holding the subject; created for the
  /// subject when missing (kept `stream_max_age_s`, with [nats] replicas); "" = the
  /// stream that holds it.
  std::string stream;
  double stream_max_age_s = 86400.0;
  /// nats: replicas of the stream kewd creates ([nats] replicas, copied here; 1–5).
  int stream_replicas = 1;
};

/// Where a NATS input connects when neither it nor [nats] names a server.
inline constexpr std::string_view kDefaultNatsUrl = "nats://127.0.0.1:4222";

/// [nats]: alert events, acknowledgements and status published on a NATS server (design
/// §5.9), the events kept in a JetStream stream for subscribers that were away.
struct NatsConfig {
  /// The servers of one NATS cluster, "nats://HOST:PORT" each (keys servers, or url: one
  /// URL or several comma-separated); the client connects to any and reconnects to any.
  /// Empty: publish nothing.
  std::vector<std::string> servers;
  /// Replicas (1–5) of what kewd creates in JetStream: the alert stream, the lease bucket
  /// and the feed streams of durable NATS inputs; an existing one is updated to it.
  int replicas = 1;
  std::string name = "kewd";                 ///< the connection's name on the server
  std::string alerts_subject = "kew.alerts"; ///< ALERT objects go to <alerts_subject>.<zone>
  std::string acks_subject = "kew.acks";     ///< ACK objects
  std::string status_subject = "kew.status"; ///< ALIVE objects (not kept)
  std::string tracks_subject = "kew.tracks"; ///< TRACKS snapshots (not kept)
  double tracks_interval_s = 0.0;            ///< 0: no track snapshots
  std::string stream = "KEW_ALERTS";         ///< JetStream stream of alerts and acks; "" = none
  double stream_max_age_s = 7 * 86400.0;     ///< events older than this leave the stream
  std::uint64_t stream_max_bytes = 1ull << 30;
  /// Events waiting for the server (while it is away) before the oldest are dropped (counted).
  std::size_t outbox = 100000;
  /// Hot standby: kewd instances of one lease_key elect one active through the JetStream
  /// key-value bucket lease_bucket; the others compute silently and take over when it dies.
  bool hot_standby = false;
  std::string lease_bucket = "KEW_LEASE";
  /// Hot standby: the key-value bucket (no TTL) holding the pair's origin under
  /// lease_key: where the feed and the numbering of the pair's computation begin.
  std::string pair_bucket = "KEW_PAIR";
  /// Hot standby: the active writes a checkpoint of its computation every this many
  /// seconds (0: never) into the JetStream stream checkpoint_stream, and an instance that
  /// starts judges the feed from the latest one instead of the pair's origin.
  double checkpoint_interval_s = 300.0;
  std::string checkpoint_stream = "KEW_CHECKPOINTS";
  std::string lease_key = "active";
  double lease_ttl_s = 1.5;  ///< a dead active is replaced within 1.25 × this
  std::string instance;      ///< this kewd's name in the lease; "" = HOST-PID
  /// Alert events a standby keeps for a takeover (the active's last ones it may not have
  /// published).
  std::size_t standby_history = 10000;
};

struct ServiceConfig {
  std::string alert_listen = "127.0.0.1:4747";
  std::size_t max_subscribers = 32;
  std::size_t subscriber_queue = 262144;  ///< objects queued per subscriber before it is cut off
  std::size_t subscriber_queue_bytes = 64u << 20;  ///< bytes queued per subscriber before it is cut off
  double request_timeout_s = 10.0;  ///< a connection must complete its first request line in this time
  double idle_timeout_s = 60.0;     ///< a connection not watching must complete a request this often
  double write_timeout_s = 30.0;    ///< a write to a subscriber that takes longer cuts it off
  /// Silent connections one address may hold; one more from it closes its longest-silent.
  std::size_t silent_per_address = 4;
  double alive_interval_s = 1.0;
  double tick_interval_s = 1.0;         ///< live clock tick (timeouts, kinetic events)
  LogLevel log_level = LogLevel::Info;
  std::string alert_log;                ///< JSON-lines file of every alert event; "" = none
  std::uint64_t alert_log_max_bytes = 64ull << 20;
  int alert_log_keep = 5;
  AlertLogSync alert_log_sync = AlertLogSync::Interval;
  /// Bytes of alert events kept in memory while the alert log cannot be written; beyond,
  /// the oldest are dropped (counted).
  std::uint64_t alert_log_queue_bytes = 64ull << 20;
  /// Where kewd keeps what must survive a restart (the last seq and alert number,
  /// design §4.7); "" = the alert log's directory, or none without an alert log.
  std::string state_directory;
  std::string record_file;              ///< canonical NDJSON of every decoded record; "" = none
  /// Bytes of records kept in memory while the record file cannot be written; beyond,
  /// the oldest are dropped (counted).
  std::uint64_t record_file_queue_bytes = 64ull << 20;
  bool tracks_stream = true;            ///< allow WATCH "tracks": true
  /// A record dated more than this after the wall clock is refused ("future_time"), s.
  double max_future_s = 10.0;
  bool allow_remote = false;            ///< alert_listen may be other than loopback
};

struct Cat004Config {
  bool enabled = false;
  std::string destination = "127.0.0.1:8601";  ///< UDP "HOST:PORT"; multicast allowed
  std::string interface = "0.0.0.0";
  int ttl = 1;
  std::uint8_t sac = 0, sic = 1;
  double alive_interval_s = 1.0;
};

struct ModbusConfig {
  bool enabled = false;
  std::string listen = "127.0.0.1:1502";
  int unit_id = 1;
  int table_entries = 8;
  bool read_only = false;
  int max_connections = 8;
  /// A client that completes no request for this long is disconnected, s.
  double idle_timeout_s = 10.0;
  /// Clients that have completed no request one address may hold (at least 1); one more
  /// from it closes its longest-silent.
  int silent_per_address = 4;
  bool allow_remote = false;  ///< `listen` may be other than loopback
  /// Client addresses (canonical_ip form) whose writes are served; empty: every client.
  std::vector<std::string> acknowledge_from;
};

/// The HTTP server of design §5.8: map, JSON API, WebSocket, acknowledgement, metrics.
struct HttpConfig {
  bool enabled = true;
  std::string listen = "127.0.0.1:8747";
  bool allow_remote = false;  ///< `listen` may be other than loopback
  /// The map's files; "" = the installed share/kew/web (the source tree's web/ when kewd
  /// runs from its build tree).
  std::string web_root;
  /// Served under /leaflet/ (Debian's libjs-leaflet).
  std::string leaflet_root = "/usr/share/javascript/leaflet";
  /// Host names (besides localhost and IP literals) a POST /api/ack may name in Host.
  std::vector<std::string> host_names;
  std::size_t max_connections = 64;       ///< HTTP and WebSocket connections at once
  /// Connections waiting for a request one address may hold; one more from it closes its
  /// longest-waiting. Above a browser's 6 per host, for users behind one proxy or NAT.
  std::size_t silent_per_address = 16;
  std::size_t max_header_bytes = 8192;    ///< request line and headers; beyond: 431
  std::size_t max_body_bytes = 4096;      ///< request body; beyond: 413
  double request_timeout_s = 10.0;        ///< a request must arrive whole within this
  double write_timeout_s = 30.0;          ///< a reply or WebSocket client that stalls this long is closed
  std::size_t client_queue_bytes = 16u << 20;  ///< WebSocket bytes queued per client before cut-off
  /// The map's tile server, a URL template with {z}, {x} and {y} (http or https); "" =
  /// the offline Natural Earth base map. Served to the page by GET /api/map-config.
  std::string tile_url;
  std::string tile_attribution;  ///< shown on the map with tile_url's tiles (plain text)
};

/// A kewd file: the shared tables (pipeline, decoding) and kewd's own.
struct Config : config::SharedConfig {
  ServiceConfig service;
  Cat004Config cat004;
  ModbusConfig modbus;
  HttpConfig http;
  NatsConfig nats;
  std::vector<InputConfig> inputs;
  std::vector<NotifyConfig> notify;
  std::string origin;  ///< the file's name in messages ("" for the built-in defaults)
};

/// The state directory kewd uses: `state_directory`, else the alert log's directory;
/// "" when there is neither (seq and numbers then start at 1 at each start).
std::string state_directory(const ServiceConfig& service);

/// Parses TOML text; `origin` names it in error messages. Throws config::ConfigError.
Config parse_config(std::string_view toml_text, std::string_view origin = "config");
/// Reads and parses a file. Throws config::ConfigError.
Config load_config(const std::string& path);
/// kewd without a file: every default, and the default aerodrome table loaded
/// (config::default_shared_config). Throws config::ConfigError when it cannot be read.
Config default_config();

/// `kewd --replay FILE` (design §5.6): what the command line says about the replay.
struct ReplaySettings {
  std::string file;                                   ///< the recording
  protocol::Format format = protocol::Format::Auto;
  double speed = 1.0;                                 ///< multiple of recorded speed; 0: as fast as possible
  std::string alert_listen;                           ///< "" = the configuration's alert_listen
  std::string http_listen;                            ///< "" = the configuration's [http] listen
  std::string alert_log;                              ///< "" = none (nothing is written unless asked)
};

/// Turns `config` (built-in defaults, or the file of -c) into the configuration of a
/// replay: its shared tables and [service] limits stay; its [[input]] tables are replaced
/// by one paced `file` input named "replay" reading `replay.file`; every listener is on
/// loopback (allow_remote cleared: check_config then refuses any other address); the
/// outputs that reach other systems or write files (CAT004, Modbus, notifiers,
/// record_file, the state directory, the alert log unless `replay.alert_log`) are off. Relative paths
/// are made absolute.
void apply_replay(Config& config, const ReplaySettings& replay);

/// One socket kewd listens on, as configured.
struct Listener {
  std::string name;     ///< "[service] alert_listen", "[modbus] listen", "[input 2] address"
  std::string address;  ///< HOST:PORT as configured
  bool udp = false;
  bool allow_remote = false;
};
/// Every listening socket of `config`: the subscriber port, Modbus and HTTP when enabled, and the
/// udp and tcp-server inputs.
std::vector<Listener> listeners(const Config& config);

/// The directories systemd creates for kewd.service before it runs kewd (the unit's
/// LogsDirectory= and StateDirectory=: /var/log/kew, /var/lib/kew), absolute.
std::vector<std::string> systemd_directories();

struct CheckOptions {
  bool listen_any = false;  ///< kewd --listen-any
  /// Directories that systemd creates before kewd starts (systemd_directories() for
  /// `kewd --check-config`, which may run before the service ever started): one that is
  /// missing while its parent directory exists passes, with a note. Empty when kewd is
  /// about to start: what it writes to must exist then.
  std::vector<std::string> created_by_systemd;
};

/// What the file alone cannot tell, checked by `kewd --check-config` and again before
/// kewd starts, so that a file that passes the check does not fail at start. Returns
/// notes on what passed on trust (a directory systemd will create). Throws
/// config::ConfigError naming the key and its value:
/// - every listener binds a loopback address unless its table says allow_remote = true
///   or `listen_any` (kewd --listen-any);
/// - no two listeners share a port (per protocol, TCP or UDP, and address family);
/// - alert_log and record_file are distinct, are not directories, and can be written:
///   an existing file writable, its directory existing and writable (the alert log
///   rotates by renaming in it; a new file is created in it);
/// - the state directory is a writable directory, or can be created (its parent exists);
/// - a directory of `options.created_by_systemd` may be missing if its parent exists.
std::vector<std::string> check_config(const Config& config, const CheckOptions& options);
/// check_config for kewd about to start (nothing created by systemd on trust).
inline void check_config(const Config& config, bool listen_any) { check_config(config, CheckOptions{listen_any, {}}); }

}  // namespace kew::daemon
