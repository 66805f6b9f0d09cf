#include "kew/protocol/modbus_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace kew::protocol {

bool modbus_function_writes(std::uint8_t function) {
  switch (static_cast<ModbusFunction>(function)) {
    case ModbusFunction::WriteSingleCoil:
    case ModbusFunction::WriteMultipleCoils:
    case ModbusFunction::WriteSingleRegister:
    case ModbusFunction::WriteMultipleRegisters:
    case ModbusFunction::MaskWriteRegister:
    case ModbusFunction::ReadWriteMultipleRegisters:
      return true;
    default:
      return false;
  }
}

namespace {

constexpr std::uint16_t kRegisterMax = std::numeric_limits<std::uint16_t>::max();

std::uint16_t saturate_count(std::uint64_t count) {
  return static_cast<std::uint16_t>(std::min<std::uint64_t>(count, kRegisterMax));
}

/// Rounds `value / unit` to the nearest whole number (halves away from zero) and clamps it
/// to a register; NaN reads as the maximum (unknown is never reported as close).
std::uint16_t saturate_figure(double value, double unit) {
  if (std::isnan(value)) return kRegisterMax;
  const double scaled = std::round(value / unit);
  if (scaled <= 0.0) return 0;
  if (scaled >= kRegisterMax) return kRegisterMax;
  return static_cast<std::uint16_t>(scaled);
}

/// Whole seconds elapsed, truncated: an age is reported as "at least N seconds".
std::uint16_t saturate_age(double seconds) {
  if (std::isnan(seconds) || seconds >= kRegisterMax) return kRegisterMax;
  if (seconds <= 0.0) return 0;
  return static_cast<std::uint16_t>(seconds);
}

/// NaN sorts as "no loss predicted" so the ordering stays a strict weak order.
double sortable_time_to_loss(const AlertEvent& e) {
  return std::isnan(e.t_los_s) ? std::numeric_limits<double>::infinity() : e.t_los_s;
}

/// Most urgent first (design §5.5: "a table of the most severe alerts"); alert number, then
/// id, make the order total so equal alerts never swap rows between snapshots.
bool more_urgent(const AlertEvent* x, const AlertEvent* y) {
  return std::make_tuple(-static_cast<int>(x->severity), sortable_time_to_loss(*x), x->number,
                         std::string_view(x->id)) <
         std::make_tuple(-static_cast<int>(y->severity), sortable_time_to_loss(*y), y->number,
                         std::string_view(y->id));
}

std::uint16_t state_code(AlertState state) {
  return state == AlertState::New ? 1 : 2;
}

void write_row(const AlertEvent& e, std::span<std::uint16_t> row) {
  row[kColAlertNumber] = e.number;
  row[kColSeverity] = static_cast<std::uint16_t>(e.severity);
  row[kColTrackA] = e.a.track_number;
  row[kColTimeToLoss] = saturate_figure(e.t_los_s, 1.0);
  row[kColState] = state_code(e.state);
  // An APW row leaves the pair's columns 0 whatever the event holds, so a panel never
  // shows a track or a closest approach the alert does not have.
  if (e.kind == AlertKind::Apw) return;
  row[kColTrackB] = e.b.track_number;
  row[kColCpaHorizontal] = saturate_figure(e.cpa_h_m, 10.0);
  row[kColCpaVertical] = saturate_figure(e.cpa_v_ft, 10.0);
}

int clamp_table_entries(int table_entries) {
  return std::clamp(table_entries, 0, kModbusMaxTableEntries);
}

}  // namespace

std::size_t modbus_register_count(int table_entries) {
  return kRegTableStart +
         static_cast<std::size_t>(clamp_table_entries(table_entries)) * kModbusTableRowWidth;
}

