#pragma once
#include <string_view>

namespace kew::protocol {

/// kew's release, "MAJOR.MINOR.PATCH" (the VERSION object's "release").
std::string_view release();

/// Version of the subscriber protocol of design §5.3 (the VERSION object's "proto").
inline constexpr int kAlertStreamProtocol = 1;

}  // namespace kew::protocol
