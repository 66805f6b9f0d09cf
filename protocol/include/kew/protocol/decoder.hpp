#pragma once
// The contract every track decoder keeps (design §5.1–5.2, issue "Protocol"):
//  - incremental: bytes may be split anywhere between feed() calls, and the reports are
//    the same as if the whole input had arrived at once;
//  - bounded: no message larger than max_message_bytes() is buffered; a longer one is
//    skipped and counted;
//  - resynchronising: after garbage the decoder finds the next plausible message;
//  - message-framed when asked: end_message() closes a datagram, nothing crosses it;
//  - every refusal is counted by reason in rejections().
// Decoders know nothing of sockets or files: the caller moves the bytes.

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "kew/track/track_report.hpp"
#include "kew/util/rejections.hpp"

namespace kew::protocol {

using ReportSink = std::function<void(const TrackReport&)>;

class Decoder {
 public:
  virtual ~Decoder() = default;

  /// Consumes the next bytes of the stream, calling `sink` for each complete report.
  virtual void feed(std::span<const std::byte> bytes, const ReportSink& sink) = 0;

  /// End of stream: a trailing partial message is counted ("truncated") and dropped;
  /// reports held back for merging (SBS) are emitted. The decoder may be fed again after.
  virtual void finish(const ReportSink& sink) = 0;

  /// The bytes fed since the last finish() or end_message() were one whole message (a UDP
  /// datagram): what they leave unfinished ends with them, as a complete message (a text
  /// datagram without a final newline still holds a whole last line, not a truncated one),
  /// and then, as after finish(), nothing is carried over to the next bytes. The default
  /// is finish(); line framings and wrappers override it.
  virtual void end_message(const ReportSink& sink) { finish(sink); }

  /// Live inputs: when the bytes about to be fed were received (UTC s). Formats that carry
  /// only a time of day (ASTERIX) then date each record by the day that puts it within
  /// 12 h of that time, as they do for a pcap capture, instead of counting days from the
  /// first record (a stream that starts with a record from just before midnight would be
  /// dated a day ahead). nullopt, the default, keeps the stream rule. Wrappers pass it on.
  virtual void set_receive_time(std::optional<double> utc_s) { (void)utc_s; }

  /// Short stable name of the format ("ndjson", "asterix", "sbs", ...).
  virtual std::string_view format_name() const = 0;

  /// Largest message the decoder buffers, bytes.
  virtual std::size_t max_message_bytes() const = 0;

  Rejections& rejections() { return rejections_; }
  const Rejections& rejections() const { return rejections_; }

  /// Convenience for text: feed(as_bytes(text)).
  void feed_text(std::string_view text, const ReportSink& sink) {
    feed(std::as_bytes(std::span<const char>(text.data(), text.size())), sink);
  }

 private:
  Rejections rejections_;
};

}  // namespace kew::protocol
