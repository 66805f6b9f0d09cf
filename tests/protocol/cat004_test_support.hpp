#pragma once
// What the CAT004 tests of kew's encoder (test_cat004_encoder.cpp, test_cat004_apw.cpp)
// share: bytes written out by hand and compared as hex, the options and the alert the
// byte-exact records of both were worked out from, and encoding an alert and reading
// datagrams back.

#include <gtest/gtest.h>

#include <cstddef>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "kew/protocol/encoders/cat004.hpp"
#include "kew/protocol/encoders/cat004_reader.hpp"

namespace kew::protocol::cat004_test {

inline std::vector<std::byte> bytes(std::initializer_list<unsigned> values) {
  std::vector<std::byte> out;
  for (unsigned v : values) out.push_back(static_cast<std::byte>(v));
  return out;
}

inline std::string hex(const std::vector<std::byte>& data) {
  std::string text;
  constexpr char kDigits[] = "0123456789abcdef";
  for (std::byte b : data) {
    const auto v = static_cast<unsigned>(b);
    if (!text.empty()) text.push_back(' ');
    text.push_back(kDigits[v >> 4]);
    text.push_back(kDigits[v & 0xF]);
  }
  return text;
}

// 2024-04-29 14:13:20.25 UTC: time of day 51200.25 s = 6553632/128 = 0x640020.
inline constexpr double kT = 1714400000.25;

inline Cat004Options options() {
  Cat004Options o;
  o.sac = 25;
  o.sic = 100;
  return o;
}

/// A new warning about aircraft a (BAW123, track 12), open for 10 s, 41 s from the loss
/// (or the entry): the items every byte-exact record starts with (I004/020, 040, 045, 030,
/// 170, CD and TC).
inline AlertEvent alert_about_a(std::string id) {
  AlertEvent e;
  e.id = std::move(id);
  e.number = 0x1234;
  e.state = AlertState::New;
  e.severity = Severity::Warning;
  e.t = kT;
  e.opened_t = kT - 10.0;
  e.a.id = "4CA123";
  e.a.source = "sbs";
  e.a.callsign = "BAW123";
  e.a.track_number = 12;
  e.t_los_s = 41.0;
  return e;
}

/// The one datagram the encoder writes for `e` alone; empty, failing the test, otherwise.
inline std::vector<std::byte> encoded(const AlertEvent& e) {
  Cat004Encoder encoder(options());
  EXPECT_TRUE(encoder.add_alert(e));
  std::vector<std::vector<std::byte>> datagrams = encoder.take_datagrams();
  EXPECT_EQ(datagrams.size(), 1u);
  return datagrams.empty() ? std::vector<std::byte>{} : std::move(datagrams[0]);
}

inline std::vector<Cat004Record> read_all(const std::vector<std::byte>& datagram, Cat004Reader& reader) {
  std::vector<Cat004Record> records;
  reader.read(datagram, [&](const Cat004Record& r) { records.push_back(r); });
  return records;
}

}  // namespace kew::protocol::cat004_test
