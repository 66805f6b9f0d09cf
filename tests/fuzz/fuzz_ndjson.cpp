// libFuzzer target: any bytes as a canonical NDJSON stream (protocol/include/kew/protocol/ndjson.hpp).
#include "fuzz_text_support.hpp"
#include "kew/protocol/ndjson.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A small line limit makes the over-long path as common as the normal one.
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    return kew::protocol::make_ndjson_decoder({.max_line_bytes = 256});
  });
  return 0;
}
