#pragma once
#include <string>
#include <string_view>

namespace kew::protocol {

/// kew's release, "MAJOR.MINOR.PATCH" (the VERSION object's "release").
std::string_view release();

/// The source revision the binary was built from: 12 hex digits of the git commit, with
/// "-dirty" when tracked files differed from it, the name a package build gave, or
/// "unknown" (the VERSION, START and ALIVE objects' "revision").
std::string_view revision();

/// What `--version` prints: "TOOL RELEASE (REVISION)", e.g. "kewd 0.1.0 (3f2a1c9e0b7d)".
std::string version_line(std::string_view tool);

/// Version of the subscriber protocol of design §5.3 (the VERSION object's "proto").
/// 2: ALERT objects say their `kind` ("stca", or "apw" with a `volume` and no `b`).
inline constexpr int kAlertStreamProtocol = 2;

}  // namespace kew::protocol
