#pragma once
// Logging for kewd: spdlog to stderr with syslog priority prefixes when stderr is the
// journal (systemd sets JOURNAL_STREAM), plain levels on a terminal, syslog when the
// daemon forks into the background.

#include <string>
#include <string_view>

#include <spdlog/spdlog.h>

namespace kew::daemon {

enum class LogTarget { Stderr, Syslog };

/// Installs the default logger. `level` is a config level name ("info", ...).
void setup_logging(LogTarget target, std::string_view level);
/// Changes the level of the installed logger (SIGHUP reload).
void set_log_level(std::string_view level);

}  // namespace kew::daemon
