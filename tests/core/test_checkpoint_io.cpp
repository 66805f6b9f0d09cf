// The byte form of a checkpoint (design §5.9): every value back as written, bit for bit;
// every truncation and malformed value refused with its offset.
#include "kew/util/checkpoint_io.hpp"

#include <cmath>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

namespace kew::util {
namespace {

std::uint64_t bits_of(double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

TEST(CheckpointIo, EveryValueReadsBackAsWritten) {
  const double doubles[] = {0.0, -0.0, 1.0 / 3.0, -1e-310, std::numeric_limits<double>::infinity(),
                            -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::max()};
  CheckpointWriter out;
  out.tag("section");
  out.u8(0xfe);
  out.u16(0xbeef);
  out.u32(0xdeadbeef);
  out.u64(0x0123456789abcdefULL);
  out.i32(-42);
  for (const double d : doubles) out.f64(d);
  out.boolean(true);
  out.boolean(false);
  out.text("");
  out.text(std::string("a\0b", 3));
  out.optional(std::optional<double>{}, [&](double v) { out.f64(v); });
  out.optional(std::optional<double>{2.5}, [&](double v) { out.f64(v); });

  CheckpointReader in(out.bytes());
  in.tag("section");
  EXPECT_EQ(in.u8(), 0xfe);
  EXPECT_EQ(in.u16(), 0xbeef);
  EXPECT_EQ(in.u32(), 0xdeadbeefu);
  EXPECT_EQ(in.u64(), 0x0123456789abcdefULL);
  EXPECT_EQ(in.i32(), -42);
  for (const double d : doubles) EXPECT_EQ(bits_of(in.f64()), bits_of(d));
  EXPECT_TRUE(in.boolean());
  EXPECT_FALSE(in.boolean());
  EXPECT_EQ(in.text(), "");
  EXPECT_EQ(in.text(), std::string("a\0b", 3));
  EXPECT_FALSE(in.optional<double>([&] { return in.f64(); }));
  EXPECT_EQ(in.optional<double>([&] { return in.f64(); }), 2.5);
  EXPECT_TRUE(in.at_end());
}

TEST(CheckpointIo, IntegersAreLittleEndianWhateverTheMachine) {
  CheckpointWriter out;
  out.u32(0x04030201);
  EXPECT_EQ(out.bytes(), std::string("\x01\x02\x03\x04", 4));
}

TEST(CheckpointIo, ATruncationIsRefusedAtItsOffset) {
  CheckpointWriter out;
  out.u64(7);
  out.text("twelve bytes");
  for (std::size_t size = 0; size < out.bytes().size(); ++size) {
    CheckpointReader in(std::string_view(out.bytes()).substr(0, size));
    EXPECT_THROW(
        {
          in.u64();
          in.text();
        },
        CheckpointError)
        << size;
  }
  CheckpointReader in(std::string_view(out.bytes()).substr(0, 10));
  in.u64();
  try {
    in.text();
    FAIL();
  } catch (const CheckpointError& e) {
    EXPECT_STREQ(e.what(), "checkpoint byte 8: truncated");
  }
}

TEST(CheckpointIo, MalformedValuesAreRefused) {
  enum class Colour : std::uint8_t { Red, Green, Blue };
  CheckpointWriter out;
  out.u8(2);  // a boolean
  out.u8(3);  // a Colour
  out.tag("tracks");
  CheckpointReader in(out.bytes());
  EXPECT_THROW(in.boolean(), CheckpointError);
  EXPECT_THROW(in.enumeration(Colour::Blue), CheckpointError);
  EXPECT_THROW(in.tag("alerts"), CheckpointError);
}

}  // namespace
}  // namespace kew::util
