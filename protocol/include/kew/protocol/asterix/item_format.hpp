#pragma once
// Building blocks of the ASTERIX record reader: how long a data item is.
// A record can only be walked if the length of every item its FSPEC announces is known,
// so each category's UAP lists a format for every item, used or not
// (EUROCONTROL "ASTERIX Part 1", §4.3: fixed, extended, repetitive, explicit, compound).

#include <cstddef>
#include <cstdint>
#include <span>

namespace kew::protocol::asterix {

enum class ItemKind : std::uint8_t {
  /// Not defined at this position (spare FRN or spare subfield): a record announcing it
  /// cannot be walked.
  Undefined,
  /// Always `size` bytes.
  Fixed,
  /// A first part of `size` bytes then parts of `next_size` bytes while the last bit
  /// of the part just read (FX) is 1; at most `max_parts` parts (0: no limit).
  /// Also covers FX-terminated repetitive items (I048/030, I062/510).
  Extended,
  /// One byte REP, then REP elements of `size` bytes.
  Repetitive,
  /// One byte LEN counting itself, then LEN - 1 bytes (RE and SP fields).
  Explicit,
  /// A primary subfield (FX-extended bitmap, 7 subfields per byte, first subfield in the
  /// most significant bit) followed by the subfields it announces, in order.
  Compound,
};

struct ItemFormat {
  ItemKind kind = ItemKind::Undefined;
  std::uint8_t size = 0;
  std::uint8_t next_size = 0;
  std::uint8_t max_parts = 0;
  std::span<const ItemFormat> subfields{};
};

constexpr ItemFormat undefined_item() { return {}; }
constexpr ItemFormat fixed(std::uint8_t bytes) { return {ItemKind::Fixed, bytes, 0, 0, {}}; }
constexpr ItemFormat extended(std::uint8_t first = 1, std::uint8_t next = 1,
                              std::uint8_t max_parts = 0) {
  return {ItemKind::Extended, first, next, max_parts, {}};
}
constexpr ItemFormat repetitive(std::uint8_t element_bytes) {
  return {ItemKind::Repetitive, element_bytes, 0, 0, {}};
}
constexpr ItemFormat explicit_length() { return {ItemKind::Explicit, 0, 0, 0, {}}; }
constexpr ItemFormat compound(std::span<const ItemFormat> subfields) {
  return {ItemKind::Compound, 0, 0, 0, subfields};
}

enum class WalkError : std::uint8_t {
  None,
  /// An FSPEC or compound primary subfield announces an undefined item or subfield.
  UnknownItem,
  /// The item (or the FSPEC) runs past the end of the data block.
  Overflow,
  /// An explicit item's length byte is 0.
  BadExplicitLength,
  /// The record's FSPEC announces nothing (and is not trailing zero padding).
  EmptyRecord,
};

/// The stable rejection reason for a walk error ("asterix_unknown_item", ...).
const char* walk_error_reason(WalkError error);

struct ItemLength {
  std::size_t bytes = 0;  ///< Length of the item, bytes (> 0 when error is None).
  WalkError error = WalkError::None;
};

/// Length of the item of format `format` that starts at `data`, of which `available`
/// bytes remain in the data block. Never reads past data + available.
ItemLength measure_item(const ItemFormat& format, const std::uint8_t* data, std::size_t available);

/// Subfield `index` (0-based, in UAP order) of a compound item `item` whose format is
/// `format`; empty when the subfield is absent or the item is malformed.
std::span<const std::uint8_t> compound_subfield(const ItemFormat& format,
                                                std::span<const std::uint8_t> item,
                                                std::size_t index);

}  // namespace kew::protocol::asterix
