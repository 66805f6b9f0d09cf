#pragma once
// The parse loop shared by the byte-stream framings (raw blocks, final format, pcap):
// each framing judges the message starting at a position, the loop accepts it, skips one
// byte of garbage (counting one resynchronisation per run of garbage), waits for more
// bytes, or reports a truncated tail at the end of the stream.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

#include "block_decoder.hpp"
#include "kew/protocol/decoder.hpp"
#include "stream_buffer.hpp"

namespace kew::protocol::asterix {

class FramedStreamDecoder : public Decoder {
 public:
  void feed(std::span<const std::byte> bytes, const ReportSink& sink) final;
  void finish(const ReportSink& sink) final;
  /// Pcap's own capture times, set per packet, take precedence over this.
  void set_receive_time(std::optional<double> utc_s) final { blocks_.set_capture_time(utc_s); }

 protected:
  /// `resync_reason`: the rejection counted once per run of skipped garbage bytes.
  FramedStreamDecoder(const AsterixOptions& options, std::string_view resync_reason);

  enum class Verdict {
    Accept,     ///< A message of `length` bytes starts here.
    Discard,    ///< `length` bytes are to be dropped silently (already counted).
    Garbage,    ///< No plausible message starts here: skip one byte.
    Wait,       ///< Undecidable until more bytes arrive.
    Truncated,  ///< At the end of the stream: the rest is a partial message.
  };
  struct Judgement {
    Verdict verdict;
    std::size_t length = 0;
  };

  /// Judges the bytes at the start of `rest` (everything after the current position);
  /// `at_end`: no more bytes will come.
  virtual Judgement judge(std::span<const std::uint8_t> rest, bool at_end) = 0;
  /// Handles an accepted message.
  virtual void accept(std::span<const std::uint8_t> message, const ReportSink& sink) = 0;
  /// Back to the state of a new stream (after finish()).
  virtual void restart() {}

  /// Inside a run of garbage: framings then ask for stronger evidence before accepting.
  bool skipping() const { return skipping_; }
  /// True until a message has been accepted since the start or since garbage.
  bool unconfirmed() const { return unconfirmed_; }
  /// Called from accept(): the message just accepted is not evidence that the stream is
  /// in step (its contents could not be checked), so the next one is judged as after garbage.
  void distrust() { unconfirmed_ = true; }

  BlockDecoder blocks_;

 private:
  std::size_t parse(std::span<const std::uint8_t> bytes, bool at_end, const ReportSink& sink);

  std::string_view resync_reason_;
  StreamBuffer buffer_;
  bool skipping_ = false;
  bool unconfirmed_ = true;
};

}  // namespace kew::protocol::asterix
