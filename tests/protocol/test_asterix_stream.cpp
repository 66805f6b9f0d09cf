// The Decoder contract of the four ASTERIX framings: incremental (1 byte at a time and
// random chunks give exactly the reports of one feed), resynchronising after garbage with
// the reason counted, bounded, and the pcap variants (byte orders, nanosecond stamps, link
// types, fragments). Also the framing confidence used by format auto-detection.

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::Counts;
using test::decode_all;
using test::read_file;

std::string fixture(const std::string& name) {
  return read_file(std::string(KEW_TEST_DATA_DIR) + "/asterix/" + name);
}

std::uint32_t be16(const std::string& s, std::size_t at) {
  return (std::uint32_t{static_cast<std::uint8_t>(s[at])} << 8) | static_cast<std::uint8_t>(s[at + 1]);
}

/// The data blocks of a final-format file, back to back (header and trailer removed).
std::string raw_blocks_of_ff(const std::string& ff) {
  std::string raw;
  for (std::size_t at = 0; at + 2 <= ff.size();) {
    const std::size_t length = be16(ff, at);
    raw += ff.substr(at + 8, length - 12);
    at += length;
  }
  return raw;
}

/// The data blocks of a raw stream, one string each.
std::vector<std::string> split_blocks(const std::string& raw) {
  std::vector<std::string> blocks;
  for (std::size_t at = 0; at + 3 <= raw.size();) {
    const std::size_t length = be16(raw, at + 1);
    blocks.push_back(raw.substr(at, length));
    at += length;
  }
  return blocks;
}

AsterixOptions croatia_radars() {
  AsterixOptions options;
  for (const int sic : {11, 12, 13, 14, 201, 204, 205}) {
    options.radars.push_back({25, static_cast<std::uint8_t>(sic), 45.0, 16.0, 100.0});
  }
  return options;
}

auto maker(AsterixFraming framing, AsterixOptions options = {}) {
  return [framing, options] { return make_asterix_decoder(framing, options); };
}

struct Decoded {
  std::vector<TrackReport> reports;
  Counts rejections;
};

Decoded decode(AsterixFraming framing, const std::string& input, const AsterixOptions& options = {}) {
  auto decoder = make_asterix_decoder(framing, options);
  Decoded d;
  d.reports = decode_all(*decoder, input);
  d.rejections = decoder->rejections().by_reason();
  return d;
}

/// A garbage run no plausible block, frame or pcap record header can start in: bytes of
/// unassigned categories (0, 171, 255) and lengths/magic numbers that cannot be real.
std::string garbage(std::size_t n) {
  static const char kPattern[] = {'\xFF', '\x00', '\xAB', '\xFF', '\xAB', '\x00'};
  std::string g;
  for (std::size_t i = 0; i < n; ++i) g += kPattern[i % sizeof kPattern];
  return g;
}

// ---- Incrementality -------------------------------------------------------------------------

TEST(AsterixIncremental, RawBlocksAnySplitGivesTheSameReports) {
  const std::string raw = raw_blocks_of_ff(fixture("jade/final_frame_062_first3min.ff"));
  ASSERT_GT(raw.size(), 100000U);
  test::expect_incremental(maker(AsterixFraming::RawBlocks), raw);
}

TEST(AsterixIncremental, RawBlocksMixedCategoriesAnySplit) {
  const std::string raw = fixture("croatiacontrol/cat062cat065.raw") + fixture("croatiacontrol/cat048.raw") +
                          fixture("croatiacontrol/cat034.raw") + fixture("croatiacontrol/cat21_re.ast") +
                          fixture("jasterix/cat021ed0.26.bin") + fixture("asterix4py/cat062.ast");
  test::expect_incremental(maker(AsterixFraming::RawBlocks, croatia_radars()), raw);
}

TEST(AsterixIncremental, FinalFormatAnySplitGivesTheSameReports) {
  test::expect_incremental(maker(AsterixFraming::FinalFormat), fixture("jade/final_frame_062_first3min.ff"));
}

