// libFuzzer target: any bytes as an SBS-1 BaseStation stream (protocol/include/kew/protocol/sbs.hpp).
#include "fuzz_text_support.hpp"
#include "kew/protocol/sbs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // A tiny address table exercises eviction and the table-full path.
  kew::protocol::fuzz::fuzz_decoder(data, size, [] {
    return kew::protocol::make_sbs_decoder(
        {.utc_offset_s = 3600, .max_line_bytes = 256, .max_addresses = 4, .address_stale_after_s = 5});
  });
  return 0;
}
