#pragma once
// Finds a track's slot from its (source, id) without a second copy of either string:
// an open-addressing table (linear probing, backward-shift deletion) of 8-byte buckets
// holding a 32-bit hash of the key and the slot. The strings themselves live in the
// track table; a lookup compares them only for buckets whose hash matches. A node-based
// map would cost ~70 bytes per track (node, key copy, bucket pointer); this costs 16 at
// the maximum load of one half.

#include <cstdint>
#include <string_view>
#include <vector>

namespace kew::track {

class TrackIndex {
 public:
  using Slot = std::uint32_t;
  static constexpr Slot kAbsent = ~Slot{0};

  /// The hash under which (source, id) is stored; a function of the bytes alone.
  static std::uint32_t hash(std::string_view source, std::string_view id);

  /// The slot stored under `hash` for which `is_key(slot)` is true, or kAbsent.
  template <class IsKey>
  Slot find(std::uint32_t hash, IsKey&& is_key) const {
    if (buckets_.empty()) return kAbsent;
    for (std::size_t i = hash & mask_;; i = (i + 1) & mask_) {
      const Bucket& b = buckets_[i];
      if (b.slot == kAbsent) return kAbsent;
      if (b.hash == hash && is_key(b.slot)) return b.slot;
    }
  }

  /// Stores slot under hash. The caller guarantees that no stored slot has the same key.
  void insert(std::uint32_t hash, Slot slot);
  /// Removes the bucket holding exactly (hash, slot); false when there is none.
  bool erase(std::uint32_t hash, Slot slot);

  std::size_t size() const { return size_; }
  /// Buckets allocated (a power of two, at least twice size(), or 0).
  std::size_t capacity() const { return buckets_.size(); }
  /// Every stored bucket is reachable from its home position without crossing an empty
  /// bucket (what find() relies on), and size() counts the stored buckets.
  bool is_valid() const;

 private:
  struct Bucket {
    std::uint32_t hash = 0;
    Slot slot = kAbsent;
  };
  void grow();
  void place(Bucket b);

  std::vector<Bucket> buckets_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

}  // namespace kew::track
