#pragma once
// When to send the next request to an HTTP server (design §5.7): at the configured
// interval while it answers, backing off after failures (doubling from a least to a
// most delay), and never sooner than the server asked (Retry-After). Pure arithmetic,
// times in seconds; the caller measures the interval from the start of the last request,
// so a 1 s poll of a slow server still polls once a second.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace kew::daemon {

class RetrySchedule {
 public:
  /// `interval_s` > 0 between answered requests; failures wait `backoff_min_s`, doubling
  /// up to `backoff_max_s` (both > 0, min ≤ max).
  RetrySchedule(double interval_s, double backoff_min_s, double backoff_max_s)
      : interval_s_(interval_s), backoff_min_s_(backoff_min_s), backoff_max_s_(std::max(backoff_min_s, backoff_max_s)) {}

  /// The wait after an answer the caller took (s): the interval, or longer when the
  /// server asked for more.
  double after_success(std::optional<double> retry_after_s = std::nullopt) {
    failures_ = 0;
    return std::max(interval_s_, retry_after_s.value_or(0.0));
  }
  /// The wait after a failure (s): the backoff (min × 2^(failures − 1), at most max), at
  /// least the interval, and at least what the server asked (even beyond max: a server
  /// that names its limit knows it).
  double after_failure(std::optional<double> retry_after_s = std::nullopt) {
    ++failures_;
    const double exponent = static_cast<double>(std::min<std::uint64_t>(failures_ - 1, 62));
    const double backoff = std::min(backoff_max_s_, backoff_min_s_ * std::exp2(exponent));
    return std::max({interval_s_, backoff, retry_after_s.value_or(0.0)});
  }
  /// Failures since the last success.
  std::uint64_t consecutive_failures() const { return failures_; }

 private:
  double interval_s_;
  double backoff_min_s_;
  double backoff_max_s_;
  std::uint64_t failures_ = 0;
};

}  // namespace kew::daemon
