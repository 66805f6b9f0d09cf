#pragma once
// The Modbus TCP alarm register map (design §5.5) and the Modbus rules kew's server applies
// to requests, as pure functions: no sockets here (the server is kew::daemon::ModbusServer).
// docs/modbus.md documents every address with its reference number, unit and
// encoding; the constants below are the single source of those addresses.
//
// Modbus facts relied on (MODBUS Application Protocol Specification V1.1b3, MODBUS
// Messaging on TCP/IP Implementation Guide V1.0b): registers are big-endian 16-bit words;
// an ADU on TCP is a 7-byte MBAP header (transaction id, protocol id 0, length of what
// follows, unit id) then the PDU (function code and data), at most 260 bytes in all.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "kew/alert/alert_event.hpp"
#include "kew/util/rejections.hpp"

namespace kew::protocol {

/// The alarm state the daemon publishes to the Modbus server.
struct AlarmSnapshot {
  /// Active alerts, any order (the table sorts them). Events in state End are not active
  /// and are ignored.
  std::vector<AlertEvent> active;
  std::uint32_t live_tracks = 0;
  /// Data age: wall-clock seconds since the last record was accepted; ≥ 0, and the
  /// default (1e9) means "never" (the register saturates).
  double seconds_since_last_record = 1e9;
  bool feed_healthy = false;  ///< discrete input 4
  bool degraded = false;      ///< discrete input 5 (overloaded or stale)
  std::uint32_t uptime_s = 0;
  std::uint32_t unacknowledged = 0;
};

/// The two read-only tables of the map, indexed by PDU address (0-based). Holding
/// registers mirror input_registers; the single coil is not part of the map (it always
/// reads 0).
struct RegisterMap {
  std::vector<std::uint8_t> discrete_inputs;    ///< each 0 or 1
  std::vector<std::uint16_t> input_registers;
};

/// Input register 0. Bumped whenever an address changes meaning. The row kinds
/// (registers 9–12) kept it at 1: they were reserved registers reading 0, and 0 (every row
/// STCA) is what a server without APW means by them.
inline constexpr std::uint16_t kModbusMapVersion = 1;

/// Discrete inputs (function 2), PDU addresses. 6 and 7 are reserved and read 0, so that
/// panels reading a whole byte are answered.
enum ModbusDiscreteInput : std::uint16_t {
  kDiAnyAlert = 0,
  kDiCaution = 1,
  kDiWarning = 2,
  kDiLoss = 3,
  kDiFeedHealthy = 4,
  kDiDegraded = 5,
};
inline constexpr std::size_t kModbusDiscreteInputCount = 8;

/// Input registers (function 4) and their holding-register mirror (function 3).
enum ModbusRegister : std::uint16_t {
  kRegMapVersion = 0,
  kRegActiveAlerts = 1,
  kRegHighestSeverity = 2,
  kRegLiveTracks = 3,
  kRegSecondsSinceLastRecord = 4,
  kRegHeartbeat = 5,
  kRegUptimeHigh = 6,
  kRegUptimeLow = 7,
  kRegUnacknowledged = 8,
  /// First of kModbusRowKindRegisters registers holding the kind of each alert-table row,
  /// one bit per row (ModbusAlertKind): row r is bit r % 16 (bit 0 the least significant)
  /// of register kRegRowKinds + r / 16. A row is not widened for it: a ninth column would
  /// move every row after the first (docs/modbus.md).
  kRegRowKinds = 9,
  // 13–15 reserved, read 0.
  kRegTableStart = 16,
};

/// The value of a row's kind bit.
enum ModbusAlertKind : std::uint16_t {
  kKindStca = 0,  ///< STCA, or an empty row
  kKindApw = 1,   ///< area proximity warning: columns track B and CPA read 0
};

/// Offsets within one alert-table row.
enum ModbusTableColumn : std::uint16_t {
  kColAlertNumber = 0,
  kColSeverity = 1,
  kColTrackA = 2,
  kColTrackB = 3,
  kColTimeToLoss = 4,     ///< seconds
  kColCpaHorizontal = 5,  ///< units of 10 m
  kColCpaVertical = 6,    ///< units of 10 ft
  kColState = 7,          ///< 0 empty row, 1 new, 2 update
};
inline constexpr std::size_t kModbusTableRowWidth = 8;
/// Largest table honoured (the configuration allows 0–64); larger requests are clamped.
inline constexpr int kModbusMaxTableEntries = 64;
/// Registers of row kinds, 16 rows each (9–12).
inline constexpr std::size_t kModbusRowKindRegisters = 4;
static_assert(kModbusRowKindRegisters * 16 >= kModbusMaxTableEntries &&
                  kRegRowKinds + kModbusRowKindRegisters <= kRegTableStart,
              "the row kinds cover every row and stay within the reserved registers");

/// The coil table: coil 0 acknowledges every current alert when written 1.
inline constexpr std::uint16_t kCoilAcknowledge = 0;
inline constexpr std::size_t kModbusCoilCount = 1;

/// Number of input (and holding) registers for `table_entries` rows, after clamping
/// table_entries to [0, kModbusMaxTableEntries].
std::size_t modbus_register_count(int table_entries);

/// Builds the map of `s` (design §5.5).
///   table_entries: rows in the table, clamped to [0, kModbusMaxTableEntries];
///   heartbeat: register 5 as is (the server increments it once a second, wrapping).
/// Counts saturate at 65535; uptime is 32-bit, high word first (register 6). Figures are
/// rounded to the nearest unit (halves away from zero) then clamped to 0..65535; a figure
/// that is not a number reads 65535 ("unknown" reads as far away, never as a near miss).
/// Seconds since the last record are truncated (a 0.9 s old record is 0 s old). Rows are
/// filled most severe first, then smallest time to loss (or to entry, APW), then smallest
/// alert number, then id, whatever their kind; rows without an alert are all zero. An APW
/// row has its kind bit set (registers 9–12) and reads 0 in track B and both CPA columns:
/// there is no second aircraft, and the event's pair figures describe no pair.
RegisterMap build_register_map(const AlarmSnapshot& s, int table_entries, std::uint16_t heartbeat);

/// Modbus exception codes kew answers with.
enum class ModbusException : std::uint8_t {
  None = 0,
  IllegalFunction = 0x01,
  IllegalDataAddress = 0x02,
  IllegalDataValue = 0x03,
  /// Answered while the state kew last published came from an active hot-standby
  /// instance that may no longer speak (design §5.9): ask the other instance.
  ServerDeviceBusy = 0x06,
  /// Answered to a unit id that is not kew's (the server is addressed by IP; see
  /// check_modbus_unit).
  GatewayTargetFailedToRespond = 0x0B,
};

/// Function codes kew knows (the rest are answered ILLEGAL FUNCTION).
enum class ModbusFunction : std::uint8_t {
  ReadCoils = 0x01,
  ReadDiscreteInputs = 0x02,
  ReadHoldingRegisters = 0x03,
  ReadInputRegisters = 0x04,
  WriteSingleCoil = 0x05,
  WriteSingleRegister = 0x06,
  WriteMultipleCoils = 0x0F,
  WriteMultipleRegisters = 0x10,
  MaskWriteRegister = 0x16,
  ReadWriteMultipleRegisters = 0x17,
};

/// True for the function codes that write (05, 06, 15, 16, 22, 23): the ones refused when
/// the map is read-only, or to a client that may not write.
bool modbus_function_writes(std::uint8_t function);

/// What the server must do with one request PDU.
struct ModbusVerdict {
  /// None: answer the request normally from the map (reads) or by echoing it (writes).
  ModbusException exception = ModbusException::None;
  /// The request writes 1 to coil 0: acknowledge every current alert.
  bool acknowledge = false;
  /// The request cannot be answered at all (function codes 0x80–0xFF are reserved for
  /// exception responses, so no exception reply can name them): close the connection.
  bool drop_connection = false;
  /// Why it was refused: a stable snake_case key for kew::Rejections (empty when
  /// accepted).
  std::string_view reason;
};

/// The shape of the map the server serves.
struct ModbusMapShape {
  std::size_t discrete_inputs = kModbusDiscreteInputCount;
  std::size_t registers = kRegTableStart;  ///< input and holding registers alike
  std::size_t coils = kModbusCoilCount;
  bool read_only = false;  ///< every write is refused with ILLEGAL FUNCTION
};

/// Judges one request PDU (function code then data, no MBAP header) against the map, in
/// the order of the specification's state diagrams: function code (unknown → ILLEGAL
/// FUNCTION; any write when read-only → ILLEGAL FUNCTION), then the PDU length and the
/// quantity (→ ILLEGAL DATA VALUE: reads of 1–2000 bits or 1–125 registers, coil writes
/// of 0x0000/0xFF00 or 1–1968 bits with a matching byte count), then the addresses
/// (outside the table → ILLEGAL DATA ADDRESS; registers are never writable, coils other
/// than 0 neither). An empty PDU is ILLEGAL FUNCTION.
ModbusVerdict check_modbus_request(std::span<const std::uint8_t> pdu, const ModbusMapShape& shape);

/// True when a request to `unit_id` is for kew configured as `configured_unit`: that id,
/// or 0 or 255, which the TCP implementation guide designates for a server addressed
/// directly by its IP address.
bool modbus_unit_is_ours(std::uint8_t unit_id, int configured_unit);

/// Modbus TCP framing: splits a byte stream into ADUs (MBAP header + PDU). A Modbus TCP
/// stream cannot be resynchronised after a bad header (there is no start marker), so a
/// bad header is fatal to the stream: the caller closes the connection. Holds at most one
/// incomplete ADU (≤ kMaxAduBytes) between calls.
class MbapFramer {
 public:
  static constexpr std::size_t kHeaderBytes = 7;
  static constexpr std::size_t kMaxAduBytes = 260;

