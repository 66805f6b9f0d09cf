// libFuzzer target: any bytes as one CAT004 datagram. The reader must count what it
// refuses and never crash, read out of bounds or throw. Every record it accepts must
// survive a second read of a datagram re-encoded by kew's encoder from the figures the
// reader found (the encoder's own invariants are exercised on hostile values).
//
//   clang++ -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined \
//     -Icore/include -Iprotocol/include tests/fuzz/fuzz_cat004_reader.cpp \
//     protocol/src/encoders/cat004.cpp protocol/src/encoders/cat004_reader.cpp \
//     protocol/src/asterix/record_walker.cpp protocol/src/asterix/record_fields.cpp \
//     protocol/src/asterix/day_clock.cpp core/src/util/rejections.cpp -o fuzz_cat004_reader
// (or link kew_protocol and kew_core built with the same sanitizers).

#include <cstddef>
#include <cstdint>
#include <span>

#include "kew/protocol/encoders/cat004.hpp"
#include "kew/protocol/encoders/cat004_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kew::protocol;
  Cat004Reader reader;
  Cat004Encoder encoder(Cat004Options{});
  const auto bytes = std::as_bytes(std::span<const std::uint8_t>(data, size));
  reader.read(bytes, [&](const Cat004Record& record) {
    kew::AlertEvent event;
    event.t = record.time_of_day_s.value_or(0.0);
    event.number = record.alert_id.value_or(0);
    event.a.track_number = record.track_number_1.value_or(0);
    event.b.track_number = record.track_number_2.value_or(0);
    if (record.aircraft_1 && record.aircraft_1->identifier) {
      event.a.callsign = *record.aircraft_1->identifier;
    }
    event.t_los_s = record.time_to_conflict_s.value_or(-1.0);
    event.cpa_h_m = record.minimum_horizontal_separation_m.value_or(1e300);
    encoder.add_alert(event);
  });
  Cat004Reader again;
  std::size_t records = 0;
  for (const auto& datagram : encoder.take_datagrams()) {
    again.read(datagram, [&](const Cat004Record&) { ++records; });
  }
  if (again.rejections().total() != 0) __builtin_trap();  // kew's own output must read
  (void)records;
  return 0;
}
