// GzipDecoder: streaming inflate in front of any decoder, concatenated members, and every
// way a compressed stream goes wrong.
#include <gtest/gtest.h>

#include "kew/protocol/gzip.hpp"
#include "kew/protocol/ndjson.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;
using test::gzip_member;

std::string canonical_lines(int count) {
  std::string text;
  for (int i = 0; i < count; ++i)
    text += "{\"t\":" + std::to_string(1000 + i) + ",\"id\":\"A" + std::to_string(i % 50) +
            "\",\"lat\":51.5,\"lon\":-0.1,\"alt_ft\":" + std::to_string(1000 + i % 300) + "}\n";
  return text;
}

std::unique_ptr<Decoder> gzip_ndjson(GzipMode mode = GzipMode::WhenMagic) {
  return make_gzip_decoder(make_ndjson_decoder(), mode);
}

TEST(GzipDecoder, InflatesToTheSameReportsAsThePlainText) {
  const std::string plain = canonical_lines(3000);
  auto plain_decoder = make_ndjson_decoder();
  const auto expected = decode_all(*plain_decoder, plain);
  ASSERT_EQ(expected.size(), 3000u);
  auto decoder = gzip_ndjson();
  test::expect_same_reports(expected, decode_all(*decoder, gzip_member(plain)));
  EXPECT_EQ(decoder->rejections().total(), 0u);
  EXPECT_EQ(decoder->format_name(), "ndjson");
  EXPECT_EQ(decoder->max_message_bytes(), 4096u);
}

TEST(GzipDecoder, HighlyCompressedInputLargerThanTheOutputBuffer) {
  // ~1.3 MB of identical lines deflate to a few KB: one small input produces many
  // output buffers.
  std::string plain;
  for (int i = 0; i < 20000; ++i) plain += "{\"t\":1,\"id\":\"A\",\"lat\":1,\"lon\":2,\"alt_ft\":3}\n";
  const std::string compressed = gzip_member(plain, 9);
  ASSERT_LT(compressed.size(), 20000u);
  auto decoder = gzip_ndjson();
  EXPECT_EQ(decode_all(*decoder, compressed).size(), 20000u);
}

TEST(GzipDecoder, ConcatenatedMembersAreDecodedInOrder) {
  const std::string plain = canonical_lines(900);
  // Cut inside lines, so a line spans two members.
  const std::string stream = gzip_member(plain.substr(0, 10001)) +
                             gzip_member(plain.substr(10001, 7)) + gzip_member("") +
                             gzip_member(plain.substr(10008));
  auto plain_decoder = make_ndjson_decoder();
  const auto expected = decode_all(*plain_decoder, plain);
  auto decoder = gzip_ndjson();
  test::expect_same_reports(expected, decode_all(*decoder, stream));
  EXPECT_EQ(decoder->rejections().total(), 0u);
  test::expect_incremental([] { return gzip_ndjson(); }, stream);
}

TEST(GzipDecoder, PlainInputPassesThroughWhenMagicIsAbsent) {
  const std::string plain = canonical_lines(10);
  auto decoder = gzip_ndjson(GzipMode::WhenMagic);
  EXPECT_EQ(decode_all(*decoder, plain).size(), 10u);
  // One byte of input: too short for the magic, still passed on at finish().
  auto tiny = make_gzip_decoder(make_ndjson_decoder());
  decode_all(*tiny, "x");
  EXPECT_EQ(tiny->rejections().count("truncated"), 1u);
  test::expect_incremental([] { return gzip_ndjson(); }, plain);
}

TEST(GzipDecoder, AlwaysModeRefusesPlainInput) {
  auto decoder = gzip_ndjson(GzipMode::Always);
  EXPECT_TRUE(decode_all(*decoder, canonical_lines(10)).empty());
  EXPECT_EQ(decoder->rejections().count("gzip_corrupt"), 1u);
  EXPECT_EQ(decoder->rejections().total(), 1u);
}

