// libFuzzer target: any bytes as a traffic-library OpenSky JSON array (protocol/include/kew/protocol/opensky.hpp).
#include "fuzz_text_support.hpp"
#include "kew/protocol/opensky.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A small element limit makes the over-long resynchronisation path common.
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    return kew::protocol::make_opensky_json_decoder({.max_object_bytes = 300});
  });
  return 0;
}
