#pragma once
// Reads one [[notify]] table (design §5.10).

#include "kew/config/document.hpp"
#include "kew/daemon/notify_config.hpp"

namespace kew::daemon {

/// Reads `r` into `n`; throws config::ConfigError naming the key for a wrong value.
void read_notify(config::TableReader& r, NotifyConfig& n);

}  // namespace kew::daemon
