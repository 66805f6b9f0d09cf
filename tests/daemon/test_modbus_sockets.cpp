// The Modbus server at the byte level, through raw TCP sockets: exact replies, pipelined
// requests, streams it must drop, the acknowledge callback's thread, a prompt stop.

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <stdexcept>
#include <thread>

#include "free_port.hpp"
#include "test_modbus_support.hpp"

namespace kew::test {
namespace {

/// A request ADU: transaction id, protocol 0, length, unit 1, then the PDU.
std::vector<std::uint8_t> request(std::uint16_t transaction, const std::vector<std::uint8_t>& pdu,
                                  std::uint8_t unit = 1) {
  const auto length = static_cast<std::uint16_t>(pdu.size() + 1);
  // Sized once and filled: GCC 12 at -O3 misreads vector::insert after a 7-byte initializer
  // list as out of bounds (-Warray-bounds; a false positive of GCC 12 inlining libstdc++).
  std::vector<std::uint8_t> adu(7 + pdu.size());
  adu[0] = static_cast<std::uint8_t>(transaction >> 8);
  adu[1] = static_cast<std::uint8_t>(transaction & 0xFF);
  adu[4] = static_cast<std::uint8_t>(length >> 8);
  adu[5] = static_cast<std::uint8_t>(length & 0xFF);
  adu[6] = unit;
  std::copy(pdu.begin(), pdu.end(), adu.begin() + 7);
  return adu;
}

TEST(ModbusSockets, PipelinedRequestsAreAnsweredInOrder) {
  RunningServer s;
  RawClient c(s.port());
  ASSERT_TRUE(c.connected());
  std::vector<std::uint8_t> both = request(0x0102, {0x04, 0x00, 0x01, 0x00, 0x02});  // regs 1–2
  const auto second = request(0x0103, {0x02, 0x00, 0x00, 0x00, 0x06});              // inputs 0–5
  both.insert(both.end(), second.begin(), second.end());
  c.send(both);
  // 3 active alerts, highest severity 3.
  EXPECT_EQ(c.receive(13), (std::vector<std::uint8_t>{0x01, 0x02, 0, 0, 0, 7, 1, 0x04, 4, 0, 3, 0, 3}));
  // Inputs 0–4 set, 5 clear: 0b0001'1111.
  EXPECT_EQ(c.receive(10), (std::vector<std::uint8_t>{0x01, 0x03, 0, 0, 0, 4, 1, 0x02, 1, 0x1F}));
}

TEST(ModbusSockets, BadQuantityIsIllegalDataValue) {
  RunningServer s;
  RawClient c(s.port());
  c.send(request(7, {0x04, 0x00, 0x00, 0x00, 0x00}));
  EXPECT_EQ(c.receive(9), (std::vector<std::uint8_t>{0, 7, 0, 0, 0, 3, 1, 0x84, 0x03}));
  c.send(request(8, {0x2B, 0x0E, 0x01, 0x00}));  // device identification: not offered
  EXPECT_EQ(c.receive(9), (std::vector<std::uint8_t>{0, 8, 0, 0, 0, 3, 1, 0xAB, 0x01}));
  EXPECT_EQ(s.server->stats().requests, 2u);
  EXPECT_EQ(s.server->stats().exceptions, 2u);
}

TEST(ModbusSockets, WriteSingleCoilIsEchoedAfterTheCallback) {
  RunningServer s;
  RawClient c(s.port());
  const auto write = request(9, {0x05, 0x00, 0x00, 0xFF, 0x00});
  c.send(write);
  EXPECT_EQ(c.receive(write.size()), write);
  EXPECT_EQ(*s.acknowledgements, 1);  // called before the reply was sent
}

TEST(ModbusSockets, ReservedFunctionCodeDropsTheConnection) {
  RunningServer s;
  RawClient c(s.port());
  c.send(request(1, {0x83, 0x02}));
  EXPECT_TRUE(c.closed_by_peer());
  EXPECT_EQ(s.server->stats().rejected.count("modbus_reserved_function_code"), 1u);
}

TEST(ModbusSockets, OversizedLengthDropsTheConnection) {
  RunningServer s;
  RawClient c(s.port());
  c.send({0, 1, 0, 0, 0x10, 0x00, 1});  // MBAP length 4096
  EXPECT_TRUE(c.closed_by_peer());
  EXPECT_EQ(s.server->stats().rejected.count("modbus_bad_length"), 1u);
  RawClient next(s.port());
  next.send(request(2, {0x04, 0x00, 0x00, 0x00, 0x01}));
  EXPECT_EQ(next.receive(11), (std::vector<std::uint8_t>{0, 2, 0, 0, 0, 5, 1, 0x04, 2, 0, 1}));
}

TEST(ModbusSockets, ThrowingCallbackDoesNotStopTheServer) {
  daemon::ModbusConfig config;
  config.listen = kew::testing::free_loopback_address();
  daemon::ModbusServer server(config, [](const std::string&) { throw std::runtime_error("daemon gone"); });
  server.start();
  RawClient c(server.bound_port());
  const auto write = request(3, {0x05, 0x00, 0x00, 0xFF, 0x00});
  c.send(write);
  EXPECT_EQ(c.receive(write.size()), write);
  EXPECT_EQ(server.stats().rejected.count("modbus_acknowledge_callback_failed"), 1u);
}

TEST(ModbusSockets, AStatePublishedAsActiveIsNotServedOnceTheInstanceMayNotSpeak) {
  // A hot-standby active stalled past its lease: its server thread may run before its
  // I/O thread steps down, and must not answer from (nor acknowledge) the active's state.
  daemon::ModbusConfig config;
  config.listen = kew::testing::free_loopback_address();
  config.table_entries = kTableEntries;
  auto may_speak = std::make_shared<std::atomic<bool>>(true);
  auto acknowledgements = std::make_shared<std::atomic<int>>(0);
  daemon::ModbusServer server(config, [acknowledgements](const std::string&) { ++*acknowledgements; });
  server.set_speaking_check([may_speak] { return may_speak->load(); });
  server.publish(known_snapshot(), true);
  server.start();
  RawClient c(server.bound_port());
  c.send(request(1, {0x04, 0x00, 0x01, 0x00, 0x01}));  // register 1: active alerts
  EXPECT_EQ(c.receive(11), (std::vector<std::uint8_t>{0, 1, 0, 0, 0, 5, 1, 0x04, 2, 0, 3}));

  *may_speak = false;
  c.send(request(2, {0x04, 0x00, 0x01, 0x00, 0x01}));
  EXPECT_EQ(c.receive(9), (std::vector<std::uint8_t>{0, 2, 0, 0, 0, 3, 1, 0x84, 0x06}));
  c.send(request(3, {0x05, 0x00, 0x00, 0xFF, 0x00}));  // acknowledge: refused too
  EXPECT_EQ(c.receive(9), (std::vector<std::uint8_t>{0, 3, 0, 0, 0, 3, 1, 0x85, 0x06}));
  EXPECT_EQ(*acknowledgements, 0);
  EXPECT_EQ(server.stats().rejected.count("modbus_not_speaking"), 2u);

  // The standby's own state is served whatever the lease says.
  server.publish(known_snapshot(), false);
  c.send(request(4, {0x04, 0x00, 0x01, 0x00, 0x01}));
  EXPECT_EQ(c.receive(11), (std::vector<std::uint8_t>{0, 4, 0, 0, 0, 5, 1, 0x04, 2, 0, 3}));
}

TEST(ModbusSockets, StopClosesEveryConnection) {
  RunningServer s;
  RawClient a(s.port());
  RawClient b(s.port());
  ASSERT_TRUE(wait_for([&] { return s.server->stats().connections_open == 2; }));
  s.server->stop();
  EXPECT_TRUE(a.closed_by_peer());
  EXPECT_TRUE(b.closed_by_peer());
  EXPECT_EQ(s.server->stats().connections_open, 0u);
  s.server->stop();  // idempotent
}

TEST(ModbusSockets, BadConfigurationThrows) {
  daemon::ModbusConfig config;
  config.listen = "no port";
  EXPECT_THROW(daemon::ModbusServer(config, {}), std::runtime_error);
  config.listen = kew::testing::free_loopback_address();
  config.table_entries = 65;
  EXPECT_THROW(daemon::ModbusServer(config, {}), std::runtime_error);

  // A port already taken cannot be bound.
  config.table_entries = 8;
  daemon::ModbusServer first(config, {});
  config.listen = "127.0.0.1:" + std::to_string(first.bound_port());
  EXPECT_THROW(daemon::ModbusServer(config, {}), std::runtime_error);
}

}  // namespace
}  // namespace kew::test
