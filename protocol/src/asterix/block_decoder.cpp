#include "block_decoder.hpp"

#include <array>

#include "bytes.hpp"
#include "kew/protocol/asterix/uap.hpp"

namespace kew::protocol::asterix {

namespace {

constexpr std::size_t kBlockHeaderBytes = 3;

/// Categories listed by EUROCONTROL (ASTERIX categories page, 2023), civil and military.
constexpr std::array<bool, 256> kAssigned = [] {
  std::array<bool, 256> assigned{};
  for (const int c : {1,   2,   3,   4,   7,   8,   9,   10,  11,  15,  16,  17,  18,
                      19,  20,  21,  22,  23,  24,  25,  30,  31,  32,  34,  48,  62,
                      63,  65,  150, 151, 152, 205, 238, 240, 247, 252}) {
    assigned[static_cast<std::size_t>(c)] = true;
  }
  return assigned;
}();

}  // namespace

bool is_assigned_category(std::uint8_t category) { return kAssigned[category]; }

bool is_decoded_category(std::uint8_t category) {
  return category == 21 || category == 48 || category == 62;
}

BlockDecoder::BlockDecoder(const AsterixOptions& options, Rejections& rejections)
    : rejections_(rejections), clock_(options.day_start_utc_s), radars_(options.radars) {}

void BlockDecoder::decode_block(const std::uint8_t* block, std::size_t size, const ReportSink& sink) {
  switch (block[0]) {
    case 62:
      decode_records(cat062_uap(), decode_cat062, block, size, sink);
      return;
    case 48:
      decode_records(cat048_uap(), decode_cat048, block, size, sink);
      return;
    case 21:
      if (block_is_cat021_v026(block, size)) {
        decode_records(cat021_v026_uap(), decode_cat021_v026, block, size, sink);
      } else {
        decode_records(cat021_uap(), decode_cat021, block, size, sink);
      }
      return;
    default:
      if (is_assigned_category(block[0])) {
        rejections_.reject("asterix_category_ignored", "data block of a category kew does not decode");
      } else {
        rejections_.reject("asterix_unknown_category", "data block of an unassigned category");
      }
  }
}

void BlockDecoder::decode_blocks(const std::uint8_t* payload, std::size_t size,
                                 const ReportSink& sink) {
  std::size_t offset = 0;
  while (offset < size) {
    const std::size_t remaining = size - offset;
    const std::size_t length = remaining >= kBlockHeaderBytes ? be16(payload + offset + 1) : 0;
    if (length < kBlockHeaderBytes || length > remaining) {
      rejections_.reject("asterix_bad_block_length", "data block length does not fit its container");
      return;
    }
    decode_block(payload + offset, length, sink);
    offset += length;
  }
}

void BlockDecoder::decode_records(const Uap& uap,
                                  bool (*decode)(const RecordItems&, RecordContext&, TrackReport&),
                                  const std::uint8_t* block, std::size_t size,
                                  const ReportSink& sink) {
  RecordContext context{rejections_, clock_, radars_};
  std::size_t offset = kBlockHeaderBytes;
  while (offset < size) {
    const std::uint8_t* record = block + offset;
    const std::size_t remaining = size - offset;
    if (is_zero_padding(record, remaining)) return;
    const RecordWalk walk = walk_record(uap, record, remaining, items_);
    if (walk.error != WalkError::None) {
      // Without the length of this record the rest of the block cannot be found.
      rejections_.reject(walk_error_reason(walk.error), "record cannot be walked; rest of block skipped");
      return;
    }
    reset_report(report_);
    if (decode(items_, context, report_)) sink(report_);
    offset += walk.bytes;
  }
}

bool BlockDecoder::records_fit(const Uap& uap, const std::uint8_t* block, std::size_t size) {
  std::size_t offset = kBlockHeaderBytes;
  bool any_record = false;
  while (offset < size) {
    if (is_zero_padding(block + offset, size - offset)) break;
    const RecordWalk walk = walk_record(uap, block + offset, size - offset, items_);
    if (walk.error != WalkError::None || !items_.has(1)) return false;
    offset += walk.bytes;
    any_record = true;
  }
  return any_record;
}

bool BlockDecoder::block_is_cat021_v026(const std::uint8_t* block, std::size_t size) {
  // Short 0.26 records can happen to walk under 2.x as several records without I021/010:
  // a profile fits only when every record carries it.
  return !records_fit(cat021_uap(), block, size) && records_fit(cat021_v026_uap(), block, size);
}

bool BlockDecoder::walks_cleanly(const std::uint8_t* block, std::size_t size) {
  switch (block[0]) {
    case 62: return records_fit(cat062_uap(), block, size);
    case 48: return records_fit(cat048_uap(), block, size);
    case 21: return records_fit(cat021_uap(), block, size) || records_fit(cat021_v026_uap(), block, size);
    default: return false;
  }
}

}  // namespace kew::protocol::asterix
