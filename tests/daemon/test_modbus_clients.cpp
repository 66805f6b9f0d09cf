// The Modbus server read and written by real clients run as subprocesses: mbpoll (a
// libmodbus master) and pymodbus (an independent implementation), design §5.5.

#include <gtest/gtest.h>

#include <thread>

#include "test_modbus_support.hpp"

namespace kew::test {
namespace {

constexpr std::size_t kHeartbeat = protocol::kRegHeartbeat;

class WithMbpoll : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_mbpoll()) {
      GTEST_SKIP() << "*** mbpoll is not installed (apt-get install mbpoll): Modbus client test SKIPPED ***";
    }
  }
  /// mbpoll, once, unit 1, 2 s timeout, against the server; it writes `values` when given.
  CommandResult mbpoll(const RunningServer& s, const std::string& options, const std::string& values = "") {
    return run_command("mbpoll -m tcp -a 1 -1 -o 2 " + options + " 127.0.0.1 -p " +
                       std::to_string(s.port()) + " " + values);
  }
};

class WithPymodbus : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto found = python_with_pymodbus();
    if (!found) {
      GTEST_SKIP() << "*** python3-pymodbus is not installed: Modbus client test SKIPPED ***";
    }
    python = *found;
  }
  CommandResult client(const RunningServer& s, const std::string& arguments) {
    return modbus_client(python, s.port(), arguments);
  }
  std::string python;
};

// --- mbpoll ------------------------------------------------------------------------

TEST_F(WithMbpoll, ReadsInputRegistersWithOneBasedReferences) {
  RunningServer s;
  // -t 3 input registers; mbpoll's reference 1 is PDU address 0 (reference 30001).
  const CommandResult r = mbpoll(s, "-t 3 -r 1 -c 48");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto values = mbpoll_values(r.output);
  const auto expected = expected_registers();
  ASSERT_EQ(values.size(), expected.size()) << r.output;
  for (std::size_t address = 0; address < expected.size(); ++address) {
    if (address == kHeartbeat) continue;
    EXPECT_EQ(values.at(static_cast<int>(address) + 1), expected[address]) << "register " << address;
  }
}

TEST_F(WithMbpoll, HoldingRegistersMirrorInputRegisters) {
  RunningServer s;
  const CommandResult r = mbpoll(s, "-t 4 -0 -r 16 -c 32");  // -0: PDU addresses
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto values = mbpoll_values(r.output);
  const auto expected = expected_registers();
  for (std::size_t address = 16; address < expected.size(); ++address) {
    EXPECT_EQ(values.at(static_cast<int>(address)), expected[address]) << "register " << address;
  }
}

TEST_F(WithMbpoll, ReadsDiscreteInputsAndUptime) {
  RunningServer s;
  const CommandResult inputs = mbpoll(s, "-t 1 -0 -r 0 -c 8");
  ASSERT_EQ(inputs.exit_code, 0) << inputs.output;
  // any alert, caution, warning, loss, feed healthy, not degraded, reserved, reserved
  EXPECT_EQ(mbpoll_values(inputs.output),
            (std::map<int, long>{{0, 1}, {1, 1}, {2, 1}, {3, 1}, {4, 1}, {5, 0}, {6, 0}, {7, 0}}));

  const CommandResult uptime = mbpoll(s, "-t 3:int -B -0 -r 6 -c 1");  // -B: high word first
  ASSERT_EQ(uptime.exit_code, 0) << uptime.output;
  EXPECT_EQ(mbpoll_values(uptime.output).at(6), 123456);
}

TEST_F(WithMbpoll, CoilZeroAcknowledgesAndReadsBackZero) {
  RunningServer s;
  const CommandResult write = mbpoll(s, "-t 0 -r 1", "1");  // reference 00001 = coil 0
  ASSERT_EQ(write.exit_code, 0) << write.output;
  EXPECT_EQ(*s.acknowledgements, 1);
  const CommandResult read = mbpoll(s, "-t 0 -r 1 -c 1");
  ASSERT_EQ(read.exit_code, 0) << read.output;
  EXPECT_EQ(mbpoll_values(read.output).at(1), 0);
}