RegisterMap build_register_map(const AlarmSnapshot& s, int table_entries, std::uint16_t heartbeat) {
  std::vector<const AlertEvent*> active;
  active.reserve(s.active.size());
  for (const AlertEvent& e : s.active) {
    if (e.state != AlertState::End) active.push_back(&e);
  }
  std::sort(active.begin(), active.end(), more_urgent);

  RegisterMap map;
  map.discrete_inputs.assign(kModbusDiscreteInputCount, 0);
  map.input_registers.assign(modbus_register_count(table_entries), 0);

  Severity highest = Severity::None;
  for (const AlertEvent* e : active) {
    highest = std::max(highest, e->severity);
    if (e->severity == Severity::Caution) map.discrete_inputs[kDiCaution] = 1;
    if (e->severity == Severity::Warning) map.discrete_inputs[kDiWarning] = 1;
    if (e->severity == Severity::Loss) map.discrete_inputs[kDiLoss] = 1;
  }
  map.discrete_inputs[kDiAnyAlert] = active.empty() ? 0 : 1;
  map.discrete_inputs[kDiFeedHealthy] = s.feed_healthy ? 1 : 0;
  map.discrete_inputs[kDiDegraded] = s.degraded ? 1 : 0;

  auto& r = map.input_registers;
  r[kRegMapVersion] = kModbusMapVersion;
  r[kRegActiveAlerts] = saturate_count(active.size());
  r[kRegHighestSeverity] = static_cast<std::uint16_t>(highest);
  r[kRegLiveTracks] = saturate_count(s.live_tracks);
  r[kRegSecondsSinceLastRecord] = saturate_age(s.seconds_since_last_record);
  r[kRegHeartbeat] = heartbeat;
  r[kRegUptimeHigh] = static_cast<std::uint16_t>(s.uptime_s >> 16);
  r[kRegUptimeLow] = static_cast<std::uint16_t>(s.uptime_s & 0xFFFFu);
  r[kRegUnacknowledged] = saturate_count(s.unacknowledged);

  const std::size_t rows =
      std::min(active.size(), static_cast<std::size_t>(clamp_table_entries(table_entries)));
  for (std::size_t i = 0; i < rows; ++i) {
    write_row(*active[i], std::span<std::uint16_t>(r).subspan(
                              kRegTableStart + i * kModbusTableRowWidth, kModbusTableRowWidth));
    if (active[i]->kind == AlertKind::Apw) {
      r[kRegRowKinds + i / 16] |= static_cast<std::uint16_t>(kKindApw << (i % 16));
    }
  }
  return map;
}

namespace {

// Quantity limits of the application protocol specification (§6.1–6.4, 6.11, 6.12).
constexpr std::size_t kMaxReadBits = 2000;
constexpr std::size_t kMaxReadRegisters = 125;
constexpr std::size_t kMaxWriteBits = 1968;
constexpr std::uint16_t kCoilOn = 0xFF00;
constexpr std::uint16_t kCoilOff = 0x0000;

std::uint16_t word_at(std::span<const std::uint8_t> pdu, std::size_t offset) {
  return static_cast<std::uint16_t>((pdu[offset] << 8) | pdu[offset + 1]);
}

ModbusVerdict refuse(ModbusException exception, std::string_view reason) {
  return ModbusVerdict{exception, false, false, reason};
}

bool is_register_write(std::uint8_t function) {
  return modbus_function_writes(function) &&
         function != static_cast<std::uint8_t>(ModbusFunction::WriteSingleCoil) &&
         function != static_cast<std::uint8_t>(ModbusFunction::WriteMultipleCoils);
}

/// Reads: function, start address, quantity.
ModbusVerdict check_read(std::span<const std::uint8_t> pdu, std::size_t max_quantity,
                         std::size_t table_size) {
  if (pdu.size() != 5) return refuse(ModbusException::IllegalDataValue, "modbus_bad_pdu_length");
  const std::size_t start = word_at(pdu, 1);
  const std::size_t quantity = word_at(pdu, 3);
  if (quantity < 1 || quantity > max_quantity) {
    return refuse(ModbusException::IllegalDataValue, "modbus_bad_quantity");
  }
  if (start + quantity > table_size) {
    return refuse(ModbusException::IllegalDataAddress, "modbus_address_out_of_map");
  }
  return {};
}

ModbusVerdict check_write_single_coil(std::span<const std::uint8_t> pdu, std::size_t coils) {
  if (pdu.size() != 5) return refuse(ModbusException::IllegalDataValue, "modbus_bad_pdu_length");
  const std::uint16_t address = word_at(pdu, 1);
  const std::uint16_t value = word_at(pdu, 3);
  if (value != kCoilOn && value != kCoilOff) {
    return refuse(ModbusException::IllegalDataValue, "modbus_bad_coil_value");
  }
  if (address != kCoilAcknowledge || coils == 0) {
    return refuse(ModbusException::IllegalDataAddress, "modbus_address_out_of_map");
  }
  return ModbusVerdict{ModbusException::None, value == kCoilOn, false, {}};
}

/// Function, start address, quantity, byte count, packed bits (least significant bit of
/// the first byte is the first coil).
ModbusVerdict check_write_multiple_coils(std::span<const std::uint8_t> pdu, std::size_t coils) {
  if (pdu.size() < 7) return refuse(ModbusException::IllegalDataValue, "modbus_bad_pdu_length");
  const std::size_t start = word_at(pdu, 1);
  const std::size_t quantity = word_at(pdu, 3);
  const std::size_t byte_count = pdu[5];
  if (quantity < 1 || quantity > kMaxWriteBits || byte_count != (quantity + 7) / 8 ||
      pdu.size() != 6 + byte_count) {
    return refuse(ModbusException::IllegalDataValue, "modbus_bad_quantity");
  }
  if (start + quantity > coils) {
    return refuse(ModbusException::IllegalDataAddress, "modbus_address_out_of_map");
  }
  const bool acknowledge = start == kCoilAcknowledge && (pdu[6] & 0x01) != 0;
  return ModbusVerdict{ModbusException::None, acknowledge, false, {}};
}

}  // namespace

