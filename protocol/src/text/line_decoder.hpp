#pragma once
// The line framing shared by every line-oriented text decoder (NDJSON, SBS, OpenSky CSV,
// readsb): splits the byte stream into lines across feed() calls, bounds the line length,
// skips blank and '#' comment lines, and counts every refused line with its number.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "kew/protocol/decoder.hpp"
#include "text_fields.hpp"

namespace kew::protocol::text {

class LineDecoder : public Decoder {
 public:
  /// `max_line_bytes`: longest line buffered, bytes, excluding the '\n' but including a
  /// '\r' before it; at least 16 (smaller values are raised to 16).
  explicit LineDecoder(std::size_t max_line_bytes);

  void feed(std::span<const std::byte> bytes, const ReportSink& sink) final;
  void finish(const ReportSink& sink) final;
  /// A last line without '\n' is a whole line here, refused by its own reason if at all.
  void end_message(const ReportSink& sink) final;
  std::size_t max_message_bytes() const final { return max_line_bytes_; }

 protected:
  /// One line without its terminator ('\n' and a '\r' before it), neither blank nor a
  /// comment. May call `sink` any number of times.
  virtual LineResult decode_line(std::string_view line, const ReportSink& sink) = 0;
  /// End of stream, after the last line: drop per-stream state (e.g. a CSV header).
  virtual void end_of_stream(const ReportSink& /*sink*/) {}

 private:
  /// `terminated` is false for a last line that ended with the stream instead of '\n':
  /// if it is refused, it is counted as "truncated" (the Decoder contract).
  void dispatch(std::string_view line, bool terminated, const ReportSink& sink);
  void reject_too_long();
  /// finish() and end_message(): `complete` tells whether an unterminated last line is
  /// whole (a datagram's) or cut by the end of a stream.
  void end(bool complete, const ReportSink& sink);

  std::size_t max_line_bytes_;
  std::string partial_;          // the start of a line whose '\n' has not arrived yet
  bool skipping_ = false;        // inside a line already counted as too long
  std::uint64_t line_number_ = 1;  // 1-based number of the line being read
};

}  // namespace kew::protocol::text
