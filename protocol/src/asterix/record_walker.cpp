#include "kew/protocol/asterix/record_walker.hpp"

#include <algorithm>

namespace kew::protocol::asterix {

namespace {

constexpr std::uint8_t kFx = 0x01;

/// Length of an FX-terminated bitmap (FSPEC or compound primary subfield) allowing at most
/// `max_bytes` bytes; 0 when it does not end within `available` bytes or `max_bytes`.
std::size_t bitmap_length(const std::uint8_t* data, std::size_t available, std::size_t max_bytes,
                          WalkError& error) {
  const std::size_t limit = std::min(available, max_bytes);
  for (std::size_t i = 0; i < limit; ++i) {
    if ((data[i] & kFx) == 0) return i + 1;
  }
  // Running past the block is an overflow; running past the profile announces items
  // that do not exist.
  error = available <= max_bytes ? WalkError::Overflow : WalkError::UnknownItem;
  return 0;
}

/// Bit of item `index` (0-based) in an FX-terminated bitmap.
bool bitmap_bit(const std::uint8_t* bitmap, std::size_t index) {
  return (bitmap[index / 7] & (0x80U >> (index % 7))) != 0;
}

ItemLength measure_extended(const ItemFormat& format, const std::uint8_t* data,
                            std::size_t available) {
  if (format.size == 0 || format.next_size == 0) return {0, WalkError::UnknownItem};
  std::size_t length = format.size;
  std::size_t parts = 1;
  while (true) {
    if (length > available) return {0, WalkError::Overflow};
    const bool more = (data[length - 1] & kFx) != 0;
    if (!more || (format.max_parts != 0 && parts == format.max_parts)) return {length, WalkError::None};
    length += format.next_size;
    ++parts;
  }
}

ItemLength measure_compound(const ItemFormat& format, const std::uint8_t* data,
                            std::size_t available) {
  const std::size_t subfields = format.subfields.size();
  WalkError error = WalkError::None;
  const std::size_t primary = bitmap_length(data, available, (subfields + 6) / 7, error);
  if (primary == 0) return {0, error};
  std::size_t length = primary;
  for (std::size_t index = 0; index < primary * 7; ++index) {
    if (!bitmap_bit(data, index)) continue;
    if (index >= subfields) return {0, WalkError::UnknownItem};
    const ItemLength sub = measure_item(format.subfields[index], data + length, available - length);
    if (sub.error != WalkError::None) return sub;
    length += sub.bytes;
  }
  return {length, WalkError::None};
}

}  // namespace

const char* walk_error_reason(WalkError error) {
  switch (error) {
    case WalkError::UnknownItem: return "asterix_unknown_item";
    case WalkError::Overflow: return "asterix_item_overflow";
    case WalkError::BadExplicitLength: return "asterix_bad_explicit_length";
    case WalkError::EmptyRecord: return "asterix_empty_record";
    case WalkError::None: break;
  }
  return "asterix_ok";
}

ItemLength measure_item(const ItemFormat& format, const std::uint8_t* data, std::size_t available) {
  switch (format.kind) {
    case ItemKind::Undefined:
      return {0, WalkError::UnknownItem};
    case ItemKind::Fixed:
      if (format.size > available) return {0, WalkError::Overflow};
      return {format.size, WalkError::None};
    case ItemKind::Extended:
      return measure_extended(format, data, available);
    case ItemKind::Repetitive: {
      if (available < 1) return {0, WalkError::Overflow};
      const std::size_t length = 1 + std::size_t{data[0]} * format.size;
      if (length > available) return {0, WalkError::Overflow};
      return {length, WalkError::None};
    }
    case ItemKind::Explicit: {
      if (available < 1) return {0, WalkError::Overflow};
      if (data[0] == 0) return {0, WalkError::BadExplicitLength};
      if (data[0] > available) return {0, WalkError::Overflow};
      return {data[0], WalkError::None};
    }
    case ItemKind::Compound:
      return measure_compound(format, data, available);
  }
  return {0, WalkError::UnknownItem};
}

std::span<const std::uint8_t> compound_subfield(const ItemFormat& format,
                                                std::span<const std::uint8_t> item,
                                                std::size_t index) {
  if (format.kind != ItemKind::Compound || index >= format.subfields.size()) return {};
  WalkError error = WalkError::None;
  const std::size_t primary =
      bitmap_length(item.data(), item.size(), (format.subfields.size() + 6) / 7, error);
  if (primary == 0 || index >= primary * 7 || !bitmap_bit(item.data(), index)) return {};
  std::size_t offset = primary;
  for (std::size_t i = 0; i <= index; ++i) {
    if (!bitmap_bit(item.data(), i)) continue;
    const ItemLength sub =
        measure_item(format.subfields[i], item.data() + offset, item.size() - offset);
    if (sub.error != WalkError::None) return {};
    if (i == index) return item.subspan(offset, sub.bytes);
    offset += sub.bytes;
  }
  return {};
}

RecordWalk walk_record(const Uap& uap, const std::uint8_t* record, std::size_t available,
                       RecordItems& items) {
  const std::size_t frns = std::min<std::size_t>(uap.items.size(), RecordItems::kMaxFrn);
  WalkError error = WalkError::None;
  const std::size_t fspec = bitmap_length(record, available, (frns + 6) / 7, error);
  if (fspec == 0) return {0, error, 0};

  items.base_ = record;
  items.present_ = 0;
  std::size_t length = fspec;
  for (std::size_t index = 0; index < fspec * 7; ++index) {
    if (!bitmap_bit(record, index)) continue;
    const auto frn = static_cast<unsigned>(index + 1);
    if (index >= frns) return {0, WalkError::UnknownItem, frn};
    const ItemLength item = measure_item(uap.items[index], record + length, available - length);
    if (item.error != WalkError::None) return {0, item.error, frn};
    items.present_ |= std::uint64_t{1} << frn;
    items.offset_[frn] = static_cast<std::uint16_t>(length);
    items.length_[frn] = static_cast<std::uint16_t>(item.bytes);
    length += item.bytes;
  }
  if (items.present_ == 0) return {0, WalkError::EmptyRecord, 0};
  return {length, WalkError::None, 0};
}

bool is_zero_padding(const std::uint8_t* bytes, std::size_t size) {
  return std::all_of(bytes, bytes + size, [](std::uint8_t b) { return b == 0; });
}

}  // namespace kew::protocol::asterix
