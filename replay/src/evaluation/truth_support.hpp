#pragma once
// What the pair truth (truth.cpp) and the area truth (area_truth.cpp) both do with runs of
// whole seconds: note, join and look them up, find a trace by its key, and search the
// seconds around a time. Internal to kew_replay.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "kew/replay/truth.hpp"

namespace kew::replay {

/// Appends second `s` to ranges of increasing seconds, extending the last range when `s`
/// follows it. True when a new range was started.
inline bool append_second(std::vector<SecondRange>& ranges, std::int64_t s) {
  if (!ranges.empty() && ranges.back().last + 1 == s) {
    ranges.back().last = s;
    return false;
  }
  ranges.push_back({s, s});
  return true;
}

/// Sorts ranges and joins those that overlap or touch.
inline std::vector<SecondRange> union_of(std::vector<SecondRange> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const SecondRange& x, const SecondRange& y) { return x.first < y.first; });
  std::vector<SecondRange> out;
  for (const SecondRange& r : ranges) {
    if (!out.empty() && r.first <= out.back().last + 1)
      out.back().last = std::max(out.back().last, r.last);
    else
      out.push_back(r);
  }
  return out;
}

/// The first range of sorted, disjoint `ranges` meeting [from, to], if any.
inline const SecondRange* first_meeting(const std::vector<SecondRange>& ranges, std::int64_t from, std::int64_t to) {
  const auto it = std::lower_bound(ranges.begin(), ranges.end(), from,
                                   [](const SecondRange& r, std::int64_t s) { return r.last < s; });
  if (it == ranges.end() || it->first > to) return nullptr;
  return &*it;
}

/// The first second of sorted, disjoint `ranges` in [from, to], if any.
inline std::optional<std::int64_t> first_second_in(const std::vector<SecondRange>& ranges, std::int64_t from,
                                                   std::int64_t to) {
  const SecondRange* r = first_meeting(ranges, from, to);
  if (!r) return std::nullopt;
  return std::max(r->first, from);
}

/// The value of `key` in `traces`, sorted by key; nullptr when it has none.
template <class Trace>
const Trace* find_trace(const std::vector<std::pair<std::uint64_t, Trace>>& traces, std::uint64_t key) {
  const auto it = std::lower_bound(traces.begin(), traces.end(), key,
                                   [](const auto& entry, std::uint64_t k) { return entry.first < k; });
  if (it == traces.end() || it->first != key) return nullptr;
  return &it->second;
}

/// The whole seconds within `within_s` of `t`, the nearest first (of two as near, the
/// earlier); none when `t` is not finite or `within_s` not ≥ 0.
inline std::vector<std::int64_t> seconds_nearest_first(double t, double within_s) {
  std::vector<std::int64_t> seconds;
  if (!std::isfinite(t) || !(within_s >= 0.0)) return seconds;
  const auto from = static_cast<std::int64_t>(std::ceil(t - within_s));
  const auto to = static_cast<std::int64_t>(std::floor(t + within_s));
  for (std::int64_t s = from; s <= to; ++s) seconds.push_back(s);
  std::stable_sort(seconds.begin(), seconds.end(), [t](std::int64_t x, std::int64_t y) {
    return std::abs(static_cast<double>(x) - t) < std::abs(static_cast<double>(y) - t);
  });
  return seconds;
}

}  // namespace kew::replay
