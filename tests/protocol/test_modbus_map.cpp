// The Modbus alarm register map (design §5.5) and the request rules of kew's server, as
// pure functions: every register of hand-built snapshots, ordering, saturation, and the
// exception chosen for each kind of bad request.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "kew/protocol/modbus_map.hpp"

namespace kew::protocol {
namespace {

AlertEvent alert(std::uint16_t number, Severity severity, double t_los_s, AlertState state = AlertState::New) {
  AlertEvent e;
  e.id = "id" + std::to_string(number);
  e.number = number;
  e.severity = severity;
  e.state = state;
  e.t_los_s = t_los_s;
  e.a.track_number = static_cast<std::uint16_t>(number * 10 + 1);
  e.b.track_number = static_cast<std::uint16_t>(number * 10 + 2);
  e.cpa_h_m = 1234.0;
  e.cpa_v_ft = 450.0;
  return e;
}

std::vector<std::uint16_t> row(const RegisterMap& map, std::size_t index) {
  const auto begin = map.input_registers.begin() +
                     static_cast<std::ptrdiff_t>(kRegTableStart + index * kModbusTableRowWidth);
  return {begin, begin + static_cast<std::ptrdiff_t>(kModbusTableRowWidth)};
}

TEST(ModbusMap, EmptySnapshotHasVersionAndZeros) {
  const RegisterMap map = build_register_map(AlarmSnapshot{}, 2, 0);
  ASSERT_EQ(map.discrete_inputs.size(), 8u);
  EXPECT_EQ(map.discrete_inputs, std::vector<std::uint8_t>(8, 0));
  ASSERT_EQ(map.input_registers.size(), 16u + 2 * 8);
  std::vector<std::uint16_t> expected(32, 0);
  expected[kRegMapVersion] = 1;
  expected[kRegSecondsSinceLastRecord] = 65535;  // default age 1e9 s: never
  EXPECT_EQ(map.input_registers, expected);
}

TEST(ModbusMap, EveryStatusRegisterAndInput) {
  AlarmSnapshot s;
  s.active = {alert(7, Severity::Warning, 42.4), alert(3, Severity::Caution, 100.0)};
  s.live_tracks = 321;
  s.seconds_since_last_record = 4.9;
  s.feed_healthy = true;
  s.degraded = true;
  s.uptime_s = 0x0001'86A1;  // 100001 s: the high word is 1
  s.unacknowledged = 2;
  const RegisterMap map = build_register_map(s, 1, 4242);

  EXPECT_EQ(map.discrete_inputs, (std::vector<std::uint8_t>{1, 1, 1, 0, 1, 1, 0, 0}));
  const std::vector<std::uint16_t> expected_status = {1, 2, 2, 321, 4, 4242, 0x0001, 0x86A1,
                                                      2, 0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(std::vector<std::uint16_t>(map.input_registers.begin(), map.input_registers.begin() + 16),
            expected_status);
  // One row only: the warning (more severe than the caution).
  ASSERT_EQ(map.input_registers.size(), 24u);
  EXPECT_EQ(row(map, 0), (std::vector<std::uint16_t>{7, 2, 71, 72, 42, 123, 45, 1}));
}

TEST(ModbusMap, LossAloneSetsOnlyLossInput) {
  AlarmSnapshot s;
  s.active = {alert(1, Severity::Loss, 0.0, AlertState::Update)};
  const RegisterMap map = build_register_map(s, 4, 0);
  EXPECT_EQ(map.discrete_inputs, (std::vector<std::uint8_t>{1, 0, 0, 1, 0, 0, 0, 0}));
  EXPECT_EQ(map.input_registers[kRegHighestSeverity], 3);
  EXPECT_EQ(row(map, 0)[kColState], 2);
  EXPECT_EQ(row(map, 0)[kColTimeToLoss], 0);
}

TEST(ModbusMap, TableSortedBySeverityThenTimeToLossThenNumber) {
  AlarmSnapshot s;
  s.active = {alert(5, Severity::Caution, 30.0), alert(9, Severity::Warning, 50.0),
              alert(2, Severity::Warning, 20.0), alert(4, Severity::Warning, 20.0),
              alert(8, Severity::Loss, 0.0),     alert(6, Severity::Caution, std::nan(""))};
  const RegisterMap map = build_register_map(s, 6, 0);
  std::vector<std::uint16_t> numbers;
  for (std::size_t i = 0; i < 6; ++i) numbers.push_back(row(map, i)[kColAlertNumber]);
  EXPECT_EQ(numbers, (std::vector<std::uint16_t>{8, 2, 4, 9, 5, 6}));
  EXPECT_EQ(map.input_registers[kRegActiveAlerts], 6);
  EXPECT_EQ(map.input_registers[kRegHighestSeverity], 3);
}

TEST(ModbusMap, TableKeepsTheMostSevereWhenFull) {
  AlarmSnapshot s;
  s.active = {alert(1, Severity::Caution, 10.0), alert(2, Severity::Loss, 0.0),
              alert(3, Severity::Warning, 10.0)};
  const RegisterMap map = build_register_map(s, 2, 0);
  ASSERT_EQ(map.input_registers.size(), 32u);
  EXPECT_EQ(row(map, 0)[kColAlertNumber], 2);
  EXPECT_EQ(row(map, 1)[kColAlertNumber], 3);
  EXPECT_EQ(map.input_registers[kRegActiveAlerts], 3);  // the count is not cut by the table
}

TEST(ModbusMap, EmptyRowsAreAllZero) {
  AlarmSnapshot s;
  s.active = {alert(1, Severity::Caution, 10.0)};
  const RegisterMap map = build_register_map(s, 3, 0);
  EXPECT_NE(row(map, 0)[kColState], 0);
  EXPECT_EQ(row(map, 1), std::vector<std::uint16_t>(8, 0));
  EXPECT_EQ(row(map, 2), std::vector<std::uint16_t>(8, 0));
}

TEST(ModbusMap, EndedAlertsAreNotActive) {
  AlarmSnapshot s;
  s.active = {alert(1, Severity::Warning, 10.0, AlertState::End)};
  const RegisterMap map = build_register_map(s, 1, 0);
  EXPECT_EQ(map.discrete_inputs[kDiAnyAlert], 0);
  EXPECT_EQ(map.discrete_inputs[kDiWarning], 0);
  EXPECT_EQ(map.input_registers[kRegActiveAlerts], 0);
  EXPECT_EQ(map.input_registers[kRegHighestSeverity], 0);
  EXPECT_EQ(row(map, 0), std::vector<std::uint16_t>(8, 0));
}

AlertEvent apw(std::uint16_t number, Severity severity, double t_los_s) {
  AlertEvent e = alert(number, severity, t_los_s);
  e.kind = AlertKind::Apw;
  e.volume = "EDR205";
  e.volume_kind = "restricted";
  return e;
}

// An APW row sits among the STCA rows by urgency, has its kind bit set (register 9, bit
// r for row r) and reads 0 in track B and the CPA columns, even when the event holds
// something there.
TEST(ModbusMap, ApwRowsSayTheirKindAndHaveNoSecondAircraft) {
  AlarmSnapshot s;
  s.active = {alert(7, Severity::Warning, 42.4), apw(3, Severity::Loss, 0.0),
              apw(5, Severity::Caution, 90.0)};
  const RegisterMap map = build_register_map(s, 4, 0);
  ASSERT_EQ(map.input_registers.size(), 16u + 4 * 8);  // the row is not widened
  EXPECT_EQ(map.discrete_inputs, (std::vector<std::uint8_t>{1, 1, 1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(map.input_registers[kRegActiveAlerts], 3);
  EXPECT_EQ(map.input_registers[kRegHighestSeverity], 3);
  EXPECT_EQ(row(map, 0), (std::vector<std::uint16_t>{3, 3, 31, 0, 0, 0, 0, 1}));     // APW, inside
  EXPECT_EQ(row(map, 1), (std::vector<std::uint16_t>{7, 2, 71, 72, 42, 123, 45, 1}));  // STCA
  EXPECT_EQ(row(map, 2), (std::vector<std::uint16_t>{5, 1, 51, 0, 90, 0, 0, 1}));    // APW
  EXPECT_EQ(row(map, 3), std::vector<std::uint16_t>(8, 0));
  EXPECT_EQ(map.input_registers[kRegRowKinds], (kKindApw << 0) | (kKindApw << 2));
  for (std::size_t r = kRegRowKinds + 1; r < kRegTableStart; ++r) {
    EXPECT_EQ(map.input_registers[r], 0) << "register " << r;
  }
}

// 64 rows: four registers of 16 bits; a row the table cannot hold has no bit.
TEST(ModbusMap, RowKindsCoverEveryRow) {
  AlarmSnapshot s;
  for (std::uint16_t i = 0; i < 70; ++i) {
    // Distinct times to loss put alert i in row i.
    s.active.push_back(i % 3 == 0 ? apw(i, Severity::Caution, i) : alert(i, Severity::Caution, i));
  }
  std::vector<std::uint16_t> expected(kModbusRowKindRegisters, 0);
  for (std::size_t r = 0; r < 64; ++r) {
    if (r % 3 == 0) expected[r / 16] = static_cast<std::uint16_t>(expected[r / 16] | (1u << (r % 16)));
  }
  RegisterMap map = build_register_map(s, 64, 0);
  const auto kinds = [&map] {
    const auto first = map.input_registers.begin() + kRegRowKinds;
    return std::vector<std::uint16_t>(first, first + static_cast<std::ptrdiff_t>(kModbusRowKindRegisters));
  };
  EXPECT_EQ(kinds(), expected);
  EXPECT_EQ(expected[0], 0x9249);  // rows 0, 3, 6, 9, 12, 15
  for (std::size_t r = 0; r < 64; ++r) {
    const bool is_apw = (map.input_registers[kRegRowKinds + r / 16] >> (r % 16)) & 1u;
    EXPECT_EQ(row(map, r)[kColAlertNumber], r);
    EXPECT_EQ(is_apw, r % 3 == 0) << "row " << r;
    if (is_apw) {
      EXPECT_EQ(row(map, r)[kColTrackB], 0) << "row " << r;
    }
  }
  map = build_register_map(s, 8, 0);
  EXPECT_EQ(kinds(), (std::vector<std::uint16_t>{0x0049, 0, 0, 0}));  // rows 0, 3, 6
}

TEST(ModbusMap, FiguresRoundAndSaturate) {
  AlertEvent e = alert(1, Severity::Caution, 12.5);
  e.cpa_h_m = 14.99;  // 1.499 × 10 m → 1
  e.cpa_v_ft = 15.0;  // 1.5 × 10 ft → 2 (halves away from zero)
  AlarmSnapshot s;
  s.active = {e};
  EXPECT_EQ(row(build_register_map(s, 1, 0), 0),
            (std::vector<std::uint16_t>{1, 1, 11, 12, 13, 1, 2, 1}));

  s.active[0].t_los_s = 1e7;
  s.active[0].cpa_h_m = 1e9;
  s.active[0].cpa_v_ft = std::numeric_limits<double>::infinity();
  EXPECT_EQ(row(build_register_map(s, 1, 0), 0),
            (std::vector<std::uint16_t>{1, 1, 11, 12, 65535, 65535, 65535, 1}));

  s.active[0].t_los_s = -3.0;
  s.active[0].cpa_h_m = std::nan("");
  s.active[0].cpa_v_ft = -0.4;
  EXPECT_EQ(row(build_register_map(s, 1, 0), 0),
            (std::vector<std::uint16_t>{1, 1, 11, 12, 0, 65535, 0, 1}));
}

TEST(ModbusMap, CountsAndAgeSaturate) {
  AlarmSnapshot s;
  s.live_tracks = 70000;
  s.unacknowledged = 1'000'000;
  s.seconds_since_last_record = 65535.9;
  RegisterMap map = build_register_map(s, 0, 65535);
  EXPECT_EQ(map.input_registers[kRegLiveTracks], 65535);
  EXPECT_EQ(map.input_registers[kRegUnacknowledged], 65535);
  EXPECT_EQ(map.input_registers[kRegSecondsSinceLastRecord], 65535);
  EXPECT_EQ(map.input_registers[kRegHeartbeat], 65535);

  s.seconds_since_last_record = 65534.99;  // truncated, not rounded
  EXPECT_EQ(build_register_map(s, 0, 0).input_registers[kRegSecondsSinceLastRecord], 65534);
  s.seconds_since_last_record = -2.0;
  EXPECT_EQ(build_register_map(s, 0, 0).input_registers[kRegSecondsSinceLastRecord], 0);
  s.seconds_since_last_record = std::nan("");
  EXPECT_EQ(build_register_map(s, 0, 0).input_registers[kRegSecondsSinceLastRecord], 65535);
}

TEST(ModbusMap, UptimeIsHighWordFirst) {
  AlarmSnapshot s;
  s.uptime_s = 0xDEAD'BEEF;
  const RegisterMap map = build_register_map(s, 0, 0);
  EXPECT_EQ(map.input_registers[kRegUptimeHigh], 0xDEAD);
  EXPECT_EQ(map.input_registers[kRegUptimeLow], 0xBEEF);
}

TEST(ModbusMap, TableEntriesAreClamped) {
  EXPECT_EQ(modbus_register_count(-5), 16u);
  EXPECT_EQ(modbus_register_count(0), 16u);
  EXPECT_EQ(modbus_register_count(8), 80u);
  EXPECT_EQ(modbus_register_count(1000), 16u + 64 * 8);
  EXPECT_EQ(build_register_map(AlarmSnapshot{}, 1000, 0).input_registers.size(), 16u + 64 * 8);
}

// --- Requests ---------------------------------------------------------------------

ModbusMapShape shape(bool read_only = false) {
  ModbusMapShape s;
  s.registers = 32;
  s.read_only = read_only;
  return s;
}

std::vector<std::uint8_t> pdu(std::uint8_t function, std::uint16_t a, std::uint16_t b) {
  return {function, static_cast<std::uint8_t>(a >> 8), static_cast<std::uint8_t>(a & 0xFF),
          static_cast<std::uint8_t>(b >> 8), static_cast<std::uint8_t>(b & 0xFF)};
}

ModbusException exception_for(const std::vector<std::uint8_t>& request, bool read_only = false) {
  return check_modbus_request(request, shape(read_only)).exception;
}

TEST(ModbusRequest, ReadsInsideTheMapAreAccepted) {
  EXPECT_EQ(exception_for(pdu(0x04, 0, 32)), ModbusException::None);
  EXPECT_EQ(exception_for(pdu(0x03, 31, 1)), ModbusException::None);
  EXPECT_EQ(exception_for(pdu(0x02, 0, 8)), ModbusException::None);
  EXPECT_EQ(exception_for(pdu(0x01, 0, 1)), ModbusException::None);
  EXPECT_EQ(exception_for(pdu(0x04, 0, 16), true), ModbusException::None);  // reads stay allowed
}

TEST(ModbusRequest, ReadsBeyondTheMapAreIllegalDataAddress) {
  EXPECT_EQ(exception_for(pdu(0x04, 0, 33)), ModbusException::IllegalDataAddress);
  EXPECT_EQ(exception_for(pdu(0x03, 32, 1)), ModbusException::IllegalDataAddress);
  EXPECT_EQ(exception_for(pdu(0x02, 7, 2)), ModbusException::IllegalDataAddress);
  EXPECT_EQ(exception_for(pdu(0x01, 1, 1)), ModbusException::IllegalDataAddress);
  EXPECT_EQ(exception_for(pdu(0x04, 0xFFFF, 125)), ModbusException::IllegalDataAddress);
  EXPECT_EQ(check_modbus_request(pdu(0x04, 40, 1), shape()).reason, "modbus_address_out_of_map");
}

TEST(ModbusRequest, BadQuantitiesAndLengthsAreIllegalDataValue) {
  EXPECT_EQ(exception_for(pdu(0x04, 0, 0)), ModbusException::IllegalDataValue);
  EXPECT_EQ(exception_for(pdu(0x03, 0, 126)), ModbusException::IllegalDataValue);
  EXPECT_EQ(exception_for(pdu(0x02, 0, 2001)), ModbusException::IllegalDataValue);
  EXPECT_EQ(exception_for({0x04, 0x00, 0x00, 0x00}), ModbusException::IllegalDataValue);
  EXPECT_EQ(exception_for({0x04, 0x00, 0x00, 0x00, 0x01, 0x00}), ModbusException::IllegalDataValue);
  EXPECT_EQ(exception_for(pdu(0x05, 0, 0x1234)), ModbusException::IllegalDataValue);
}

TEST(ModbusRequest, CoilZeroAcknowledgesOnlyWhenWrittenOne) {
  const ModbusVerdict on = check_modbus_request(pdu(0x05, 0, 0xFF00), shape());
  EXPECT_EQ(on.exception, ModbusException::None);
  EXPECT_TRUE(on.acknowledge);
  const ModbusVerdict off = check_modbus_request(pdu(0x05, 0, 0x0000), shape());
  EXPECT_EQ(off.exception, ModbusException::None);
  EXPECT_FALSE(off.acknowledge);

  const std::vector<std::uint8_t> multiple_on = {0x0F, 0x00, 0x00, 0x00, 0x01, 0x01, 0x01};
  EXPECT_TRUE(check_modbus_request(multiple_on, shape()).acknowledge);
  const std::vector<std::uint8_t> multiple_off = {0x0F, 0x00, 0x00, 0x00, 0x01, 0x01, 0x00};
  const ModbusVerdict v = check_modbus_request(multiple_off, shape());
  EXPECT_EQ(v.exception, ModbusException::None);
  EXPECT_FALSE(v.acknowledge);
}

TEST(ModbusRequest, OtherWritesAreIllegalDataAddress) {
  EXPECT_EQ(exception_for(pdu(0x05, 1, 0xFF00)), ModbusException::IllegalDataAddress);
  const std::vector<std::uint8_t> two_coils = {0x0F, 0x00, 0x00, 0x00, 0x02, 0x01, 0x03};
  EXPECT_EQ(exception_for(two_coils), ModbusException::IllegalDataAddress);
  EXPECT_EQ(exception_for(pdu(0x06, 0, 1)), ModbusException::IllegalDataAddress);
  const std::vector<std::uint8_t> registers = {0x10, 0x00, 0x00, 0x00, 0x01, 0x02, 0x00, 0x05};
  EXPECT_EQ(exception_for(registers), ModbusException::IllegalDataAddress);
  EXPECT_EQ(check_modbus_request(pdu(0x06, 0, 1), shape()).reason, "modbus_register_write");
}

TEST(ModbusRequest, MalformedCoilWritesAreIllegalDataValue) {
  const std::vector<std::uint8_t> byte_count_mismatch = {0x0F, 0x00, 0x00, 0x00, 0x01, 0x02, 0x01, 0x00};
  EXPECT_EQ(exception_for(byte_count_mismatch), ModbusException::IllegalDataValue);
  const std::vector<std::uint8_t> truncated = {0x0F, 0x00, 0x00, 0x00, 0x09, 0x02, 0x01};
  EXPECT_EQ(exception_for(truncated), ModbusException::IllegalDataValue);
  const std::vector<std::uint8_t> zero_quantity = {0x0F, 0x00, 0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(exception_for(zero_quantity), ModbusException::IllegalDataValue);
}

TEST(ModbusRequest, ReadOnlyRefusesEveryWriteWithIllegalFunction) {
  EXPECT_EQ(exception_for(pdu(0x05, 0, 0xFF00), true), ModbusException::IllegalFunction);
  EXPECT_EQ(exception_for(pdu(0x05, 9, 0x1234), true), ModbusException::IllegalFunction);
  EXPECT_EQ(exception_for(pdu(0x06, 0, 1), true), ModbusException::IllegalFunction);
  const std::vector<std::uint8_t> coils = {0x0F, 0x00, 0x00, 0x00, 0x01, 0x01, 0x01};
  const ModbusVerdict v = check_modbus_request(coils, shape(true));
  EXPECT_EQ(v.exception, ModbusException::IllegalFunction);
  EXPECT_FALSE(v.acknowledge);
  EXPECT_EQ(v.reason, "modbus_write_read_only");
}

TEST(ModbusRequest, UnknownFunctionsAreIllegalFunction) {
  EXPECT_EQ(exception_for({0x07}), ModbusException::IllegalFunction);  // read exception status
  EXPECT_EQ(exception_for({0x11}), ModbusException::IllegalFunction);  // report server id
  EXPECT_EQ(exception_for({0x2B, 0x0E, 0x01, 0x00}), ModbusException::IllegalFunction);
  EXPECT_EQ(exception_for({}), ModbusException::IllegalFunction);
  const ModbusVerdict reserved = check_modbus_request(std::vector<std::uint8_t>{0x84, 0x02}, shape());
  EXPECT_TRUE(reserved.drop_connection);
}

TEST(ModbusRequest, UnitIdentifiers) {
  EXPECT_TRUE(modbus_unit_is_ours(1, 1));
  EXPECT_TRUE(modbus_unit_is_ours(0, 1));
  EXPECT_TRUE(modbus_unit_is_ours(255, 1));
  EXPECT_FALSE(modbus_unit_is_ours(2, 1));
  EXPECT_TRUE(modbus_unit_is_ours(17, 17));
  EXPECT_FALSE(modbus_unit_is_ours(1, 17));
}

// --- Framing ----------------------------------------------------------------------

std::vector<std::uint8_t> adu(std::uint16_t transaction, const std::vector<std::uint8_t>& pdu_bytes) {
  const auto length = static_cast<std::uint16_t>(pdu_bytes.size() + 1);
  // Sized once and filled: GCC 12 at -O3 misreads vector::insert after a 7-byte initializer
  // list as out of bounds (-Warray-bounds; a false positive of GCC 12 inlining libstdc++).
  std::vector<std::uint8_t> out(7 + pdu_bytes.size());
  out[0] = static_cast<std::uint8_t>(transaction >> 8);
  out[1] = static_cast<std::uint8_t>(transaction & 0xFF);
  out[4] = static_cast<std::uint8_t>(length >> 8);
  out[5] = static_cast<std::uint8_t>(length & 0xFF);
  out[6] = 1;  // unit
  std::copy(pdu_bytes.begin(), pdu_bytes.end(), out.begin() + 7);
  return out;
}

TEST(MbapFramer, SplitsPipelinedAndFragmentedRequests) {
  const auto first = adu(1, pdu(0x04, 0, 16));
  const auto second = adu(2, pdu(0x02, 0, 6));
  std::vector<std::uint8_t> stream = first;
  stream.insert(stream.end(), second.begin(), second.end());

  MbapFramer framer;
  Rejections rejections;
  std::vector<std::vector<std::uint8_t>> seen;
  const auto collect = [&](std::span<const std::uint8_t> a) { seen.emplace_back(a.begin(), a.end()); };
  // One byte short of both, then the rest byte by byte.
  ASSERT_TRUE(framer.feed(std::span(stream).first(stream.size() - 1), rejections, collect));
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0], first);
  EXPECT_EQ(framer.pending_bytes(), second.size() - 1);
  ASSERT_TRUE(framer.feed(std::span(stream).last(1), rejections, collect));
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[1], second);
  EXPECT_EQ(framer.pending_bytes(), 0u);
  EXPECT_EQ(rejections.total(), 0u);
}

TEST(MbapFramer, BadProtocolIdFailsTheStream) {
  MbapFramer framer;
  Rejections rejections;
  int adus = 0;
  const std::string garbage = "GET / HTTP/1.0\r\n\r\n";
  const std::vector<std::uint8_t> bytes(garbage.begin(), garbage.end());
  EXPECT_FALSE(framer.feed(bytes, rejections, [&](auto) { ++adus; }));
  EXPECT_TRUE(framer.failed());
  EXPECT_EQ(adus, 0);
  EXPECT_EQ(rejections.count("modbus_bad_protocol_id"), 1u);
  // Failed for good: a valid request afterwards is not taken.
  EXPECT_FALSE(framer.feed(adu(1, pdu(0x04, 0, 1)), rejections, [&](auto) { ++adus; }));
  EXPECT_EQ(adus, 0);
}

TEST(MbapFramer, LengthOutsideTheAduLimitFails) {
  for (const unsigned length : {0u, 1u, 255u, 0xFFFFu}) {
    MbapFramer framer;
    Rejections rejections;
    const std::vector<std::uint8_t> header = {0, 1, 0, 0, static_cast<std::uint8_t>(length >> 8),
                                              static_cast<std::uint8_t>(length & 0xFF), 1};
    EXPECT_FALSE(framer.feed(header, rejections, [](auto) {})) << length;
    EXPECT_EQ(rejections.count("modbus_bad_length"), 1u) << length;
  }
  MbapFramer framer;
  Rejections rejections;
  // The largest legal ADU (length 254, 260 bytes) passes.
  std::vector<std::uint8_t> largest = {0, 1, 0, 0, 0, 254, 1};
  largest.resize(260, 0x03);
  int adus = 0;
  EXPECT_TRUE(framer.feed(largest, rejections, [&](auto a) { adus += static_cast<int>(a.size()); }));
  EXPECT_EQ(adus, 260);
}

}  // namespace
}  // namespace kew::protocol
