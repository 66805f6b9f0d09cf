#include "kew/track/time_guard.hpp"

#include <algorithm>
#include <iterator>

namespace kew::track {

TimeGuard::TimeGuard(double max_jump_s, double max_lateness_s, std::size_t confirm)
    : max_jump_s_(max_jump_s), max_lateness_s_(max_lateness_s), confirm_(std::max<std::size_t>(confirm, 1)) {}

namespace {

// Moves the elements of `from` that satisfy `pick` to the end of `to`, both in order.
template <class Pick>
void move_out(std::vector<TrackReport>& from, std::vector<TrackReport>& to, Pick pick) {
  const auto kept = std::stable_partition(from.begin(), from.end(), [&](const TrackReport& r) { return !pick(r); });
  std::move(kept, from.end(), std::back_inserter(to));
  from.erase(kept, from.end());
}

}  // namespace

void TimeGuard::refuse_contradicted(double t, std::vector<TrackReport>& refused) {
  move_out(held_, refused, [&](const TrackReport& r) { return t < r.t - max_lateness_s_; });
}

bool TimeGuard::hold(const TrackReport& r) {
  held_.push_back(r);
  return held_.size() >= confirm_;
}

void TimeGuard::release(std::vector<TrackReport>& released) {
  std::move(held_.begin(), held_.end(), std::back_inserter(released));
  held_.clear();
}

void TimeGuard::release_reached(double clock, std::vector<TrackReport>& released) {
  move_out(held_, released, [&](const TrackReport& r) { return !ahead(r.t, clock); });
}

}  // namespace kew::track
