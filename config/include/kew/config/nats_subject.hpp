#pragma once
// NATS subjects as configurations name them (kewd, kew-replay --to) and kewd's
// publisher builds them (design §5.9).

#include <string>
#include <string_view>

namespace kew::config {

/// `subject` is dot-separated tokens, none empty, with no white space or control
/// character; '*' and '>' only as whole tokens and only when `wildcards` (for
/// subscribing), '>' only last.
bool valid_nats_subject(std::string_view subject, bool wildcards);

/// A name as one subject token and MQTT topic level (no '.', wildcard, '/', '+', '#' or
/// space): a zone "N40.5E004.5" becomes "N40_5E004_5"; "" becomes "_".
std::string nats_subject_token(std::string_view name);

}  // namespace kew::config
