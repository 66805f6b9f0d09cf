// libFuzzer target: any bytes as readsb JSON lines (protocol/include/kew/protocol/readsb.hpp).
#include "fuzz_text_support.hpp"
#include "kew/protocol/readsb.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    return kew::protocol::make_readsb_decoder({.max_line_bytes = 700});
  });
  return 0;
}