TEST_F(WithMbpoll, ReportsIllegalDataAddressAndIllegalFunction) {
  RunningServer s;
  const CommandResult beyond = mbpoll(s, "-t 3 -0 -r 48 -c 1");
  EXPECT_NE(beyond.exit_code, 0);
  EXPECT_NE(beyond.output.find("Illegal data address"), std::string::npos) << beyond.output;
  const CommandResult other_coil = mbpoll(s, "-t 0 -0 -r 1", "1");
  EXPECT_NE(other_coil.exit_code, 0);
  EXPECT_NE(other_coil.output.find("Illegal data address"), std::string::npos) << other_coil.output;

  RunningServer read_only(true);
  const CommandResult refused = mbpoll(read_only, "-t 0 -0 -r 0", "1");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("Illegal function"), std::string::npos) << refused.output;
  EXPECT_EQ(*read_only.acknowledgements, 0);
}

// --- pymodbus ----------------------------------------------------------------------

TEST_F(WithPymodbus, ReadsRegistersAndDiscreteInputs) {
  RunningServer s;
  const CommandResult registers = client(s, "read-input-registers 0 48");
  ASSERT_EQ(registers.exit_code, 0) << registers.output;
  auto values = json_values(registers.output);
  const auto expected = expected_registers();
  ASSERT_EQ(values.size(), expected.size()) << registers.output;
  values[kHeartbeat] = 0;
  EXPECT_EQ(values, std::vector<long>(expected.begin(), expected.end()));

  const CommandResult holding = client(s, "read-holding-registers 16 8");
  ASSERT_EQ(holding.exit_code, 0) << holding.output;
  EXPECT_EQ(json_values(holding.output), (std::vector<long>{12, 3, 103, 104, 0, 120, 30, 1}));

  const CommandResult inputs = client(s, "read-discrete-inputs 0 6");
  ASSERT_EQ(inputs.exit_code, 0) << inputs.output;
  EXPECT_EQ(json_values(inputs.output), (std::vector<long>{1, 1, 1, 1, 1, 0}));
}

