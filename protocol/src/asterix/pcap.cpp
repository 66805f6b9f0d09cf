// Classic libpcap capture files (not pcapng), parsed here rather than through libpcap so
// that the decoder stays incremental and has no system dependency. Both byte orders,
// microsecond (A1B2C3D4) and nanosecond (A1B23C4D) timestamps; link types Ethernet
// (with 802.1Q/802.1ad tags), raw IP, IPv4, Linux cooked v1/v2 and BSD loopback.
// Every IPv4 UDP payload is decoded as ASTERIX data blocks, whatever the port; IPv4
// fragments are counted and skipped (not reassembled).

#include <optional>

#include "bytes.hpp"
#include "framed_stream.hpp"
#include "framings.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr std::size_t kGlobalHeaderBytes = 24;
constexpr std::size_t kRecordHeaderBytes = 16;
/// Largest captured packet accepted (the snapshot length tcpdump uses by default).
constexpr std::uint32_t kMaxPacketBytes = 262144;
constexpr std::uint32_t kEtherTypeIpv4 = 0x0800;

enum class LinkType : std::uint32_t {
  Null = 0,
  Ethernet = 1,
  Raw = 101,
  LinuxCooked = 113,
  Ipv4 = 228,
  LinuxCooked2 = 276,
};

bool supported_link_type(std::uint32_t link_type) {
  switch (static_cast<LinkType>(link_type)) {
    case LinkType::Null:
    case LinkType::Ethernet:
    case LinkType::Raw:
    case LinkType::LinuxCooked:
    case LinkType::Ipv4:
    case LinkType::LinuxCooked2:
      return true;
  }
  return false;
}

struct FileFormat {
  bool big_endian = false;
  bool nanoseconds = false;
};

std::optional<FileFormat> read_magic(const std::uint8_t* header) {
  switch (le32(header)) {
    case 0xA1B2C3D4: return FileFormat{false, false};
    case 0xD4C3B2A1: return FileFormat{true, false};
    case 0xA1B23C4D: return FileFormat{false, true};
    case 0x4D3CB2A1: return FileFormat{true, true};
    default: return std::nullopt;
  }
}

class PcapDecoder final : public FramedStreamDecoder {
 public:
  explicit PcapDecoder(const AsterixOptions& options)
      : FramedStreamDecoder(options, "pcap_resync"), day_from_pcap_(options.day_from_pcap) {}

  std::string_view format_name() const override { return "asterix-pcap"; }
  std::size_t max_message_bytes() const override { return kMaxPacketBytes; }

 private:
  enum class State { GlobalHeader, Records, Unusable };

  struct RecordHeader {
    std::uint32_t seconds, fraction, captured, original;
  };

  std::uint32_t u32(const std::uint8_t* p) const { return format_.big_endian ? be32(p) : le32(p); }

  RecordHeader read_record_header(const std::uint8_t* p) const {
    return {u32(p), u32(p + 4), u32(p + 8), u32(p + 12)};
  }

  bool plausible(const RecordHeader& header) const {
    const std::uint32_t fraction_limit = format_.nanoseconds ? 1000000000U : 1000000U;
    if (header.captured > kMaxPacketBytes || header.original > kMaxPacketBytes ||
        header.captured > header.original || header.fraction >= fraction_limit) {
      return false;
    }
    // After garbage, also require a timestamp within a day of the last good packet.
    if (skipping() && last_seconds_) {
      const std::int64_t gap = std::int64_t{header.seconds} - std::int64_t{*last_seconds_};
      if (gap > 86400 || gap < -86400) return false;
    }
    return true;
  }

  Judgement judge_global_header(std::span<const std::uint8_t> rest, bool at_end) {
    if (rest.size() < kGlobalHeaderBytes) return {at_end ? Verdict::Truncated : Verdict::Wait};
    const auto format = read_magic(rest.data());
    if (!format) {
      rejections().reject("pcap_bad_header", "not a classic pcap file (magic number)");
      state_ = State::Unusable;
      return {Verdict::Discard, rest.size()};
    }
    format_ = *format;
    link_type_ = u32(rest.data() + 20) & 0xFFFF;
    if (!supported_link_type(link_type_)) {
      rejections().reject("pcap_unsupported_linktype", "pcap link type not supported");
      state_ = State::Unusable;
      return {Verdict::Discard, rest.size()};
    }
    state_ = State::Records;
    return {Verdict::Discard, kGlobalHeaderBytes};
  }

  Judgement judge(std::span<const std::uint8_t> rest, bool at_end) override {
    if (state_ == State::GlobalHeader) return judge_global_header(rest, at_end);
    if (state_ == State::Unusable) return {Verdict::Discard, rest.size()};
    const Judgement incomplete{at_end ? (skipping() ? Verdict::Garbage : Verdict::Truncated)
                                      : Verdict::Wait};
    if (rest.size() < kRecordHeaderBytes) return incomplete;
    const RecordHeader header = read_record_header(rest.data());
    if (!plausible(header)) return {Verdict::Garbage};
    const std::size_t length = kRecordHeaderBytes + header.captured;
    if (rest.size() < length) return incomplete;
    if (skipping()) {
      // After garbage, the record must be followed by another plausible record header
      // (or end the stream).
      if (rest.size() < length + kRecordHeaderBytes) {
        if (!at_end) return {Verdict::Wait};
      } else if (!plausible(read_record_header(rest.data() + length))) {
        return {Verdict::Garbage};
      }
    }
    return {Verdict::Accept, length};
  }

