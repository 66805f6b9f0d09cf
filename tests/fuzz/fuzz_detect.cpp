// libFuzzer target: format detection on any bytes, then the detected decoder and the
// auto-detecting decoder on the same bytes (protocol/include/kew/protocol/formats.hpp).
#include "fuzz_text_support.hpp"
#include "kew/protocol/formats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kew::protocol;
  // Detection sees the stream the decoders see: without fuzz_decoder's 4 control bytes.
  if (size < 4) return 0;
  const Format detected = detect_format(std::as_bytes(std::span<const std::uint8_t>(data + 4, size - 4)));
  if (kFormatNames.parse(to_string(detected)) != detected) __builtin_trap();
  DecoderOptions options;
  options.max_line_bytes = 512;
  if (detected != Format::AsterixDatagram) {
    fuzz::fuzz_decoder(data, size, [&] { return make_decoder(detected, options); });
  }
  fuzz::fuzz_decoder(data, size, [&] { return make_decoder(Format::Auto, options); });
  return 0;
}
