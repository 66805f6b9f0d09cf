#pragma once
// Walks one ASTERIX record: the FSPEC (7 field reference numbers per byte, FX in the
// least significant bit) and then each announced item, measured by the category's UAP.
// The walk records where each item lies; it does not interpret them.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "kew/protocol/asterix/item_format.hpp"

namespace kew::protocol::asterix {

/// A User Application Profile: the item format at each field reference number.
/// items[0] is FRN 1.
struct Uap {
  std::span<const ItemFormat> items;
};

struct RecordWalk;

/// Where each item of one walked record lies. FRNs are 1-based as in the specifications.
class RecordItems {
 public:
  /// The largest FRN a record may announce (8 FSPEC bytes of 7 FRNs each).
  static constexpr unsigned kMaxFrn = 56;

  bool has(unsigned frn) const { return frn <= kMaxFrn && ((present_ >> frn) & 1U) != 0; }
  /// The bytes of item `frn`; empty when the item is absent.
  std::span<const std::uint8_t> item(unsigned frn) const {
    if (!has(frn)) return {};
    return {base_ + offset_[frn], length_[frn]};
  }
  /// Pointer to item `frn`, which must be present (check has() first).
  const std::uint8_t* data(unsigned frn) const { return base_ + offset_[frn]; }

 private:
  friend RecordWalk walk_record(const Uap& uap, const std::uint8_t* record, std::size_t available,
                                RecordItems& items);
  std::uint64_t present_ = 0;
  const std::uint8_t* base_ = nullptr;
  std::array<std::uint16_t, kMaxFrn + 1> offset_{};
  std::array<std::uint16_t, kMaxFrn + 1> length_{};
};

struct RecordWalk {
  std::size_t bytes = 0;  ///< Length of the record (FSPEC and items), bytes.
  WalkError error = WalkError::None;
  unsigned frn = 0;       ///< The FRN at which the walk failed (0: in the FSPEC).
};

/// Walks the record at `record`, of which `available` bytes (≤ 65,535) remain in the data
/// block, filling `items`. On error, `items` is unspecified.
RecordWalk walk_record(const Uap& uap, const std::uint8_t* record, std::size_t available,
                       RecordItems& items);

/// True when `bytes` are all zero: trailing padding some systems add to a data block,
/// which is not a record.
bool is_zero_padding(const std::uint8_t* bytes, std::size_t size);

}  // namespace kew::protocol::asterix