TEST(AsterixIncremental, PcapAnySplitGivesTheSameReports) {
  test::expect_incremental(maker(AsterixFraming::Pcap, croatia_radars()),
                           fixture("croatiacontrol/cat_034_048.pcap"));
}

TEST(AsterixIncremental, GarbageStreamsAnySplitGiveTheSameOutcome) {
  // Resynchronisation decisions must not depend on where the bytes were cut either.
  const std::string raw = raw_blocks_of_ff(fixture("jade/final_frame_062_first3min.ff")).substr(0, 20000);
  std::mt19937 random(9);
  std::string noisy;
  for (std::size_t at = 0; at < raw.size(); at += 997) {
    noisy += raw.substr(at, 997);
    for (int i = 0; i < 5; ++i) noisy += static_cast<char>(random());
  }
  test::expect_incremental(maker(AsterixFraming::RawBlocks), noisy);
}

TEST(AsterixIncremental, FinalFormatWithGarbageAnySplit) {
  const std::string ff = fixture("jade/final_frame_062_first3min.ff").substr(0, 30000);
  test::expect_incremental(maker(AsterixFraming::FinalFormat), garbage(7) + ff.substr(0, 9000) + garbage(3) + ff.substr(9000));
}

TEST(AsterixDatagram, EachFeedIsOneDatagramOfOneOrMoreBlocks) {
  const std::string raw = raw_blocks_of_ff(fixture("jade/final_frame_062_first3min.ff"));
  const Decoded expected = decode(AsterixFraming::RawBlocks, raw);
  auto decoder = make_asterix_decoder(AsterixFraming::Datagram);
  EXPECT_EQ(decoder->format_name(), "asterix-datagram");
  std::vector<TrackReport> reports;
  const ReportSink sink = [&](const TrackReport& r) { reports.push_back(r); };
  // Datagrams of 1 to 4 blocks.
  const auto blocks = split_blocks(raw);
  for (std::size_t i = 0; i < blocks.size();) {
    std::string datagram;
    for (std::size_t n = 1 + i % 4; n > 0 && i < blocks.size(); --n) datagram += blocks[i++];
    decoder->feed(test::bytes_of(datagram), sink);
  }
  decoder->finish(sink);
  test::expect_same_reports(expected.reports, reports);
  EXPECT_EQ(decoder->rejections().by_reason(), expected.rejections);
}

TEST(AsterixDatagram, ABadBlockLengthEndsOnlyItsDatagram) {
  const auto blocks = split_blocks(fixture("asterix4py/cat062.ast") + fixture("croatiacontrol/cat062cat065.raw"));
  ASSERT_EQ(blocks.size(), 3U);
  auto decoder = make_asterix_decoder(AsterixFraming::Datagram);
  std::vector<TrackReport> reports;
  const ReportSink sink = [&](const TrackReport& r) { reports.push_back(r); };
  // A datagram cut short: its block claims more bytes than the datagram holds.
  decoder->feed(test::bytes_of(blocks[0].substr(0, blocks[0].size() - 5)), sink);
  EXPECT_TRUE(reports.empty());
  // The next datagram: a good block, then a header whose length runs past the end.
  decoder->feed(test::bytes_of(blocks[1] + std::string("\x3e\x01\x00\x00", 4)), sink);
  decoder->finish(sink);
  EXPECT_EQ(reports.size(), 2U);  // the two records of the good block
  EXPECT_EQ(decoder->rejections().count("asterix_bad_block_length"), 2U);
}

// ---- Resynchronisation -------------------------------------------------------------------

TEST(AsterixResync, RawBlocksSkipGarbageBeforeAndBetweenBlocks) {
  const std::string raw = raw_blocks_of_ff(fixture("jade/final_frame_062_first3min.ff"));
  const Decoded clean = decode(AsterixFraming::RawBlocks, raw);
  const auto blocks = split_blocks(raw);
  std::string dirty = garbage(41);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    dirty += blocks[i];
    if (i == 1000 || i == 2000) dirty += garbage(3 + i / 100);
  }
  const Decoded d = decode(AsterixFraming::RawBlocks, dirty);
  test::expect_same_reports(clean.reports, d.reports);
  Counts expected = clean.rejections;
  expected["asterix_resync"] = 3;  // one per run of garbage
  EXPECT_EQ(d.rejections, expected);
}

