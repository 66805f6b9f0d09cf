#include "test_hooks.hpp"

#if KEW_TEST_HOOKS
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <spdlog/spdlog.h>
#endif

namespace kew::daemon::test_hooks {

#if KEW_TEST_HOOKS
namespace {

std::string stall_file() {
  const char* path = std::getenv("KEWD_TEST_STALL_FILE");
  return path ? path : "";
}

}  // namespace

void announce() {
  if (const std::string stall = stall_file(); !stall.empty())
    spdlog::warn("KEWD_TEST_STALL_FILE is set (a test hook): the pipeline blocks while {} exists", stall);
}

void maybe_stall_pipeline() {
  static const std::string stall = stall_file();
  if (stall.empty() || !std::filesystem::exists(stall)) return;
  spdlog::warn("test hook: the pipeline is stalled while {} exists", stall);
  while (std::filesystem::exists(stall)) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  spdlog::warn("test hook: the pipeline runs again");
}
#else
void announce() {}
void maybe_stall_pipeline() {}
#endif

}  // namespace kew::daemon::test_hooks
