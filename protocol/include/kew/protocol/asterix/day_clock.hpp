#pragma once
// ASTERIX items carry the time of day only (seconds since UTC midnight). DayClock places
// each time of day on the UTC time line.

#include <optional>

namespace kew::protocol::asterix {

inline constexpr double kSecondsPerDay = 86400.0;

class DayClock {
 public:
  /// `day_start_utc_s`: UTC midnight (Unix seconds) of the day of the stream's first record.
  explicit DayClock(double day_start_utc_s) : day_start_(day_start_utc_s) {}

  /// UTC seconds of time of day `tod_s` ∈ [0, 86400).
  /// Without a capture time: a time of day more than 12 h before the latest one starts the
  /// next day; one more than 12 h after it is a late record of the previous day (it does
  /// not move the clock).
  /// With a capture time (pcap): the day that puts the record within 12 h of the capture.
  double to_utc(double tod_s);

  /// Capture time (UTC s) of the packet whose records follow; nullopt to go back to the
  /// stream rule.
  void set_capture_time(std::optional<double> capture_utc_s) { capture_utc_ = capture_utc_s; }

 private:
  double day_start_;
  std::optional<double> latest_tod_;
  std::optional<double> capture_utc_;
};

}  // namespace kew::protocol::asterix