TEST(AsterixResync, RawBlocksRecoverFromACutBlockAndRandomGarbage) {
  const std::string raw = raw_blocks_of_ff(fixture("jade/final_frame_062_first3min.ff"));
  const Decoded clean = decode(AsterixFraming::RawBlocks, raw);
  const auto blocks = split_blocks(raw);
  std::mt19937 random(5);
  std::string dirty;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    if (i == 500) {
      dirty += blocks[i].substr(0, blocks[i].size() / 2);  // a block cut in half
    } else {
      dirty += blocks[i];
    }
    if (i == 1500) {
      for (int k = 0; k < 300; ++k) dirty += static_cast<char>(random());
    }
  }
  const Decoded d = decode(AsterixFraming::RawBlocks, dirty);
  EXPECT_GE(d.rejections.count("asterix_resync") ? d.rejections.at("asterix_resync") : 0, 2U);
  // Whatever the garbage swallowed, the decoder is back in step well before the end: the
  // last 1,000 reports are those of the clean stream.
  ASSERT_GT(d.reports.size(), 1000U);
  const std::vector<TrackReport> clean_tail(clean.reports.end() - 1000, clean.reports.end());
  const std::vector<TrackReport> tail(d.reports.end() - 1000, d.reports.end());
  test::expect_same_reports(clean_tail, tail);
  EXPECT_GT(d.reports.size(), clean.reports.size() - 10);
}

TEST(AsterixResync, FinalFormatSkipsGarbageBetweenFrames) {
  const std::string ff = fixture("jade/final_frame_062_first3min.ff");
  const Decoded clean = decode(AsterixFraming::FinalFormat, ff);
  // Garbage at the start, then between two frames in the middle.
  std::size_t middle = 0;
  for (int frames = 0; frames < 1500; ++frames) middle += be16(ff, middle);
  const std::string dirty = garbage(29) + ff.substr(0, middle) + garbage(50) + ff.substr(middle);
  const Decoded d = decode(AsterixFraming::FinalFormat, dirty);
  test::expect_same_reports(clean.reports, d.reports);
  Counts expected = clean.rejections;
  expected["asterix_resync"] = 2;
  EXPECT_EQ(d.rejections, expected);
}

TEST(AsterixResync, FinalFormatFrameWithoutTrailerIsSkipped) {
  const std::string ff = fixture("jade/final_frame_062_first3min.ff");
  const Decoded clean = decode(AsterixFraming::FinalFormat, ff);
  std::string dirty = ff;
  const std::size_t first = be16(ff, 0);
  dirty[first - 1] = '\x00';  // the first frame's trailer is damaged
  const Decoded d = decode(AsterixFraming::FinalFormat, dirty);
  ASSERT_EQ(d.reports.size() + 1, clean.reports.size());  // one record per frame
  test::expect_same_reports(std::vector<TrackReport>(clean.reports.begin() + 1, clean.reports.end()), d.reports);
  EXPECT_EQ(d.rejections.at("asterix_resync"), 1U);
}

TEST(AsterixResync, PcapSkipsGarbageBetweenRecords) {
  const std::string pcap = fixture("croatiacontrol/cat_034_048.pcap");
  const Decoded clean = decode(AsterixFraming::Pcap, pcap, croatia_radars());
  // After the global header and 10 records.
  std::size_t at = 24;
  for (int records = 0; records < 10; ++records) {
    at += 16 + (static_cast<std::uint8_t>(pcap[at + 8]) | static_cast<std::uint32_t>(static_cast<std::uint8_t>(pcap[at + 9])) << 8);
  }
  const std::string dirty = pcap.substr(0, at) + garbage(77) + pcap.substr(at);
  const Decoded d = decode(AsterixFraming::Pcap, dirty, croatia_radars());
  test::expect_same_reports(clean.reports, d.reports);
  Counts expected = clean.rejections;
  expected["pcap_resync"] = 1;
  EXPECT_EQ(d.rejections, expected);
}

