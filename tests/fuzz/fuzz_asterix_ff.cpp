// libFuzzer target: any bytes as an EUROCONTROL final-format (.ff) file of ASTERIX blocks.
// Chunked and whole decoding must agree; every report must be valid.
#include "fuzz_text_support.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    kew::protocol::AsterixOptions options;
    options.radars = {{52, 156, 51.5, -0.5, 60.0}};
    return kew::protocol::make_asterix_decoder(kew::protocol::AsterixFraming::FinalFormat, options);
  });
  return 0;
}
