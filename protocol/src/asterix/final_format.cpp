// EUROCONTROL final format (".ff", the recording format of EUROCONTROL's analysis tools):
// per frame a 16-bit frame length (the whole frame, header and trailer included), board
// number, line number, recording day, a 24-bit time, then the data block(s), then the
// padding A5 A5 A5 A5. The header time is the recorder's and does not match the ASTERIX
// time of day in the recordings we have (MANIFEST: hours off), so it is ignored.
// A frame is self-checking: its length must land on the A5A5A5A5 trailer and its payload
// must be a chain of plausible data blocks ending exactly before the trailer; otherwise
// one byte is skipped ("asterix_resync", once per run) and the next candidate tried.

#include <algorithm>
#include <array>

#include "bytes.hpp"
#include "framed_stream.hpp"
#include "framings.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr std::size_t kFrameHeaderBytes = 8;
constexpr std::array<std::uint8_t, 4> kTrailer{0xA5, 0xA5, 0xA5, 0xA5};
/// Header, one minimal block (3-byte header and a 1-byte record) and the trailer.
constexpr std::size_t kMinFrameBytes = kFrameHeaderBytes + 4 + kTrailer.size();

bool has_trailer(std::span<const std::uint8_t> frame) {
  return std::equal(kTrailer.begin(), kTrailer.end(), frame.end() - static_cast<std::ptrdiff_t>(kTrailer.size()));
}

std::span<const std::uint8_t> frame_payload(std::span<const std::uint8_t> frame) {
  return frame.subspan(kFrameHeaderBytes, frame.size() - kFrameHeaderBytes - kTrailer.size());
}

/// True when `payload` is a chain of plausible data block headers ending exactly at its
/// end: with the trailer, the evidence that a frame found after garbage is real (a length
/// read from garbage can land on the trailer of a later frame; it then spans several
/// frames, and its payload does not chain).
bool payload_chains(std::span<const std::uint8_t> payload) {
  std::size_t offset = 0;
  while (offset < payload.size()) {
    if (payload.size() - offset < 3) return false;
    const std::size_t length = be16(payload.data() + offset + 1);
    if (!plausible_block_header(payload[offset], length)) return false;
    offset += length;
  }
  return offset == payload.size();
}

class FinalFormatDecoder final : public FramedStreamDecoder {
 public:
  explicit FinalFormatDecoder(const AsterixOptions& options)
      : FramedStreamDecoder(options, "asterix_resync") {}

  std::string_view format_name() const override { return "asterix-ff"; }
  std::size_t max_message_bytes() const override { return kMaxBlockBytes; }

 private:
  Judgement judge(std::span<const std::uint8_t> rest, bool at_end) override {
    // Cut short by the end of the stream: truncated when in step, else (a length read from
    // garbage) one more byte of garbage.
    const Judgement incomplete{at_end ? (unconfirmed() ? Verdict::Garbage : Verdict::Truncated)
                                      : Verdict::Wait};
    if (rest.size() < 2) return incomplete;
    const std::size_t length = be16(rest.data());
    if (length < kMinFrameBytes) return {Verdict::Garbage};
    if (rest.size() < length) return incomplete;
    const auto frame = rest.first(length);
    if (!has_trailer(frame) || !payload_chains(frame_payload(frame))) return {Verdict::Garbage};
    return {Verdict::Accept, length};
  }

  void accept(std::span<const std::uint8_t> frame, const ReportSink& sink) override {
    const auto payload = frame_payload(frame);
    blocks_.decode_blocks(payload.data(), payload.size(), sink);
  }
};

}  // namespace

std::unique_ptr<Decoder> make_final_format_decoder(const AsterixOptions& options) {
  return std::make_unique<FinalFormatDecoder>(options);
}

double final_format_confidence(std::span<const std::uint8_t> head) {
  std::size_t offset = 0;
  int frames = 0;
  while (offset + 2 <= head.size()) {
    const std::size_t length = be16(head.data() + offset);
    if (length < kMinFrameBytes) break;
    if (offset + length > head.size()) {
      // Cut by the end of head: a plausible block header right after the frame header is
      // weaker evidence than a trailer.
      const std::size_t block = offset + kFrameHeaderBytes;
      if (frames == 0 && block + 3 <= head.size() &&
          plausible_block_header(head[block], be16(head.data() + block + 1))) {
        return 0.3;
      }
      break;
    }
    const auto frame = head.subspan(offset, length);
    if (!has_trailer(frame)) break;
    if (!payload_chains(frame_payload(frame))) break;
    ++frames;
    offset += length;
  }
  if (frames == 0) return 0.0;
  return frames == 1 ? 0.8 : 0.95;
}

}  // namespace kew::protocol::asterix