TEST(AsterixResync, TruncatedTailIsCountedAtFinish) {
  const std::string raw = raw_blocks_of_ff(fixture("jade/final_frame_062_first3min.ff"));
  const auto blocks = split_blocks(raw);
  std::string cut;
  for (std::size_t i = 0; i < 10; ++i) cut += blocks[i];
  const Decoded whole = decode(AsterixFraming::RawBlocks, cut);
  const Decoded d = decode(AsterixFraming::RawBlocks, cut + blocks[10].substr(0, 9));
  test::expect_same_reports(whole.reports, d.reports);
  EXPECT_EQ(d.rejections.at("asterix_truncated"), 1U);
  const std::string ff = fixture("jade/final_frame_062_first3min.ff");
  const Decoded ff_cut = decode(AsterixFraming::FinalFormat, ff.substr(0, ff.size() - 3));
  EXPECT_EQ(ff_cut.rejections.at("asterix_truncated"), 1U);
  const std::string pcap = fixture("croatiacontrol/cat_062_065.pcap");
  const Decoded pcap_cut = decode(AsterixFraming::Pcap, pcap.substr(0, pcap.size() - 3));
  EXPECT_EQ(pcap_cut.rejections.at("asterix_truncated"), 1U);
}

TEST(AsterixResync, BlocksOfOtherCategoriesAreSkippedWholeAndCounted) {
  const std::string raw = fixture("croatiacontrol/cat034.raw") + fixture("asterix4py/cat062.ast") +
                          fixture("croatiacontrol/cat034.raw");
  const Decoded d = decode(AsterixFraming::RawBlocks, raw);
  EXPECT_EQ(d.reports.size(), 7U);
  EXPECT_EQ(d.rejections, (Counts{{"asterix_category_ignored", 2}}));
}

// ---- Pcap variants ----------------------------------------------------------------------------

/// A classic pcap file taken apart: link type, and per packet the timestamp and frame.
struct PcapFile {
  std::uint32_t link_type = 0;
  struct Packet {
    std::uint32_t seconds, microseconds;
    std::string frame;
  };
  std::vector<Packet> packets;
};

std::uint32_t le32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(s[at + static_cast<std::size_t>(i)]);
  return v;
}

PcapFile parse_pcap(const std::string& bytes) {
  EXPECT_EQ(le32(bytes, 0), 0xA1B2C3D4U) << "fixture expected little-endian, microseconds";
  PcapFile file;
  file.link_type = le32(bytes, 20);
  for (std::size_t at = 24; at + 16 <= bytes.size();) {
    const std::uint32_t captured = le32(bytes, at + 8);
    file.packets.push_back({le32(bytes, at), le32(bytes, at + 4), bytes.substr(at + 16, captured)});
    at += 16 + captured;
  }
  return file;
}

void put32(std::string& out, std::uint32_t v, bool big_endian) {
  for (int i = 0; i < 4; ++i) {
    const int shift = big_endian ? 8 * (3 - i) : 8 * i;
    out += static_cast<char>((v >> shift) & 0xFF);
  }
}

void put16(std::string& out, std::uint32_t v, bool big_endian) {
  if (big_endian) {
    out += static_cast<char>((v >> 8) & 0xFF);
    out += static_cast<char>(v & 0xFF);
  } else {
    out += static_cast<char>(v & 0xFF);
    out += static_cast<char>((v >> 8) & 0xFF);
  }
}

std::string write_pcap(const PcapFile& file, bool big_endian, bool nanoseconds) {
  std::string out;
  put32(out, nanoseconds ? 0xA1B23C4D : 0xA1B2C3D4, big_endian);
  put16(out, 2, big_endian);
  put16(out, 4, big_endian);
  put32(out, 0, big_endian);
  put32(out, 0, big_endian);
  put32(out, 262144, big_endian);
  put32(out, file.link_type, big_endian);
  for (const auto& p : file.packets) {
    put32(out, p.seconds, big_endian);
    put32(out, nanoseconds ? p.microseconds * 1000 : p.microseconds, big_endian);
    put32(out, static_cast<std::uint32_t>(p.frame.size()), big_endian);
    put32(out, static_cast<std::uint32_t>(p.frame.size()), big_endian);
    out += p.frame;
  }
  return out;
}