ModbusVerdict check_modbus_request(std::span<const std::uint8_t> pdu, const ModbusMapShape& shape) {
  if (pdu.empty()) return refuse(ModbusException::IllegalFunction, "modbus_empty_pdu");
  const std::uint8_t function = pdu[0];
  if (function >= 0x80) {
    ModbusVerdict verdict = refuse(ModbusException::IllegalFunction, "modbus_reserved_function_code");
    verdict.drop_connection = true;
    return verdict;
  }
  if (shape.read_only && modbus_function_writes(function)) {
    return refuse(ModbusException::IllegalFunction, "modbus_write_read_only");
  }
  if (is_register_write(function)) {
    // Every register is read-only: the address names nothing writable, whatever it is.
    return refuse(ModbusException::IllegalDataAddress, "modbus_register_write");
  }
  switch (static_cast<ModbusFunction>(function)) {
    case ModbusFunction::ReadCoils:
      return check_read(pdu, kMaxReadBits, shape.coils);
    case ModbusFunction::ReadDiscreteInputs:
      return check_read(pdu, kMaxReadBits, shape.discrete_inputs);
    case ModbusFunction::ReadHoldingRegisters:
    case ModbusFunction::ReadInputRegisters:
      return check_read(pdu, kMaxReadRegisters, shape.registers);
    case ModbusFunction::WriteSingleCoil:
      return check_write_single_coil(pdu, shape.coils);
    case ModbusFunction::WriteMultipleCoils:
      return check_write_multiple_coils(pdu, shape.coils);
    default:
      return refuse(ModbusException::IllegalFunction, "modbus_unsupported_function");
  }
}

bool modbus_unit_is_ours(std::uint8_t unit_id, int configured_unit) {
  return unit_id == configured_unit || unit_id == 0 || unit_id == 0xFF;
}

std::size_t MbapFramer::complete_adu_length(std::size_t start, Rejections& rejections) {
  if (buffer_.size() - start < kHeaderBytes) return 0;
  const std::uint8_t* header = buffer_.data() + start;
  const unsigned protocol_id = (header[2] << 8) | header[3];
  const std::size_t length = (header[4] << 8) | header[5];  // unit id + PDU
  if (protocol_id != 0) {
    rejections.reject("modbus_bad_protocol_id", "MBAP protocol identifier is not 0 (Modbus)");
    failed_ = true;
    return 0;
  }
  if (length < 2 || length > kMaxAduBytes - 6) {
    rejections.reject("modbus_bad_length", "MBAP length outside 2-254");
    failed_ = true;
    return 0;
  }
  const std::size_t adu_bytes = 6 + length;
  return buffer_.size() - start >= adu_bytes ? adu_bytes : 0;
}

}  // namespace kew::protocol