TEST_F(WithPymodbus, ReadMapDecodesTheTable) {
  RunningServer s;
  const CommandResult r = client(s, "read-map --entries 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(R"("uptime_s": 123456)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(R"("active_alerts": 3)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(R"({"alert_number": 12, "cpa_h_10m": 120, "cpa_v_10ft": 30, "kind": 0, )"
                          R"("severity": 3, "state": 1, "t_los_s": 0, "track_a": 103, "track_b": 104})"),
            std::string::npos)
      << r.output;
  std::size_t rows = 0;
  for (auto at = r.output.find("alert_number"); at != std::string::npos; at = r.output.find("alert_number", at + 1)) {
    ++rows;
  }
  EXPECT_EQ(rows, 3u);  // the empty fourth row is not listed
}

// An area proximity warning in the fourth row: its kind bit (register 9, bit 3) reaches a
// real client, and its track B and CPA columns read 0.
TEST_F(WithPymodbus, ReadMapSaysEachRowsKind) {
  RunningServer s;
  protocol::AlarmSnapshot snapshot = known_snapshot();
  AlertEvent area;
  area.id = "alert-14";
  area.number = 14;
  area.kind = AlertKind::Apw;
  area.severity = Severity::Caution;
  area.state = AlertState::Update;
  area.t_los_s = 120.0;  // after the caution of 95.4 s: the fourth row
  area.a.track_number = 106;
  area.b.track_number = 107;  // not an APW alert's: the map reads 0
  area.cpa_h_m = 500.0;
  area.volume = "EDR205";
  area.volume_kind = "restricted";
  snapshot.active.push_back(area);
  s.server->publish(snapshot);

  const CommandResult kinds = client(s, "read-input-registers 9 4");
  ASSERT_EQ(kinds.exit_code, 0) << kinds.output;
  EXPECT_EQ(json_values(kinds.output), (std::vector<long>{1 << 3, 0, 0, 0}));
  const CommandResult r = client(s, "read-map --entries 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(R"({"alert_number": 14, "cpa_h_10m": 0, "cpa_v_10ft": 0, "kind": 1, )"
                          R"("severity": 1, "state": 2, "t_los_s": 120, "track_a": 106, "track_b": 0})"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(R"("alert_number": 13, "cpa_h_10m": 505, "cpa_v_10ft": 0, "kind": 0,)"),
            std::string::npos)
      << r.output;
}

TEST_F(WithPymodbus, HeartbeatIncrements) {
  RunningServer s;
  const CommandResult first = client(s, "read-input-registers 5 1");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  const CommandResult second = client(s, "read-input-registers 5 1");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  ASSERT_EQ(json_values(first.output).size(), 1u);
  ASSERT_EQ(json_values(second.output).size(), 1u);
  EXPECT_GT(json_values(second.output)[0], json_values(first.output)[0]);
}

TEST_F(WithPymodbus, PublishedSnapshotIsServed) {
  RunningServer s;
  protocol::AlarmSnapshot quiet;
  quiet.live_tracks = 9;
  s.server->publish(quiet);
  const CommandResult r = client(s, "read-input-registers 0 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(json_values(r.output), (std::vector<long>{1, 0, 0, 9}));
}

TEST_F(WithPymodbus, CoilZeroAcknowledges) {
  RunningServer s;
  const CommandResult on = client(s, "write-coil 0 1");
  ASSERT_EQ(on.exit_code, 0) << on.output;
  EXPECT_EQ(*s.acknowledgements, 1);
  const CommandResult off = client(s, "write-coil 0 0");  // accepted, acknowledges nothing
  ASSERT_EQ(off.exit_code, 0) << off.output;
  EXPECT_EQ(*s.acknowledgements, 1);
  EXPECT_EQ(s.server->stats().acknowledgements, 1u);
  const CommandResult coil = client(s, "read-coils 0 1");
  ASSERT_EQ(coil.exit_code, 0) << coil.output;
  EXPECT_EQ(json_values(coil.output), (std::vector<long>{0}));
}

// An acknowledgement names the client's address and port, as the
// client itself sees its socket.
TEST_F(WithPymodbus, AcknowledgementNamesTheClientAddressAndPort) {
  RunningServer s;
  const CommandResult on = client(s, "write-coil 0 1");
  ASSERT_EQ(on.exit_code, 0) << on.output;
  const std::string me = json_client(on.output);
  ASSERT_TRUE(me.starts_with("127.0.0.1:")) << on.output;
  EXPECT_EQ(s.acknowledged_by->list(), std::vector<std::string>{me});
}

// acknowledge_from: a client at another address may read, but every write is refused
// with ILLEGAL FUNCTION (as in read-only mode) and counted; a listed address writes.
TEST_F(WithPymodbus, AcknowledgeFromRefusesWritesFromOtherAddresses) {
  RunningServer s(false, 4, 1, {"192.0.2.7", "::1"});
  for (const std::string request : {"write-coil 0 1", "write-coil 0 0", "write-register 0 5"}) {
    const CommandResult r = client(s, request);
    EXPECT_EQ(r.exit_code, 2) << request << ": " << r.output;
    EXPECT_EQ(json_exception_code(r.output), 1) << request << ": " << r.output;
  }
  EXPECT_EQ(*s.acknowledgements, 0);
  EXPECT_EQ(s.server->stats().rejected.count("modbus_write_not_permitted"), 3u);
  const CommandResult read = client(s, "read-input-registers 0 2");
  ASSERT_EQ(read.exit_code, 0) << read.output;
  EXPECT_EQ(json_values(read.output), (std::vector<long>{1, 3}));

  RunningServer listed(false, 4, 1, {"127.0.0.1"});
  const CommandResult on = client(listed, "write-coil 0 1");
  ASSERT_EQ(on.exit_code, 0) << on.output;
  EXPECT_EQ(*listed.acknowledgements, 1);
  EXPECT_EQ(listed.server->stats().rejected.count("modbus_write_not_permitted"), 0u);
}

TEST_F(WithPymodbus, InvalidAddressesAreIllegalDataAddress) {
  RunningServer s;
  for (const std::string request : {"write-coil 1 1", "write-register 0 5", "read-input-registers 48 1",
                                    "read-holding-registers 40 9", "read-discrete-inputs 8 1",
                                    "read-coils 1 1"}) {
    const CommandResult r = client(s, request);
    EXPECT_EQ(r.exit_code, 2) << request << ": " << r.output;
    EXPECT_EQ(json_exception_code(r.output), 2) << request << ": " << r.output;
  }
  EXPECT_EQ(*s.acknowledgements, 0);
  EXPECT_EQ(s.server->stats().exceptions, 6u);
  EXPECT_EQ(s.server->stats().rejected.count("modbus_address_out_of_map"), 5u);
  EXPECT_EQ(s.server->stats().rejected.count("modbus_register_write"), 1u);
}

TEST_F(WithPymodbus, ReadOnlyRefusesWritesWithIllegalFunction) {
  RunningServer s(true);
  for (const std::string request : {"write-coil 0 1", "write-coil 3 1", "write-register 0 5"}) {
    const CommandResult r = client(s, request);
    EXPECT_EQ(r.exit_code, 2) << request << ": " << r.output;
    EXPECT_EQ(json_exception_code(r.output), 1) << request << ": " << r.output;
  }
  EXPECT_EQ(*s.acknowledgements, 0);
  const CommandResult read = client(s, "read-input-registers 0 2");
  ASSERT_EQ(read.exit_code, 0) << read.output;
  EXPECT_EQ(json_values(read.output), (std::vector<long>{1, 3}));
}

TEST_F(WithPymodbus, AnswersItsUnitIdAndTheTcpConventionsOnly) {
  RunningServer s(false, 4, 17);
  for (const std::string unit : {"17", "0", "255"}) {
    const CommandResult r = client(s, "--unit " + unit + " read-input-registers 0 1");
    EXPECT_EQ(r.exit_code, 0) << unit << ": " << r.output;
    EXPECT_EQ(json_values(r.output), (std::vector<long>{1})) << unit;
  }
  const CommandResult other = client(s, "--unit 1 read-input-registers 0 1");
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_EQ(json_exception_code(other.output), 0x0B) << other.output;
}

TEST_F(WithPymodbus, SilentAndGarbageClientsDoNotBlockOthers) {
  RunningServer s;
  RawClient silent(s.port());
  RawClient partial(s.port());
  RawClient garbage(s.port());
  ASSERT_TRUE(silent.connected() && partial.connected() && garbage.connected());
  partial.send({0x00, 0x01, 0x00});  // three bytes of a header, never completed
  const std::string http = "GET / HTTP/1.0\r\n\r\n";
  garbage.send(std::vector<std::uint8_t>(http.begin(), http.end()));
  EXPECT_TRUE(garbage.closed_by_peer());

  const CommandResult r = client(s, "read-input-registers 0 3");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(json_values(r.output), (std::vector<long>{1, 3, 3}));
  EXPECT_EQ(s.server->stats().rejected.count("modbus_bad_protocol_id"), 1u);
  EXPECT_GE(s.server->stats().connections_dropped, 1u);
}

/// Reads input register 0 on `client` and waits for the answer: a panel, no longer silent.
void poll_once(RawClient& client) {
  client.send({0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x04, 0x00, 0x00, 0x00, 0x01});
  ASSERT_EQ(client.receive(11).size(), 11u);
}

TEST_F(WithPymodbus, ConnectionLimitIsEnforced) {
  RunningServer s(false, 2);
  // Two panels that have been answered hold the slots: neither is silent, so neither gives
  // way to a newcomer (they are quiet far less than half the idle time-out).
  RawClient first(s.port());
  RawClient second(s.port());
  poll_once(first);
  poll_once(second);
  ASSERT_TRUE(wait_for([&] { return s.server->stats().connections_open == 2; }));

  const CommandResult refused = client(s, "read-input-registers 0 1");
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_GE(s.server->stats().connections_refused, 1u);

  first.close();
  ASSERT_TRUE(wait_for([&] { return s.server->stats().connections_open == 1; }));
  const CommandResult served = client(s, "read-input-registers 0 1");
  EXPECT_EQ(served.exit_code, 0) << served.output;
  EXPECT_EQ(json_values(served.output), (std::vector<long>{1}));
}

// A silent client (no complete request yet) gives way to a newcomer at once, the
// longest-silent first, by the rule every listener follows (design §6.6): a flood of
// connections that reconnect before any of them is a second old cannot keep a panel out.
TEST_F(WithPymodbus, ANewcomerReplacesTheLongestSilentClientAtOnce) {
  RunningServer s(false, 2);
  RawClient longest_silent(s.port());
  ASSERT_TRUE(wait_for([&] { return s.server->stats().connections_open == 1; }));
  RawClient silent(s.port());
  ASSERT_TRUE(wait_for([&] { return s.server->stats().connections_open == 2; }));

  const CommandResult served = client(s, "read-input-registers 0 1");
  EXPECT_EQ(served.exit_code, 0) << served.output;
  EXPECT_EQ(json_values(served.output), (std::vector<long>{1}));
  EXPECT_TRUE(longest_silent.closed_by_peer());
  EXPECT_EQ(s.server->stats().rejected.count("modbus_evicted"), 1u);
  EXPECT_EQ(s.server->stats().connections_refused, 0u);
}

}  // namespace
}  // namespace kew::test