TEST(GzipDecoder, InnerRejectionsAppearOnTheWrapperWithTheirMessages) {
  auto decoder = gzip_ndjson();
  std::vector<std::string> messages;
  decoder->rejections().set_reporter(
      [&](std::string_view, std::string_view message) { messages.emplace_back(message); });
  const auto reports = decode_all(*decoder, gzip_member("not json\n" + canonical_lines(2)));
  EXPECT_EQ(reports.size(), 2u);
  EXPECT_EQ(decoder->rejections().count("bad_json"), 1u);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_NE(messages[0].find("ndjson line 1"), std::string::npos) << messages[0];
}

TEST(GzipDecoder, CorruptDataStopsTheStreamCleanlyUntilFinish) {
  const std::string plain = canonical_lines(2000);
  std::string compressed = gzip_member(plain);
  for (std::size_t i = compressed.size() / 2; i < compressed.size() / 2 + 16; ++i)
    compressed[i] = static_cast<char>(compressed[i] ^ 0x5a);
  auto decoder = gzip_ndjson();
  std::vector<TrackReport> reports;
  const ReportSink sink = [&](const TrackReport& r) { reports.push_back(r); };
  decoder->feed_text(compressed, sink);
  decoder->feed_text(gzip_member(plain), sink);  // ignored: the stream is stopped
  decoder->finish(sink);
  EXPECT_EQ(decoder->rejections().count("gzip_corrupt"), 1u);
  // Deflate data carries no check before the member's CRC: bytes inflated between the
  // damage and its detection may be wrong. Those before the damage are intact.
  ASSERT_GE(reports.size(), 500u);
  for (std::size_t i = 0; i < 500; ++i) EXPECT_EQ(reports[i].t, 1000.0 + static_cast<double>(i));
  // After finish() the decoder takes a new stream.
  EXPECT_EQ(decode_all(*decoder, gzip_member(plain)).size(), 2000u);
}

TEST(GzipDecoder, BadCrcIsCorrupt) {
  std::string compressed = gzip_member(canonical_lines(5));
  compressed[compressed.size() - 8] = static_cast<char>(compressed[compressed.size() - 8] ^ 1);
  auto decoder = gzip_ndjson();
  EXPECT_EQ(decode_all(*decoder, compressed).size(), 5u);  // the data came before the check
  EXPECT_EQ(decoder->rejections().count("gzip_corrupt"), 1u);
}

TEST(GzipDecoder, TruncatedStreamIsCountedAtFinish) {
  const std::string compressed = gzip_member(canonical_lines(500));
  auto decoder = gzip_ndjson();
  const auto reports = decode_all(*decoder, compressed.substr(0, compressed.size() - 100));
  EXPECT_LT(reports.size(), 500u);
  EXPECT_EQ(decoder->rejections().count("gzip_truncated"), 1u);
  EXPECT_EQ(decoder->rejections().count("gzip_corrupt"), 0u);
}

TEST(GzipDecoder, TrailingGarbageAfterTheLastMemberIsCountedOnce) {
  const std::string stream = gzip_member(canonical_lines(20)) + std::string(512, '\0') + "junk";
  auto decoder = gzip_ndjson();
  EXPECT_EQ(decode_all(*decoder, stream).size(), 20u);
  EXPECT_EQ(decoder->rejections().count("gzip_trailing_garbage"), 1u);
  EXPECT_EQ(decoder->rejections().total(), 1u);
  test::expect_incremental([] { return gzip_ndjson(); }, stream);
}

TEST(GzipPrefix, InflatesTheStartOfATruncatedStream) {
  const std::string plain = canonical_lines(1000);
  const std::string compressed = gzip_member(plain);
  const auto head = gunzip_prefix(test::bytes_of(compressed).subspan(0, compressed.size() / 3), 4096);
  ASSERT_GT(head.size(), 100u);
  EXPECT_LE(head.size(), 4096u);
  EXPECT_EQ(std::string_view(reinterpret_cast<const char*>(head.data()), head.size()),
            std::string_view(plain).substr(0, head.size()));
  EXPECT_TRUE(has_gzip_magic(test::bytes_of(compressed)));
  EXPECT_FALSE(has_gzip_magic(test::bytes_of(plain)));
  EXPECT_TRUE(gunzip_prefix(test::bytes_of(plain), 100).empty());
}

}  // namespace
}  // namespace kew::protocol
