#include "kew/track/track_index.hpp"

#include <functional>

namespace kew::track {

std::uint32_t TrackIndex::hash(std::string_view source, std::string_view id) {
  const std::uint64_t hs = std::hash<std::string_view>{}(source);
  const std::uint64_t hi = std::hash<std::string_view>{}(id);
  // Mix so that (a, b) and (b, a) differ and both halves reach the low bits, which
  // choose the bucket.
  std::uint64_t h = hi ^ (hs * 0x9e3779b97f4a7c15ULL + 0x7f4a7c159e3779b9ULL + (hi << 6) + (hi >> 2));
  h ^= h >> 32;
  return static_cast<std::uint32_t>(h);
}

void TrackIndex::place(Bucket b) {
  std::size_t i = b.hash & mask_;
  while (buckets_[i].slot != kAbsent) i = (i + 1) & mask_;
  buckets_[i] = b;
}

void TrackIndex::grow() {
  std::vector<Bucket> old(buckets_.empty() ? 16 : 2 * buckets_.size());
  old.swap(buckets_);
  mask_ = buckets_.size() - 1;
  for (const Bucket& b : old)
    if (b.slot != kAbsent) place(b);
}

void TrackIndex::insert(std::uint32_t hash, Slot slot) {
  if (2 * (size_ + 1) > buckets_.size()) grow();
  place({hash, slot});
  ++size_;
}

bool TrackIndex::erase(std::uint32_t hash, Slot slot) {
  if (buckets_.empty()) return false;
  std::size_t hole = hash & mask_;
  while (!(buckets_[hole].slot == slot && buckets_[hole].hash == hash)) {
    if (buckets_[hole].slot == kAbsent) return false;
    hole = (hole + 1) & mask_;
  }
  // Backward shift: pull later members of the run into the hole when their home
  // position does not lie cyclically in (hole, j], so no tombstones are needed.
  for (std::size_t j = (hole + 1) & mask_; buckets_[j].slot != kAbsent; j = (j + 1) & mask_) {
    const std::size_t home = buckets_[j].hash & mask_;
    const bool home_in_gap = hole <= j ? (home > hole && home <= j) : (home > hole || home <= j);
    if (home_in_gap) continue;
    buckets_[hole] = buckets_[j];
    hole = j;
  }
  buckets_[hole] = Bucket{};
  --size_;
  return true;
}

bool TrackIndex::is_valid() const {
  std::size_t stored = 0;
  for (std::size_t i = 0; i < buckets_.size(); ++i) {
    if (buckets_[i].slot == kAbsent) continue;
    ++stored;
    for (std::size_t k = buckets_[i].hash & mask_; k != i; k = (k + 1) & mask_)
      if (buckets_[k].slot == kAbsent) return false;
  }
  return stored == size_ && (buckets_.empty() || 2 * size_ <= buckets_.size());
}

}  // namespace kew::track
