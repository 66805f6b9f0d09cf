#pragma once
// Wrappers (gzip, format auto-detection) own an inner decoder whose rejections must
// show on the wrapper, where the caller looks. Internal to kew_protocol.

#include <limits>

#include "kew/protocol/decoder.hpp"

namespace kew::protocol::text {

/// From now on, every rejection `inner` counts is counted again on `outer` with its
/// message (outer applies the rate limit; inner reports every one). `outer` must
/// outlive `inner`'s use.
inline void forward_rejections(Decoder& inner, Rejections& outer) {
  inner.rejections() = Rejections(std::numeric_limits<std::uint64_t>::max());
  inner.rejections().set_reporter(
      [&outer](std::string_view reason, std::string_view message) { outer.reject(reason, message); });
}

}  // namespace kew::protocol::text
