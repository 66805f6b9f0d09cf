#include "kew/protocol/asterix/asterix_decoder.hpp"

#include "block_decoder.hpp"
#include "bytes.hpp"
#include "framings.hpp"

namespace kew::protocol {

namespace {

/// Live UDP: each feed() is one datagram, decoded at once; nothing is buffered.
class DatagramDecoder final : public Decoder {
 public:
  explicit DatagramDecoder(const AsterixOptions& options) : blocks_(options, rejections()) {}

  void feed(std::span<const std::byte> bytes, const ReportSink& sink) override {
    blocks_.decode_blocks(asterix::as_uint8(bytes), bytes.size(), sink);
  }
  void finish(const ReportSink&) override {}
  void set_receive_time(std::optional<double> utc_s) override { blocks_.set_capture_time(utc_s); }
  std::string_view format_name() const override { return "asterix-datagram"; }
  std::size_t max_message_bytes() const override { return asterix::kMaxBlockBytes; }

 private:
  asterix::BlockDecoder blocks_;
};

}  // namespace

std::unique_ptr<Decoder> make_asterix_decoder(AsterixFraming framing, AsterixOptions options) {
  switch (framing) {
    case AsterixFraming::RawBlocks: return asterix::make_raw_blocks_decoder(options);
    case AsterixFraming::FinalFormat: return asterix::make_final_format_decoder(options);
    case AsterixFraming::Pcap: return asterix::make_pcap_decoder(options);
    case AsterixFraming::Datagram: return std::make_unique<DatagramDecoder>(options);
  }
  return nullptr;
}

double asterix_framing_confidence(AsterixFraming framing, std::span<const std::byte> head) {
  const std::span<const std::uint8_t> bytes(asterix::as_uint8(head), head.size());
  switch (framing) {
    case AsterixFraming::RawBlocks: return asterix::raw_blocks_confidence(bytes);
    case AsterixFraming::FinalFormat: return asterix::final_format_confidence(bytes);
    case AsterixFraming::Pcap: return asterix::pcap_confidence(bytes);
    case AsterixFraming::Datagram: return 0.5 * asterix::raw_blocks_confidence(bytes);
  }
  return 0.0;
}

}  // namespace kew::protocol
