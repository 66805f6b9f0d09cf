#pragma once
// The client side of the alert stream (design §5.3): the subscriber's ?WATCH request as the
// server reads it, and the server's objects as a client (kew-watch, end-to-end tests)
// reads them back. Nothing here throws; every refusal comes back as an error text.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "kew/alert/alert_event.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/track/track_report.hpp"

namespace kew::protocol {

/// What a subscriber asked for with ?WATCH.
struct WatchRequest {
  /// false stops the stream (the connection stays open).
  bool enable = true;
  /// ALERT objects below this severity are not sent; End events of an alert that was
  /// sent are always sent.
  Severity min_severity = Severity::Caution;
  /// Send TRACK objects too.
  bool tracks = false;
};

/// A request read from a client: what it asked, or why it was refused.
template <class Request>
struct RequestParse {
  bool ok = false;
  Request request;    ///< meaningful when ok
  std::string error;  ///< why the request was refused, when !ok
};
using WatchParseResult = RequestParse<WatchRequest>;

/// Longest request line accepted, bytes (the server bounds its read buffer by it too).
inline constexpr std::size_t kMaxWatchRequestBytes = 4096;

/// Parses `?WATCH={"enable":true,"min_severity":"caution","tracks":false}` (members
/// optional, defaults as in WatchRequest), or a bare `?WATCH` meaning all defaults. A
/// trailing ';' and surrounding white space (CR, LF) are accepted, as gpsd clients send
/// them. Members kew does not know (gpsd's "json", "nmea", ...) are ignored; a known
/// member of the wrong type, an unknown severity, malformed JSON or any other command is
/// an error.
WatchParseResult parse_watch_request(std::string_view line);

/// What POST /api/ack asked (design §5.8): one alert, or all of them.
struct AckRequest {
  bool all = false;
  std::string id;  ///< when !all
};

using AckParseResult = RequestParse<AckRequest>;

/// Longest acknowledgement body accepted, bytes.
inline constexpr std::size_t kMaxAckRequestBytes = 4096;

/// Parses the body of POST /api/ack: {"id":"<alert id>"} or {"all":true}. Anything else
/// (both, neither, "all" not true, wrong types, malformed JSON) is an error.
AckParseResult parse_ack_request(std::string_view body);

/// Class of one object of the stream.
enum class StreamObjectClass : std::uint8_t { Version, Alert, Alerts, Alive, Error, Track, Ack, Start };

/// Reads the stream's lines back into kew's types. One reader is reused for many lines
/// (it keeps its parser and buffers); not thread-safe.
class AlertStreamReader {
 public:
  AlertStreamReader();
  ~AlertStreamReader();
  AlertStreamReader(const AlertStreamReader&) = delete;
  AlertStreamReader& operator=(const AlertStreamReader&) = delete;

  /// Parses one line (a trailing '\n' is allowed). Returns false, with error() telling
  /// why, when the line is not valid JSON, not an object, of an unknown class, or lacks
  /// a required member or has one of the wrong type. Members the reader does not know
  /// are ignored (newer servers may add some). Numbers printed as `null` read as NaN.
  bool read(std::string_view line);

  /// Class and seq of the last successful read(). The object's content is in the
  /// accessor of its class, valid until the next read().
  StreamObjectClass object_class() const { return class_; }
  std::uint64_t seq() const { return seq_; }
  /// ALERT: the event. Members the stream does not carry keep their defaults; the
  /// event's own `seq` is the line's seq.
  const AlertEvent& alert() const { return alert_; }
  /// ALERTS: the active alerts of the snapshot, in order.
  const std::vector<AlertEvent>& alerts() const { return alerts_; }
  const AliveStatus& alive() const { return alive_; }
  const TrackReport& track() const { return track_; }
  /// ACK: the acknowledged alert ids; text() names the interface ("modbus").
  const std::vector<std::string>& acknowledged() const { return acknowledged_; }
  /// ACK: the client that acknowledged ("HOST:PORT"; "" when the object names none).
  const std::string& acknowledging_client() const { return acknowledging_client_; }
  /// ERROR: the message. VERSION, START: the release.
  const std::string& text() const { return text_; }
  /// VERSION, START: the source revision ("" from servers before it was sent).
  const std::string& revision() const { return revision_; }
  /// START: the run id and the wall clock time of the start (UTC s).
  const std::string& run() const { return run_; }
  double start_t() const { return start_t_; }
  /// VERSION: the protocol version.
  int proto() const { return proto_; }

  /// Why the last read() failed.
  const std::string& error() const { return error_; }

 private:
  struct Parser;
  std::unique_ptr<Parser> parser_;
  StreamObjectClass class_ = StreamObjectClass::Version;
  std::uint64_t seq_ = 0;
  AlertEvent alert_;
  std::vector<AlertEvent> alerts_;
  AliveStatus alive_;
  TrackReport track_;
  std::string text_;
  std::string run_;
  std::string revision_;
  double start_t_ = 0.0;
  std::vector<std::string> acknowledged_;
  std::string acknowledging_client_;
  int proto_ = 0;
  std::string error_;
};

}  // namespace kew::protocol
