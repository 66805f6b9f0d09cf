#pragma once
// Callsign and address patterns of the configuration ([[notify]], [[volume]]): '*' any
// run of characters (none included), '?' exactly one; letters compared without case.

#include <string_view>

namespace kew::util {

/// True when `text` matches `pattern` as a whole.
bool matches_wildcard(std::string_view pattern, std::string_view text);

}  // namespace kew::util