TEST(AsterixPcap, ByteOrdersAndTimestampResolutionsDecodeAlike) {
  const std::string original = fixture("croatiacontrol/cat_034_048.pcap");
  const PcapFile file = parse_pcap(original);
  ASSERT_EQ(file.link_type, 1U);
  const Decoded expected = decode(AsterixFraming::Pcap, original, croatia_radars());
  ASSERT_EQ(expected.reports.size(), 126U);
  for (const bool big_endian : {false, true}) {
    for (const bool nanoseconds : {false, true}) {
      SCOPED_TRACE(std::string(big_endian ? "big" : "little") + "-endian, " + (nanoseconds ? "ns" : "us"));
      const Decoded d = decode(AsterixFraming::Pcap, write_pcap(file, big_endian, nanoseconds), croatia_radars());
      test::expect_same_reports(expected.reports, d.reports);
      EXPECT_EQ(d.rejections, expected.rejections);
    }
  }
}

TEST(AsterixPcap, LinuxCookedAndRawIpLinkTypesDecodeAlike) {
  const std::string original = fixture("croatiacontrol/cat_034_048.pcap");
  const Decoded expected = decode(AsterixFraming::Pcap, original, croatia_radars());
  PcapFile cooked = parse_pcap(original);
  PcapFile raw_ip = cooked;
  cooked.link_type = 113;  // LINKTYPE_LINUX_SLL
  raw_ip.link_type = 101;  // LINKTYPE_RAW
  for (std::size_t i = 0; i < cooked.packets.size(); ++i) {
    const std::string ip = cooked.packets[i].frame.substr(14);
    // SLL: packet type, ARPHRD_ETHER, address length 6, 8 address bytes, protocol.
    cooked.packets[i].frame = std::string("\x00\x00\x00\x01\x00\x06", 6) + std::string(8, '\x42') +
                              std::string("\x08\x00", 2) + ip;
    raw_ip.packets[i].frame = ip;
  }
  for (const PcapFile* variant : {&cooked, &raw_ip}) {
    SCOPED_TRACE("link type " + std::to_string(variant->link_type));
    const Decoded d = decode(AsterixFraming::Pcap, write_pcap(*variant, false, false), croatia_radars());
    test::expect_same_reports(expected.reports, d.reports);
    EXPECT_EQ(d.rejections, expected.rejections);
  }
}

TEST(AsterixPcap, Ipv4FragmentsAreCountedAndSkipped) {
  PcapFile file = parse_pcap(fixture("croatiacontrol/cat_034_048.pcap"));
  const Decoded whole = decode(AsterixFraming::Pcap, write_pcap(file, false, false), croatia_radars());
  // Every packet flagged "more fragments", or given a fragment offset: not reassembled.
  for (std::size_t i = 0; i < file.packets.size(); ++i) {
    file.packets[i].frame[14 + 6] = static_cast<char>(file.packets[i].frame[14 + 6] | (i % 2 == 0 ? 0x20 : 0x01));
  }
  const Decoded d = decode(AsterixFraming::Pcap, write_pcap(file, false, false), croatia_radars());
  EXPECT_FALSE(whole.reports.empty());
  EXPECT_TRUE(d.reports.empty());
  EXPECT_EQ(d.rejections, (Counts{{"pcap_ip_fragment", file.packets.size()}}));
}

TEST(AsterixPcap, DayComesFromTheCaptureUnlessToldOtherwise) {
  const std::string pcap = fixture("croatiacontrol/cat_062_065.pcap");
  const Decoded from_capture = decode(AsterixFraming::Pcap, pcap);
  ASSERT_EQ(from_capture.reports.size(), 2U);
  EXPECT_DOUBLE_EQ(from_capture.reports[0].t, 1393332227.3984375);  // 2014-02-25, from tshark
  AsterixOptions options;
  options.day_from_pcap = false;
  options.day_start_utc_s = 1700000000 - 1700000000 % 86400;
  const Decoded from_option = decode(AsterixFraming::Pcap, pcap, options);
  ASSERT_EQ(from_option.reports.size(), 2U);
  EXPECT_DOUBLE_EQ(from_option.reports[0].t, options.day_start_utc_s + 1393332227.3984375 - 1393286400);
}

