// libFuzzer target: any bytes as a classic pcap capture of UDP datagrams carrying ASTERIX.
// Chunked and whole decoding must agree; every report must be valid.
#include "fuzz_text_support.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    kew::protocol::AsterixOptions options;
    for (const int sic : {11, 12, 13, 14, 201, 204, 205}) {
      options.radars.push_back({25, static_cast<std::uint8_t>(sic), 45.0, 16.0, 100.0});
    }
    return kew::protocol::make_asterix_decoder(kew::protocol::AsterixFraming::Pcap, options);
  });
  return 0;
}
