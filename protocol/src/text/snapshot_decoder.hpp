#pragma once
// What the decoders of JSON snapshots share: aircraft.json (aircraft_json.hpp), the
// OpenSky REST API's state vectors (opensky_rest.hpp) and readsb's traces
// (readsb_trace.hpp). Each top-level object of the stream is one snapshot, cut out by
// JsonObjectCutter (at most max_snapshot_bytes, a longer one skipped and counted
// "object_too_long") and parsed whole; the records it makes are emitted in data-time order
// when it has been read. The data time last reported per address is remembered across
// snapshots, end_message() included (one snapshot a datagram, a message, a fetched
// file), so that a position shown again is not reported again; finish() forgets it.
// Internal to kew_protocol.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "json_object.hpp"
#include "json_object_cutter.hpp"
#include "kew/protocol/decoder.hpp"

namespace kew::protocol::text {

class SnapshotDecoder : public Decoder {
 public:
  /// How long the data time of a reported position is remembered.
  struct Memory {
    /// A position of an address at most this much later than the one last reported for
    /// it is that same position (s, >= 0): the rounding of two snapshots' times.
    double same_position_s = 0.0;
    /// Positions older than the newest snapshot time by more than this are forgotten
    /// (s): no later snapshot can report them. Infinity keeps them until finish().
    double forget_after_s = std::numeric_limits<double>::infinity();
  };

  std::size_t max_message_bytes() const final { return max_bytes_; }
  void feed(std::span<const std::byte> bytes, const ReportSink& sink) final;
  /// The end of the stream: the decoder is as new (a stream read again reports again).
  void finish(const ReportSink& sink) final;
  /// A datagram (a NATS message, a snapshot fetched) ends its framing, but the snapshots
  /// go on: what was reported stays known, so the next one reports only what is new.
  void end_message(const ReportSink& sink) final;

 protected:
  /// `what` names a snapshot in messages ("aircraft.json snapshot").
  SnapshotDecoder(std::string what, std::size_t max_snapshot_bytes, Memory memory);

  /// Decodes one snapshot (`where` names it, "aircraft.json snapshot 3"): offer() for
  /// each record, refuse() for each problem. Returns the snapshot's time (UTC s), or
  /// nullopt when it was refused whole.
  virtual std::optional<double> decode_snapshot(std::string_view text, const std::string& where) = 0;

  /// A record of the snapshot: nothing when a position of its address (report.id, as
  /// parse_address() writes it) at the same or a later data time was reported;
  /// check_report()'s problem when that refuses it; else queued for the snapshot's end
  /// and remembered.
  LineResult offer(TrackReport& report);
  void refuse(std::string_view where, const LineProblem& problem);

  /// Calls `decode(element)` for each element of the snapshot's list `list` (its member
  /// `name`, as messages say it: "\"aircraft\""), refusing each problem it returns as
  /// "`where` `entry` N". A problem, and nothing decoded, when the list is absent
  /// (missing_field) or not an array (wrong_type).
  template <class Decode>
  LineResult decode_entries(const std::optional<simdjson::dom::element>& list, std::string_view name,
                            const std::string& where, std::string_view entry, Decode&& decode);
  JsonObjectParser& json() { return json_; }

 private:
  void decode(std::string_view text, const ReportSink& sink);

  std::size_t max_bytes_;
  Memory memory_;
  JsonObjectCutter cutter_;
  JsonObjectParser json_;
  std::unordered_map<std::uint32_t, double> last_reported_;  // address key → data time reported
  std::vector<TrackReport> ready_;
  double newest_time_ = -std::numeric_limits<double>::infinity();
  std::string key_id_;  // scratch for offer()
};

template <class Decode>
LineResult SnapshotDecoder::decode_entries(const std::optional<simdjson::dom::element>& list, std::string_view name,
                                           const std::string& where, std::string_view entry, Decode&& decode) {
  if (!list) return problem("missing_field", fmt::format("no {}", name));
  simdjson::dom::array array;
  if (list->get_array().get(array) != simdjson::SUCCESS)
    return problem("wrong_type", fmt::format("{} is not an array", name));
  std::size_t index = 0;
  for (const simdjson::dom::element element : array) {
    ++index;
    if (const LineResult bad = decode(element)) refuse(fmt::format("{} {} {}", where, entry, index), *bad);
  }
  return std::nullopt;
}

}  // namespace kew::protocol::text
