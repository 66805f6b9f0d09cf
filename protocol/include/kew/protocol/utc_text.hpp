#pragma once
// The time of day people read in kew's text outputs (kew-watch's lines, notifications).

#include <string>

namespace kew::protocol {

/// "HH:MM:SSZ" of `utc_s` (Unix seconds, UTC), the second truncated; "--:--:--" when
/// `utc_s` is not finite.
std::string utc_time_of_day(double utc_s);

}  // namespace kew::protocol
