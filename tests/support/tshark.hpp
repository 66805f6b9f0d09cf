#pragma once
// Checking kew against Wireshark's ASTERIX dissector: datagrams wrapped into a pcap
// (Ethernet/IPv4/UDP, port 8600, the dissector's default) written byte by byte, and
// tshark's field values read back. Used by the CAT004 and the ASTERIX decoder tests.

#include <cstddef>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace kew::tshark {

using Datagram = std::vector<std::byte>;

/// A libpcap file (microsecond timestamps, Ethernet) of one UDP datagram 127.0.0.1:8600 →
/// :8600 per entry of `datagrams`, a second apart.
std::vector<std::byte> make_pcap(const std::vector<Datagram>& datagrams);

/// Writes make_pcap(datagrams) to `path`; returns `path`.
std::string write_pcap(const std::vector<Datagram>& datagrams, const std::string& path);

/// True when an executable tshark is on PATH.
bool on_path();

/// The standard output of `command` (run by /bin/sh).
std::string run(const std::string& command);

/// Per frame, per field: the values tshark shows for every record of the frame, in order.
using FieldValues = std::map<std::string, std::vector<std::string>>;

/// tshark -T fields on `pcap` for `fields`, one FieldValues per frame, in frame order.
std::vector<FieldValues> fields(const std::string& pcap, const std::vector<std::string>& fields);

/// Frames tshark flags as malformed or with any expert information ("" when none).
std::string problems(const std::string& pcap);

}  // namespace kew::tshark

/// Skips the calling GoogleTest test, loudly, when tshark is not on PATH; `what` names the
/// check.
#define KEW_REQUIRE_TSHARK(what)                                                          \
  do {                                                                                    \
    if (!::kew::tshark::on_path()) {                                                      \
      std::fprintf(stderr, "\n*** tshark is not on PATH: %s against Wireshark's decoder " \
                           "was NOT run (apt-get install tshark) ***\n", what);           \
      GTEST_SKIP() << "tshark is not on PATH";                                            \
    }                                                                                     \
  } while (false)
