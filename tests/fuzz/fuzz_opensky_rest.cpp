// libFuzzer target: any bytes as OpenSky REST API responses (protocol/include/kew/protocol/opensky_rest.hpp).
#include "fuzz_text_support.hpp"
#include "kew/protocol/opensky_rest.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A small response limit makes the over-long resynchronisation path common.
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    return kew::protocol::make_opensky_rest_decoder({.max_snapshot_bytes = 2000, .max_position_age_s = 10.0});
  });
  return 0;
}