TEST(AsterixPcap, BadHeaderAndOversizedRecords) {
  const Decoded not_pcap = decode(AsterixFraming::Pcap, fixture("asterix4py/cat062.ast") + std::string(30, 'x'));
  EXPECT_TRUE(not_pcap.reports.empty());
  EXPECT_EQ(not_pcap.rejections, (Counts{{"pcap_bad_header", 1}}));
  // A record header announcing more than the 262,144-byte cap is garbage, not a reason to
  // buffer: the decoder skips it and finds the next record.
  const std::string pcap = fixture("croatiacontrol/cat_062_065.pcap");
  std::string huge_header;
  put32(huge_header, 1393332227, false);
  put32(huge_header, 0, false);
  put32(huge_header, 300000, false);
  put32(huge_header, 300000, false);
  const Decoded d = decode(AsterixFraming::Pcap, pcap.substr(0, 24) + huge_header + pcap.substr(24));
  EXPECT_EQ(d.reports.size(), 2U);
  EXPECT_EQ(d.rejections.at("pcap_resync"), 1U);
  EXPECT_EQ(make_asterix_decoder(AsterixFraming::Pcap)->max_message_bytes(), 262144U);
  EXPECT_EQ(make_asterix_decoder(AsterixFraming::RawBlocks)->max_message_bytes(), 65535U);
}

// ---- Auto-detection evidence ---------------------------------------------------------------

double confidence(AsterixFraming framing, const std::string& head) {
  return asterix_framing_confidence(framing, test::bytes_of(head));
}

TEST(AsterixConfidence, EachFramingRecognisesItsOwnFiles) {
  const std::string pcap = fixture("croatiacontrol/cat_034_048.pcap").substr(0, 4096);
  const std::string ff = fixture("jade/final_frame_062_first3min.ff").substr(0, 4096);
  const std::string raw = raw_blocks_of_ff(ff);
  const std::string text = "{\"t\":1714400000.25,\"id\":\"4CA123\",\"lat\":51.47,\"lon\":-0.45,\"alt_ft\":35000}\n";
  EXPECT_GT(confidence(AsterixFraming::Pcap, pcap), 0.9);
  EXPECT_GT(confidence(AsterixFraming::FinalFormat, ff), 0.9);
  EXPECT_GT(confidence(AsterixFraming::RawBlocks, raw), 0.8);
  // Each framing is the best explanation of its own files.
  EXPECT_LT(confidence(AsterixFraming::RawBlocks, pcap), confidence(AsterixFraming::Pcap, pcap));
  EXPECT_LT(confidence(AsterixFraming::RawBlocks, ff), confidence(AsterixFraming::FinalFormat, ff));
  EXPECT_LT(confidence(AsterixFraming::FinalFormat, raw), confidence(AsterixFraming::RawBlocks, raw));
  EXPECT_LT(confidence(AsterixFraming::Datagram, raw), confidence(AsterixFraming::RawBlocks, raw));
  for (const AsterixFraming framing : {AsterixFraming::RawBlocks, AsterixFraming::FinalFormat,
                                       AsterixFraming::Pcap, AsterixFraming::Datagram}) {
    EXPECT_LT(confidence(framing, text), 0.25);
    EXPECT_EQ(confidence(framing, ""), 0.0);
  }
}

TEST(AsterixFormatNames, AreStable) {
  EXPECT_EQ(make_asterix_decoder(AsterixFraming::RawBlocks)->format_name(), "asterix-raw");
  EXPECT_EQ(make_asterix_decoder(AsterixFraming::FinalFormat)->format_name(), "asterix-ff");
  EXPECT_EQ(make_asterix_decoder(AsterixFraming::Pcap)->format_name(), "asterix-pcap");
  EXPECT_EQ(make_asterix_decoder(AsterixFraming::Datagram)->format_name(), "asterix-datagram");
}

}  // namespace
}  // namespace kew::protocol
