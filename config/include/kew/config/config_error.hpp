#pragma once

#include <stdexcept>

namespace kew::config {

/// A configuration problem, naming the file and line when known:
/// "kew.toml:12: [tracks] timeout_s = 0 is outside [1, 3600]".
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace kew::config
