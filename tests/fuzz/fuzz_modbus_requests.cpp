// libFuzzer target: any bytes as a Modbus TCP client's stream to kewd. The first byte
// picks the map shape (table rows, read-only); the rest is fed to the MBAP framer in
// three chunks, and every complete ADU's PDU is judged against the map. Framing and
// judging must never crash or read out of bounds; every verdict must be consistent: an
// accepted request is a read inside the map or a write of coil 0; a refusal names its
// reason.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "kew/protocol/modbus_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace kew::protocol;
  if (size < 1) return 0;
  const int table_entries = data[0] % 65;
  ModbusMapShape shape;
  shape.registers = modbus_register_count(table_entries);
  shape.read_only = (data[0] & 0x80) != 0;
  const std::span<const std::uint8_t> stream(data + 1, size - 1);

  kew::Rejections rejections;
  MbapFramer framer;
  const std::size_t cut1 = stream.size() / 3, cut2 = 2 * stream.size() / 3;
  const auto judge = [&](std::span<const std::uint8_t> adu) {
    if (adu.size() < MbapFramer::kHeaderBytes || adu.size() > MbapFramer::kMaxAduBytes) std::abort();
    const ModbusVerdict v = check_modbus_request(adu.subspan(MbapFramer::kHeaderBytes), shape);
    const bool accepted = v.exception == ModbusException::None && !v.drop_connection;
    if (!accepted && v.reason.empty()) std::abort();
    if (v.acknowledge && (!accepted || shape.read_only)) std::abort();
  };
  for (const auto& chunk : {stream.subspan(0, cut1), stream.subspan(cut1, cut2 - cut1), stream.subspan(cut2)}) {
    if (!framer.feed(chunk, rejections, judge)) break;
  }
  if (framer.pending_bytes() > MbapFramer::kMaxAduBytes) std::abort();
  return 0;
}
