#include "framed_stream.hpp"

#include "bytes.hpp"

namespace kew::protocol::asterix {

FramedStreamDecoder::FramedStreamDecoder(const AsterixOptions& options, std::string_view resync_reason)
    : blocks_(options, rejections()), resync_reason_(resync_reason) {}

void FramedStreamDecoder::feed(std::span<const std::byte> bytes, const ReportSink& sink) {
  buffer_.feed(std::span<const std::uint8_t>(as_uint8(bytes), bytes.size()),
               [&](std::span<const std::uint8_t> data, bool at_end) { return parse(data, at_end, sink); });
}

void FramedStreamDecoder::finish(const ReportSink& sink) {
  buffer_.finish([&](std::span<const std::uint8_t> data, bool at_end) { return parse(data, at_end, sink); });
  skipping_ = false;
  unconfirmed_ = true;
  restart();
}

std::size_t FramedStreamDecoder::parse(std::span<const std::uint8_t> bytes, bool at_end,
                                       const ReportSink& sink) {
  std::size_t position = 0;
  while (position < bytes.size()) {
    const auto rest = bytes.subspan(position);
    const Judgement judgement = judge(rest, at_end);
    switch (judgement.verdict) {
      case Verdict::Accept:
        skipping_ = false;
        unconfirmed_ = false;
        accept(rest.first(judgement.length), sink);
        position += judgement.length;
        break;
      case Verdict::Discard:
        position += judgement.length;
        break;
      case Verdict::Garbage:
        if (!skipping_) rejections().reject(resync_reason_, "garbage in the stream; resynchronising");
        skipping_ = true;
        unconfirmed_ = true;
        ++position;
        break;
      case Verdict::Wait:
        return position;
      case Verdict::Truncated:
        rejections().reject("asterix_truncated", "stream ends inside a message");
        return bytes.size();
    }
  }
  return position;
}

}  // namespace kew::protocol::asterix
