#pragma once
// Capacity growth by a quarter for the arrays that hold one entry per track, point, face
// or scheduled event. std::vector doubles, so such an array holds up to twice what it
// uses (1.4 times on average) for as long as the traffic lasts; growing by a quarter
// bounds that at 1.25 for the price of a few more copies while the traffic builds up.

#include <algorithm>
#include <cstddef>
#include <utility>

namespace kew::util {

/// Ensures v.capacity() ≥ needed, growing by at least a quarter of the capacity now.
template <class Vector>
void reserve_gently(Vector& v, std::size_t needed) {
  if (needed <= v.capacity()) return;
  v.reserve(std::max(needed, v.capacity() + v.capacity() / 4 + 16));
}

/// v.resize(n, fill...) when n is larger than v.size(), with reserve_gently's growth.
template <class Vector, class... Fill>
void grow_to(Vector& v, std::size_t n, const Fill&... fill) {
  if (n <= v.size()) return;
  reserve_gently(v, n);
  v.resize(n, fill...);
}

/// v.push_back(value) with reserve_gently's growth.
template <class Vector, class Value>
void push_back_gently(Vector& v, Value&& value) {
  reserve_gently(v, v.size() + 1);
  v.push_back(std::forward<Value>(value));
}

}  // namespace kew::util
