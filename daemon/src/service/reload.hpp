#pragma once
// SIGHUP (design §5.7): what of a re-read configuration applies in flight. Logging,
// subscriber and HTTP limits and the tick and ALIVE intervals change at once; inputs,
// outputs and pipeline parameters would change results mid-stream and wait for a restart.

#include <optional>
#include <string>

#include "../http/http_server.hpp"
#include "logging.hpp"
#include "subscribers.hpp"
#include "kew/daemon/config.hpp"

namespace kew::daemon {

/// Applies what can change of `fresh` (read from `path`) to `current` and to the servers
/// (`http` may be null); `log_level_override` (kewd -l) keeps its level whatever the file
/// says. Logs what changed.
void apply_in_flight(const std::string& path, const Config& fresh, const std::optional<LogLevel>& log_level_override,
                     Config& current, SubscriberServer& subscribers, http::HttpServer* http);

/// SIGHUP: reads `path` again and applies what can change (apply_in_flight), telling
/// systemd it reloads meanwhile. A file that does not load changes nothing and is logged;
/// an empty `path` (built-in defaults) has nothing to read.
void reload_configuration(const std::string& path, const std::optional<LogLevel>& log_level_override,
                          Config& current, SubscriberServer& subscribers, http::HttpServer* http);

}  // namespace kew::daemon