  /// Appends received bytes and calls `on_adu` with every ADU they complete (header
  /// included; the span is valid during the call only). Returns false, counted in
  /// `rejections` as "modbus_bad_protocol_id" (not 0) or "modbus_bad_length" (MBAP length
  /// outside 2–254), when a header is invalid; the framer then stays failed and ignores
  /// further input.
  template <typename OnAdu>
  bool feed(std::span<const std::uint8_t> bytes, Rejections& rejections, OnAdu&& on_adu) {
    if (failed_) return false;
    buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
    std::size_t start = 0;
    for (;;) {
      const std::size_t length = complete_adu_length(start, rejections);
      if (length == 0) break;
      on_adu(std::span<const std::uint8_t>(buffer_.data() + start, length));
      start += length;
    }
    if (failed_) {
      buffer_.clear();  // the stream is dead: hold nothing for it
      buffer_.shrink_to_fit();
    } else {
      buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start));
    }
    return !failed_;
  }

  bool failed() const { return failed_; }
  /// Bytes of an incomplete ADU held.
  std::size_t pending_bytes() const { return buffer_.size(); }

 private:
  /// Length of the ADU at `start` when it is complete, else 0 (incomplete or bad header,
  /// the latter setting failed_).
  std::size_t complete_adu_length(std::size_t start, Rejections& rejections);

  std::vector<std::uint8_t> buffer_;
  bool failed_ = false;
};

}  // namespace kew::protocol
