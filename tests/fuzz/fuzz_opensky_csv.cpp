// libFuzzer target: any bytes as an OpenSky state-vector CSV stream (protocol/include/kew/protocol/opensky.hpp).
#include "fuzz_text_support.hpp"
#include "kew/protocol/opensky.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    return kew::protocol::make_opensky_csv_decoder({.max_line_bytes = 512});
  });
  return 0;
}
