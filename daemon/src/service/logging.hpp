#pragma once
// Logging for kewd: spdlog to stderr with syslog priority prefixes when stderr is the
// journal (systemd sets JOURNAL_STREAM), plain levels on a terminal, syslog when the
// daemon forks into the background.

#include <spdlog/spdlog.h>

#include "kew/daemon/config.hpp"

namespace kew::daemon {

enum class LogTarget { Stderr, Syslog };

/// Installs the default logger.
void setup_logging(LogTarget target, LogLevel level);
/// Changes the level of the installed logger (SIGHUP reload).
void set_log_level(LogLevel level);

}  // namespace kew::daemon
