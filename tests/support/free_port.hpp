#pragma once
// kew refuses port 0 in every address (a listener on it would be unreachable at an
// unknown port), so tests and benchmarks pick free loopback ports themselves.

#include <cstdint>
#include <string>

namespace kew::testing {

/// A port on 127.0.0.1 that was free for both TCP and UDP a moment ago (bound, read,
/// released). Throws std::runtime_error when no socket can be bound.
std::uint16_t free_loopback_port();

/// "127.0.0.1:<free_loopback_port()>".
std::string free_loopback_address();

}  // namespace kew::testing
