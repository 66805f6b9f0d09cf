// libFuzzer target: any bytes as a stream of raw ASTERIX data blocks
// (protocol/include/kew/protocol/asterix/asterix_decoder.hpp). The input is decoded in up
// to 4 chunks and whole; both must agree (fuzz_text_support.hpp: the Decoder contract is
// the same for binary framings), and every report must be valid.
#include "fuzz_text_support.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    // Two radars so that CAT048 plots are converted, not only rejected.
    kew::protocol::AsterixOptions options;
    options.radars = {{25, 201, 45.0, 16.0, 100.0}, {0, 1, 41.3, 2.1, 27.0}};
    options.day_start_utc_s = 1714348800;
    return kew::protocol::make_asterix_decoder(kew::protocol::AsterixFraming::RawBlocks, options);
  });
  return 0;
}
