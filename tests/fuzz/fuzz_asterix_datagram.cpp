// libFuzzer target: any bytes as live ASTERIX UDP datagrams. A datagram never straddles
// feed() calls, so chunking changes the meaning: instead, the first 4 bytes cut the rest
// into up to 4 datagrams (one feed() each), decoded by two fresh decoders and once more by
// the first after its finish(); all three must agree, and every report must be valid.
#include "fuzz_text_support.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"

namespace {

std::unique_ptr<kew::protocol::Decoder> make() {
  kew::protocol::AsterixOptions options;
  options.radars = {{25, 201, 45.0, 16.0, 100.0}, {0, 1, 41.3, 2.1, 27.0}};
  return kew::protocol::make_asterix_decoder(kew::protocol::AsterixFraming::Datagram, options);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using kew::protocol::fuzz::decode;
  constexpr std::size_t kControl = 4;
  if (size < kControl) return 0;
  const auto stream = std::as_bytes(std::span<const std::uint8_t>(data + kControl, size - kControl));
  std::vector<std::size_t> datagram_ends;
  for (std::size_t i = 0; i < data[0] % 4; ++i) {
    datagram_ends.push_back((static_cast<std::size_t>(data[1 + i]) * 257U) % (stream.size() + 1));
  }
  std::sort(datagram_ends.begin(), datagram_ends.end());
  const auto first = make();
  const auto a = decode(*first, stream, datagram_ends);
  const auto second = make();
  const auto b = decode(*second, stream, datagram_ends);
  const auto again = decode(*first, stream, datagram_ends);
  const bool same_checksum = a.checksum == b.checksum || (std::isnan(a.checksum) && std::isnan(b.checksum));
  if (a.reports != b.reports || a.reports != again.reports || !same_checksum || a.rejections != b.rejections) {
    __builtin_trap();
  }
  return 0;
}
