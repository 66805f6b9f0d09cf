#pragma once
// A failure that repeats while a server is away (a NATS server: no connection, no
// stream, no acknowledgement; an HTTP server polled) goes to the log once, then at most every 30 s with how often it
// happened meanwhile; recovered() says so once it stops. One thread uses an instance.

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include <spdlog/spdlog.h>

namespace kew::daemon {

class RepeatedFailure {
 public:
  static constexpr auto kReportPeriod = std::chrono::seconds(30);

  /// `who` prefixes every message ("input bus", "[nats]").
  explicit RepeatedFailure(std::string who) : who_(std::move(who)) {}

  void report(std::string_view what) {
    ++since_recovery_;
    const auto now = std::chrono::steady_clock::now();
    if (reported_ && now - last_report_ < kReportPeriod) {
      ++since_report_;  // told at the next report
      return;
    }
    if (since_report_ > 0)
      spdlog::warn("{}: {} ({} more times since the last report)", who_, what, since_report_);
    else
      spdlog::warn("{}: {}", who_, what);
    reported_ = true;
    last_report_ = now;
    since_report_ = 0;
  }
  void recovered(std::string_view what) {
    if (!since_recovery_) return;
    spdlog::info("{}: {} after {} failed attempts", who_, what, since_recovery_);
    since_recovery_ = since_report_ = 0;
    reported_ = false;  // the next failure is news again
  }

 private:
  std::string who_;
  std::uint64_t since_report_ = 0;
  std::uint64_t since_recovery_ = 0;
  bool reported_ = false;
  std::chrono::steady_clock::time_point last_report_{};
};

}  // namespace kew::daemon
