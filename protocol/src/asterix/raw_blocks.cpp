// Raw concatenated data blocks. Resynchronisation heuristic (protocol/docs/asterix.md):
// a block header is plausible when its category is assigned by EUROCONTROL and its
// length is at least 4. While unconfirmed (at the start of the stream and after garbage)
// a plausible block is accepted only when the bytes right after it form another plausible
// header, or when the stream ends exactly there; otherwise one byte is skipped. Once a
// block is accepted the following ones are trusted, so a live stream is decoded without
// waiting for the next block.

#include "bytes.hpp"
#include "framed_stream.hpp"
#include "framings.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr std::size_t kHeaderBytes = 3;

class RawBlocksDecoder final : public FramedStreamDecoder {
 public:
  explicit RawBlocksDecoder(const AsterixOptions& options)
      : FramedStreamDecoder(options, "asterix_resync") {}

  std::string_view format_name() const override { return "asterix-raw"; }
  std::size_t max_message_bytes() const override { return kMaxBlockBytes; }

 private:
  Judgement judge(std::span<const std::uint8_t> rest, bool at_end) override {
    const Judgement incomplete{at_end ? (skipping() ? Verdict::Garbage : Verdict::Truncated)
                                      : Verdict::Wait};
    if (rest.size() < kHeaderBytes) return incomplete;
    const std::size_t length = be16(rest.data() + 1);
    if (!plausible_block_header(rest[0], length)) return {Verdict::Garbage};
    if (rest.size() < length) return incomplete;
    if (unconfirmed()) {
      if (rest.size() < length + kHeaderBytes) {
        // The next header is not visible yet: wait, unless the stream ends here (exactly,
        // or with a tail too short to be a header, reported as truncated next).
        if (!at_end) return {Verdict::Wait};
      } else if (!plausible_block_header(rest[length], be16(rest.data() + length + 1))) {
        return {Verdict::Garbage};
      }
    }
    return {Verdict::Accept, length};
  }

  void accept(std::span<const std::uint8_t> block, const ReportSink& sink) override {
    blocks_.decode_block(block.data(), block.size(), sink);
  }
};

}  // namespace

bool plausible_block_header(std::uint8_t category, std::size_t length) {
  return is_assigned_category(category) && length >= kHeaderBytes + 1;
}

std::unique_ptr<Decoder> make_raw_blocks_decoder(const AsterixOptions& options) {
  return std::make_unique<RawBlocksDecoder>(options);
}

double raw_blocks_confidence(std::span<const std::uint8_t> head) {
  // Count consecutive plausible blocks from the first byte; a block cut by the end of
  // `head` counts when its header is plausible.
  std::size_t offset = 0;
  int blocks = 0;
  bool decoded_category = false;
  while (offset + kHeaderBytes <= head.size()) {
    const std::size_t length = be16(head.data() + offset + 1);
    if (!plausible_block_header(head[offset], length)) return blocks == 0 ? 0.0 : 0.2;
    decoded_category = decoded_category || is_decoded_category(head[offset]);
    ++blocks;
    offset += length;
  }
  if (blocks == 0) return 0.0;
  const double base = blocks == 1 ? 0.4 : blocks == 2 ? 0.7 : 0.85;
  return decoded_category ? base + 0.05 : base;
}

}  // namespace kew::protocol::asterix
