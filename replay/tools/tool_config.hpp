#pragma once
// What kew-replay, kew-decode and kew-eval share on their command lines: the exit status
// of a usage error and the reading of a configuration file.

#include <cstdio>
#include <optional>
#include <string>

#include "kew/config/shared_config.hpp"

namespace kew::replay::tools {

/// EX_USAGE (sysexits.h): a bad flag, input name or configuration file.
inline constexpr int kUsageError = 64;

/// The shared tables of the configuration file at `path`; "" : the built-in defaults with
/// the default aerodrome table (config::default_shared_config). A kewd file is accepted:
/// its [service], [cat004], [modbus], [http] and [[input]] tables are read but not used by
/// the tools. On an error prints "<tool>: <file>:<line>: <message>" on stderr and returns
/// nullopt (the caller exits with kUsageError).
inline std::optional<config::SharedConfig> load_tool_config(const char* tool, const std::string& path) {
  try {
    return path.empty() ? config::default_shared_config() : config::load_shared_config(path);
  } catch (const config::ConfigError& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return std::nullopt;
  }
}

}  // namespace kew::replay::tools
