#pragma once
// A binary heap of (key, handle) with one entry per handle and O(log n) change of any
// handle's key. Handles are small dense integers (track slots). Ties between equal keys
// go to the smaller handle, so the order is a function of the contents alone.

#include <cstdint>
#include <utility>
#include <vector>

#include "kew/util/gentle_growth.hpp"

namespace kew::util {

/// `Before(a, b)` is true when key a must come out first (std::less: smallest first).
template <class Before>
class IndexedHeap {
 public:
  using Handle = std::uint32_t;

  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  bool contains(Handle h) const { return h < position_.size() && position_[h] != kAbsent; }
  double top_key() const { return entries_.front().key; }
  Handle top_handle() const { return entries_.front().handle; }

  /// Inserts h with `key`, or changes its key when present.
  void set(Handle h, double key) {
    grow_to(position_, h + 1, kAbsent);
    if (position_[h] == kAbsent) {
      position_[h] = static_cast<std::uint32_t>(entries_.size());
      push_back_gently(entries_, Entry{key, h});
      sift_up(entries_.size() - 1);
      return;
    }
    const std::size_t i = position_[h];
    entries_[i].key = key;
    sift_up(i);
    sift_down(position_[h]);
  }

  /// Removes h if present.
  /// Calls f(handle, key) for every entry, in no particular order (a checkpoint: set()
  /// in any order gives the same order out, ties going to the smaller handle).
  template <class F>
  void for_each(F&& f) const {
    for (const Entry& e : entries_) f(e.handle, e.key);
  }

  void erase(Handle h) {
    if (!contains(h)) return;
    const std::size_t i = position_[h];
    const std::size_t last = entries_.size() - 1;
    if (i != last) swap_entries(i, last);
    entries_.pop_back();
    position_[h] = kAbsent;
    if (i < entries_.size()) {
      const Handle moved = entries_[i].handle;
      sift_up(i);
      sift_down(position_[moved]);
    }
  }

 private:
  static constexpr std::uint32_t kAbsent = ~std::uint32_t{0};
  struct Entry {
    double key;
    Handle handle;
  };

  static bool first(const Entry& a, const Entry& b) {
    if (Before{}(a.key, b.key)) return true;
    if (Before{}(b.key, a.key)) return false;
    return a.handle < b.handle;
  }

  void sift_up(std::size_t i) {
    while (i > 0) {
      const std::size_t parent = (i - 1) / 2;
      if (!first(entries_[i], entries_[parent])) return;
      swap_entries(i, parent);
      i = parent;
    }
  }

  void sift_down(std::size_t i) {
    const std::size_t n = entries_.size();
    for (;;) {
      std::size_t best = i;
      const std::size_t left = 2 * i + 1, right = left + 1;
      if (left < n && first(entries_[left], entries_[best])) best = left;
      if (right < n && first(entries_[right], entries_[best])) best = right;
      if (best == i) return;
      swap_entries(i, best);
      i = best;
    }
  }

  void swap_entries(std::size_t i, std::size_t j) {
    std::swap(entries_[i], entries_[j]);
    position_[entries_[i].handle] = static_cast<std::uint32_t>(i);
    position_[entries_[j].handle] = static_cast<std::uint32_t>(j);
  }

  std::vector<Entry> entries_;
  std::vector<std::uint32_t> position_;
};

}  // namespace kew::util
