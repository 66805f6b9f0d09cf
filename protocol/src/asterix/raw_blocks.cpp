// Raw concatenated data blocks. Resynchronisation heuristic (protocol/docs/asterix.md):
// a block header is plausible when its category is assigned by EUROCONTROL and its length
// is at least 4. A block of a category kew decodes (021, 048, 062: "checked") must also
// split exactly into records that walk under its UAP, each with FRN 1 (I0xx/010).
//  - A checked block is accepted at once when the stream is in step (the previous block
//    was checked), so a live stream is decoded without waiting for the next block; while
//    unconfirmed (at the start, after garbage, after an unchecked block) a plausible
//    header must follow it (or the stream end there).
//  - An unchecked block (other categories, skipped whole) needs a chain of plausible
//    headers after it that reaches a checked block that walks cleanly, or exactly the end
//    of the stream, within kMaxChainBlocks blocks and kMaxLookAheadBytes bytes. Inside a
//    run of garbage it is not accepted at all: the run ends at the next checked block.
//    Garbage is full of bytes that look like category numbers and real blocks are dense,
//    so a chain from a false header too often lands on a real block; only the record walk
//    of a checked block is strong evidence. This costs no reports: unchecked blocks give
//    none (those right after garbage are counted in the run, not as ignored blocks).
// Anything else: one byte is skipped ("asterix_resync", once per run) and the next
// position tried.

#include "bytes.hpp"
#include "framed_stream.hpp"
#include "framings.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr std::size_t kHeaderBytes = 3;
/// Look-ahead limits of the chain test for unchecked blocks while unconfirmed: the buffer
/// then holds at most kMaxLookAheadBytes plus one block.
constexpr int kMaxChainBlocks = 8;
constexpr std::size_t kMaxLookAheadBytes = 4 * kMaxBlockBytes;

class RawBlocksDecoder final : public FramedStreamDecoder {
 public:
  explicit RawBlocksDecoder(const AsterixOptions& options)
      : FramedStreamDecoder(options, "asterix_resync") {}

  std::string_view format_name() const override { return "asterix-raw"; }
  std::size_t max_message_bytes() const override { return kMaxBlockBytes; }

 private:
  Judgement judge(std::span<const std::uint8_t> rest, bool at_end) override {
    // Cut short by the end of the stream: truncated when in step, else (a length read from
    // garbage) one more byte of garbage.
    const Judgement incomplete{at_end ? (unconfirmed() ? Verdict::Garbage : Verdict::Truncated)
                                      : Verdict::Wait};
    if (rest.size() < kHeaderBytes) return incomplete;
    const std::size_t length = be16(rest.data() + 1);
    if (!plausible_block_header(rest[0], length)) return {Verdict::Garbage};
    if (rest.size() < length) return incomplete;
    Verdict verdict = Verdict::Accept;
    if (is_decoded_category(rest[0])) {
      if (!blocks_.walks_cleanly(rest.data(), length)) return {Verdict::Garbage};
      if (unconfirmed()) verdict = header_follows(rest, length, at_end);
    } else {
      // Inside a run of garbage only a checked block ends the run: real blocks are dense,
      // and a chain from a false header too often lands on one.
      if (skipping()) return {Verdict::Garbage};
      verdict = chain_reaches_checked_block(rest, length, at_end);
    }
    if (verdict != Verdict::Accept) return {verdict};
    return {Verdict::Accept, length};
  }

  /// Whether a plausible block header starts at `offset` (Accept), cannot be known yet
  /// (Wait), or not (Garbage). The end of the stream, or a tail too short for a header
  /// (reported as truncated next), counts as plausible.
  static Verdict header_follows(std::span<const std::uint8_t> rest, std::size_t offset, bool at_end) {
    if (rest.size() < offset + kHeaderBytes) return at_end ? Verdict::Accept : Verdict::Wait;
    return plausible_block_header(rest[offset], be16(rest.data() + offset + 1)) ? Verdict::Accept
                                                                               : Verdict::Garbage;
  }

  /// Whether the plausible headers chained from `offset` reach a checked block that walks
  /// cleanly, or exactly the end of the stream, within the look-ahead limits.
  Verdict chain_reaches_checked_block(std::span<const std::uint8_t> rest, std::size_t offset,
                                      bool at_end) {
    for (int hops = 0; hops < kMaxChainBlocks && offset <= kMaxLookAheadBytes; ++hops) {
      if (rest.size() < offset + kHeaderBytes) {
        if (!at_end) return Verdict::Wait;
        return offset == rest.size() ? Verdict::Accept : Verdict::Garbage;
      }
      const std::size_t length = be16(rest.data() + offset + 1);
      if (!plausible_block_header(rest[offset], length)) return Verdict::Garbage;
      if (is_decoded_category(rest[offset])) {
        if (rest.size() < offset + length) return at_end ? Verdict::Garbage : Verdict::Wait;
        return blocks_.walks_cleanly(rest.data() + offset, length) ? Verdict::Accept : Verdict::Garbage;
      }
      offset += length;
    }
    return Verdict::Garbage;
  }

  void accept(std::span<const std::uint8_t> block, const ReportSink& sink) override {
    if (!is_decoded_category(block[0])) distrust();
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
