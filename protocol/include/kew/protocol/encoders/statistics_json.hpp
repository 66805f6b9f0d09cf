#pragma once
// The statistics object, one writer for both places it appears (design §5.6): kewd's
// answer to ?STATS on the alert stream ({"class":"STATS",...}) and kew-replay's
// --stats-json file. Both begin with the same figures of the pipeline, under the same
// keys; each adds the figures only it has (kewd: its inputs and listeners; kew-replay:
// audits and wall time). Every key is documented in docs/protocol.md
// ("Statistics").

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kew/util/rejections.hpp"

namespace kew {
class Pipeline;  // kew/pipeline/pipeline.hpp: the encoders read its statistics and zones
}

namespace kew::protocol {

/// One kewd input.
struct InputStatistics {
  std::string name;
  std::uint64_t bytes = 0;
  std::uint64_t reports = 0;              ///< records its decoders produced
  std::uint64_t connections = 0;          ///< accepted (server) or established (client)
  std::uint64_t connections_refused = 0;  ///< over max_connections
  std::uint64_t connections_idle = 0;     ///< closed: no byte for idle_timeout_s
  std::uint64_t accept_failures = 0;      ///< accept() failed (out of descriptors, ...)
  std::uint64_t oversized_datagrams = 0;
  std::uint64_t datagrams_dropped = 0;    ///< UDP: dropped by the kernel, the receive buffer full
  std::uint64_t messages_dropped = 0;     ///< NATS: dropped by the client while kewd fell behind
  std::uint64_t polls = 0;                ///< http: answers taken (200)
  std::uint64_t polls_unchanged = 0;      ///< http: answers "not modified" (304)
  std::uint64_t poll_failures = 0;        ///< http: no answer, an error status, too large, no token
  Rejections rejected;                    ///< its decoders' rejections
};

struct SubscriberStatistics {
  std::uint64_t accepted = 0;
  std::uint64_t refused = 0;      ///< over max_subscribers and the reserved slots, or ?WATCH in one
  std::uint64_t admin = 0;        ///< accepted into a reserved (?STATS only) slot
  std::uint64_t cut_off = 0;      ///< disconnected for falling behind (bytes, objects) or a stalled write
  std::uint64_t timed_out = 0;    ///< closed for not completing a request line in time
  std::uint64_t evicted = 0;      ///< closed, silent, to make room for a newcomer (design §6.6)
  std::uint64_t bad_requests = 0;
  std::uint64_t accept_failures = 0;   ///< accept() failed (out of descriptors, ...)
  std::uint64_t backlog_bytes_max = 0; ///< the most bytes one session had queued
};

struct Cat004Statistics {
  std::uint64_t datagrams = 0;
  std::uint64_t errors = 0;  ///< sends that failed
};

/// kewd's publisher on NATS ([nats]).
struct NatsStatistics {
  bool connected = false;
  std::uint64_t disconnects = 0;  ///< connections to the server lost
  std::uint64_t published = 0;    ///< events (alerts, acks) the server has taken (JetStream: stored)
  std::uint64_t retries = 0;      ///< publications tried again (no server, no acknowledgement in time)
  std::uint64_t queued = 0;       ///< events waiting for the server now
  std::uint64_t dropped = 0;      ///< events dropped: more than [nats] outbox waited
  std::uint64_t status_published = 0;  ///< ALIVE and TRACKS objects (not kept)
  /// Hot standby: publications JetStream refused because another publisher had added to
  /// the stream since (a stalled active's last words, or this instance fenced).
  std::uint64_t fenced = 0;
  std::optional<bool> active;          ///< hot standby: holds the lease
  /// Hot standby: active with every NATS server away (the lease unconfirmed; the outputs
  /// that need no bus go on, NATS publication waits).
  bool bus_away = false;
  /// Hot standby: checkpoints of the computation this instance wrote as the active, and
  /// whether it began from one (design §5.9).
  std::uint64_t checkpoints_written = 0;
  bool began_from_checkpoint = false;
};

/// One [[notify]] endpoint (design §5.10).
struct NotifyStatistics {
  std::string name;
  std::uint64_t delivered = 0;  ///< messages the endpoint took
  std::uint64_t failures = 0;   ///< delivery attempts that failed
  std::uint64_t dropped = 0;    ///< events dropped from its full outbox
  std::uint64_t queued = 0;     ///< events waiting now
  bool failing = false;         ///< failing longer than its failing_after_s
};

struct ModbusStatistics {
  std::uint64_t requests = 0;              ///< complete requests answered or refused
  std::uint64_t exceptions = 0;            ///< exception responses sent
  std::uint64_t connections_accepted = 0;
  std::uint64_t connections_refused = 0;   ///< closed at once: max_connections reached
  std::uint64_t acknowledgements = 0;      ///< coil 0 written 1
  std::uint64_t connections_dropped = 0;   ///< closed by kew: bad framing, idle, send failure
  std::uint64_t connections_open = 0;      ///< now
  /// Refused requests and dropped connections by reason (keys "modbus_*", README.md,
  /// "Modbus TCP alarm map").
  Rejections rejected;
};

/// What kewd adds to the pipeline's figures.
struct ServiceStatistics {
  std::uint64_t seq = 0;  ///< the number of the last alert event sent (as every object carries)
  double uptime_s = 0.0;
  std::uint64_t subscribers_now = 0;  ///< connected at this moment
  SubscriberStatistics subscribers;
  std::vector<InputStatistics> inputs;
  std::optional<Cat004Statistics> cat004;  ///< when CAT004 is enabled
  std::optional<ModbusStatistics> modbus;  ///< when Modbus is enabled
  std::optional<NatsStatistics> nats;      ///< when [nats] url is set
  std::vector<NotifyStatistics> notify;    ///< one per [[notify]]
  std::optional<std::uint64_t> alert_log_errors;  ///< when an alert log is written
  /// When an alert log is written: bytes of events waiting for it (a failing disk) and
  /// lines dropped because more than the queue's bound waited.
  std::optional<std::uint64_t> alert_log_queued_bytes;
  std::optional<std::uint64_t> alert_log_dropped;
  /// When a record file is written: bytes of records waiting for it and records dropped
  /// because more than its queue's bound waited.
  std::optional<std::uint64_t> record_file_queued_bytes;
  std::optional<std::uint64_t> record_file_dropped;
  std::optional<std::uint64_t> resident_bytes;    ///< when /proc tells
};

/// What kew-replay adds to the pipeline's figures.
struct ReplayStatistics {
  std::uint64_t audits = 0;  ///< audits run (--audit)
  std::uint64_t audit_violations_found = 0;
  std::uint64_t audit_violations_unrepaired = 0;
  double wall_s = 0.0;  ///< wall-clock duration of the run
};

/// kewd's STATS object, one line ending in '\n'. Its `rejected` is every rejection so
/// far: the pipeline's merged with the decoders' of every input (service.inputs).
std::string stats_json(const Pipeline& pipeline, const ServiceStatistics& service);

/// {"class":"ZONES","mode":"worldwide","count":…,"created":…,"retired":…,"margin_km":…,
/// "threads":…,"list":[{"name":"N49.5E013.3","south":…,"north":…,"west":…,"east":…,
/// "tracks":…,"updates":…,"probes":…,"busy_s":…,"max_scale":…},…]} and a newline: the
/// zones of design §4.9 (bounds in degrees, only in worldwide mode; busy_s the wall
/// seconds the zone's work took). The same members are ?STATS' and --stats-json's
/// "zones". GET /api/zones.
void append_zones_json(std::string& out, const Pipeline& pipeline);

/// kew-replay's statistics object, one line ending in '\n'. Its `rejected` is the
/// pipeline's rejections merged with `decoding`, the decoders' of every recording.
std::string run_statistics_json(const Pipeline& pipeline, const Rejections& decoding,
                                const ReplayStatistics& replay);

}  // namespace kew::protocol
