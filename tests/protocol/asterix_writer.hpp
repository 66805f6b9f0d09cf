#pragma once
// A test-only ASTERIX writer: records built item by item, data blocks, compound items, and
// minimal records each decoder accepts, to which a test adds the items it is about.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "kew/protocol/asterix/uap.hpp"

namespace kew::protocol::asterix_writer {

using Bytes = std::vector<std::uint8_t>;

inline void put(Bytes& out, std::uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

/// One record: items by FRN, written in FRN order after an FSPEC that announces them.
class RecordWriter {
 public:
  void set(unsigned frn, Bytes item) { items_[frn] = std::move(item); }

  Bytes bytes() const {
    unsigned last = 0;
    for (const auto& [frn, item] : items_) last = std::max(last, frn);
    const unsigned fspec_bytes = (last + 6) / 7;
    Bytes out(fspec_bytes, 0);
    for (const auto& [frn, item] : items_) {
      out[(frn - 1) / 7] |= static_cast<std::uint8_t>(0x80U >> ((frn - 1) % 7));
    }
    for (unsigned i = 0; i + 1 < fspec_bytes; ++i) out[i] |= 0x01;  // FX
    for (const auto& [frn, item] : items_) out.insert(out.end(), item.begin(), item.end());
    return out;
  }

 private:
  std::map<unsigned, Bytes> items_;
};

inline Bytes data_block(std::uint8_t category, const std::vector<Bytes>& records) {
  Bytes body;
  for (const Bytes& r : records) body.insert(body.end(), r.begin(), r.end());
  Bytes block{category};
  put(block, body.size() + 3, 2);
  block.insert(block.end(), body.begin(), body.end());
  return block;
}

/// A compound item announcing subfields `present` (0-based) with the given contents.
inline Bytes compound_item(const std::map<unsigned, Bytes>& present) {
  unsigned last = 0;
  for (const auto& [index, sub] : present) last = std::max(last, index + 1);
  const unsigned primary = std::max(1U, (last + 6) / 7);
  Bytes out(primary, 0);
  for (const auto& [index, sub] : present) out[index / 7] |= static_cast<std::uint8_t>(0x80U >> (index % 7));
  for (unsigned i = 0; i + 1 < primary; ++i) out[i] |= 0x01;
  for (const auto& [index, sub] : present) out.insert(out.end(), sub.begin(), sub.end());
  return out;
}

inline std::int64_t quantize(double value, double lsb) { return std::llround(value / lsb); }

/// Decodes `stream` (data blocks) as one datagram: every block is decoded, whatever it holds.
inline std::vector<TrackReport> decode_bytes(const Bytes& stream,
                                             const AsterixOptions& options = {},
                                             Rejections* rejections = nullptr) {
  auto decoder = make_asterix_decoder(AsterixFraming::Datagram, options);
  std::vector<TrackReport> reports;
  const ReportSink sink = [&](const TrackReport& r) { reports.push_back(r); };
  decoder->feed(std::as_bytes(std::span<const std::uint8_t>(stream)), sink);
  decoder->finish(sink);
  if (rejections != nullptr) rejections->merge(decoder->rejections());
  return reports;
}

/// A minimal CAT062 record of SAC/SIC 25/100 that the decoder accepts: time of day
/// `tod_lsb` (1/128 s), a WGS-84 position, FL350, and the track number if given.
inline RecordWriter minimal_cat062(std::uint32_t tod_lsb,
                                   std::optional<std::uint16_t> track_number) {
  using namespace asterix::cat062;
  RecordWriter w;
  w.set(kDataSource, {25, 100});
  Bytes tod;
  put(tod, tod_lsb, 3);
  w.set(kTimeOfTrack, tod);
  Bytes position;
  put(position, static_cast<std::uint32_t>(quantize(51.47, 180.0 / 33554432.0)), 4);
  put(position, static_cast<std::uint32_t>(quantize(-0.45, 180.0 / 33554432.0)), 4);
  w.set(kPositionWgs84, position);
  w.set(kMeasuredFl, {0x05, 0x78});  // 1400 quarter FL = FL350
  if (track_number) {
    Bytes number;
    put(number, *track_number, 2);
    w.set(kTrackNumber, number);
  }
  return w;
}

/// A minimal CAT048 record of radar 25/7 that the decoder accepts (a plot at 50 NM, FL200),
/// with the track number and address if given.
inline RecordWriter minimal_cat048(std::optional<std::uint16_t> track_number,
                                   std::optional<std::uint32_t> address) {
  using namespace asterix::cat048;
  RecordWriter w;
  w.set(kDataSource, {25, 7});
  w.set(kTimeOfDay, {0x10, 0x00, 0x00});
  w.set(kPolarPosition, {0x32, 0x00, 0x40, 0x00});  // RHO 50 NM, THETA 90 deg
  w.set(kFlightLevel, {0x03, 0x20});                 // 800 quarter FL = FL200
  if (track_number) {
    Bytes number;
    put(number, *track_number, 2);
    w.set(kTrackNumber, number);
  }
  if (address) {
    Bytes bytes;
    put(bytes, *address, 3);
    w.set(kAddress, bytes);
  }
  return w;
}

inline AsterixOptions radar_25_7() {
  AsterixOptions options;
  options.radars.push_back({25, 7, 47.45, 8.56, 500.0});
  return options;
}

/// Decodes `records` of `category` as one block (CAT048 of radar 25/7); every record must
/// give a report, nothing counted.
inline std::vector<TrackReport> decode_every_record(std::uint8_t category,
                                                    const std::vector<Bytes>& records) {
  Rejections rejections;
  auto reports = decode_bytes(data_block(category, records), radar_25_7(), &rejections);
  EXPECT_EQ(rejections.total(), 0U);
  EXPECT_EQ(reports.size(), records.size());
  return reports;
}

}  // namespace kew::protocol::asterix_writer
