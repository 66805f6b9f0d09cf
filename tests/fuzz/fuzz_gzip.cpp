// libFuzzer target: any bytes as a gzip stream in front of the NDJSON decoder
// (protocol/include/kew/protocol/gzip.hpp). Seeds should be gzip files: mutations of
// valid members reach deep into inflate and member concatenation.
#include "fuzz_text_support.hpp"
#include "kew/protocol/gzip.hpp"
#include "kew/protocol/ndjson.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kew::protocol;
  // The control byte that sets the chunk count also picks the mode.
  const GzipMode mode = size > 0 && (data[0] & 0x80) != 0 ? GzipMode::Always : GzipMode::WhenMagic;
  fuzz::fuzz_decoder(data, size, [mode] { return make_gzip_decoder(make_ndjson_decoder(), mode); });
  if (size > 4) {
    const auto stream = std::as_bytes(std::span<const std::uint8_t>(data + 4, size - 4));
    const auto head = gunzip_prefix(stream, 1 + data[1] * 64u);
    if (head.size() > 1u + data[1] * 64u) __builtin_trap();
  }
  return 0;
}
