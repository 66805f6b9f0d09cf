#pragma once
// The daemon configuration tests' check of a refused file: parse_config throws a
// ConfigError whose message holds `needle` (file:line, the key, the reason).
#include <gtest/gtest.h>

#include <string>

#include "kew/daemon/config.hpp"

namespace kew::daemon::config_test {

inline void expect_error(const std::string& text, const std::string& needle) {
  try {
    parse_config(text, "t.toml");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace kew::daemon::config_test