  void accept(std::span<const std::uint8_t> record, const ReportSink& sink) override {
    const RecordHeader header = read_record_header(record.data());
    last_seconds_ = header.seconds;
    const double capture_s =
        header.seconds + header.fraction * (format_.nanoseconds ? 1e-9 : 1e-6);
    const auto payload = udp_payload(record.subspan(kRecordHeaderBytes));
    if (!payload) return;
    blocks_.set_capture_time(day_from_pcap_ ? std::optional<double>(capture_s) : std::nullopt);
    blocks_.decode_blocks(payload->data(), payload->size(), sink);
  }

  /// The network-layer bytes of a captured frame and their EtherType.
  std::optional<std::pair<std::span<const std::uint8_t>, std::uint32_t>> network_layer(
      std::span<const std::uint8_t> frame) {
    std::size_t offset = 0;
    std::uint32_t ether_type = 0;
    switch (static_cast<LinkType>(link_type_)) {
      case LinkType::Ethernet:
        if (frame.size() < 14) return std::nullopt;
        ether_type = be16(frame.data() + 12);
        offset = 14;
        while (ether_type == 0x8100 || ether_type == 0x88A8) {  // VLAN tags
          if (frame.size() < offset + 4) return std::nullopt;
          ether_type = be16(frame.data() + offset + 2);
          offset += 4;
        }
        break;
      case LinkType::LinuxCooked:
        if (frame.size() < 16) return std::nullopt;
        ether_type = be16(frame.data() + 14);
        offset = 16;
        break;
      case LinkType::LinuxCooked2:
        if (frame.size() < 20) return std::nullopt;
        ether_type = be16(frame.data());
        offset = 20;
        break;
      case LinkType::Null: {
        if (frame.size() < 4) return std::nullopt;
        // The address family is in the capturing host's byte order; AF_INET is 2 everywhere.
        const bool inet = le32(frame.data()) == 2 || be32(frame.data()) == 2;
        ether_type = inet ? kEtherTypeIpv4 : 0;
        offset = 4;
        break;
      }
      case LinkType::Raw:
      case LinkType::Ipv4:
        if (frame.empty()) return std::nullopt;
        ether_type = (frame[0] >> 4) == 4 ? kEtherTypeIpv4 : 0;
        break;
    }
    return std::make_pair(frame.subspan(offset), ether_type);
  }

  std::optional<std::span<const std::uint8_t>> udp_payload(std::span<const std::uint8_t> frame) {
    const auto network = network_layer(frame);
    if (!network) {
      rejections().reject("pcap_truncated_packet", "captured frame shorter than its link header");
      return std::nullopt;
    }
    const auto [ip, ether_type] = *network;
    if (ether_type != kEtherTypeIpv4 || ip.empty() || (ip[0] >> 4) != 4) {
      rejections().reject("pcap_not_ipv4", "packet is not IPv4");
      return std::nullopt;
    }
    const std::size_t header_bytes = std::size_t{ip[0] & 0x0FU} * 4;
    if (header_bytes < 20 || ip.size() < header_bytes) {
      rejections().reject("pcap_truncated_packet", "IPv4 header truncated or malformed");
      return std::nullopt;
    }
    const std::size_t total = be16(ip.data() + 2);
    const std::uint32_t fragment = be16(ip.data() + 6);
    if ((fragment & 0x3FFF) != 0) {  // more-fragments flag or a fragment offset
      rejections().reject("pcap_ip_fragment", "IPv4 fragment (not reassembled)");
      return std::nullopt;
    }
    if (ip[9] != 17) {
      rejections().reject("pcap_not_udp", "IPv4 packet is not UDP");
      return std::nullopt;
    }
    if (total < header_bytes + 8 || total > ip.size()) {
      rejections().reject("pcap_truncated_packet", "IPv4 packet truncated or malformed");
      return std::nullopt;
    }
    const auto udp = ip.subspan(header_bytes, total - header_bytes);
    const std::size_t udp_length = be16(udp.data() + 4);
    if (udp_length < 8 || udp_length > udp.size()) {
      rejections().reject("pcap_truncated_packet", "UDP length does not fit the IPv4 packet");
      return std::nullopt;
    }
    return udp.subspan(8, udp_length - 8);
  }

  void restart() override {
    state_ = State::GlobalHeader;
    last_seconds_.reset();
  }

  bool day_from_pcap_;
  State state_ = State::GlobalHeader;
  FileFormat format_;
  std::uint32_t link_type_ = 0;
  std::optional<std::uint32_t> last_seconds_;
};

}  // namespace

std::unique_ptr<Decoder> make_pcap_decoder(const AsterixOptions& options) {
  return std::make_unique<PcapDecoder>(options);
}

double pcap_confidence(std::span<const std::uint8_t> head) {
  if (head.size() < 4) return 0.0;
  const auto format = read_magic(head.data());
  if (!format) return 0.0;
  if (head.size() < kGlobalHeaderBytes) return 0.9;
  const std::uint32_t link = (format->big_endian ? be32(head.data() + 20) : le32(head.data() + 20)) & 0xFFFF;
  return supported_link_type(link) ? 0.99 : 0.5;
}

}  // namespace kew::protocol::asterix
