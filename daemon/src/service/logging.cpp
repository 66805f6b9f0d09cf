#include "logging.hpp"

#include <cstdlib>
#include <memory>

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/sinks/syslog_sink.h>

namespace kew::daemon {

namespace {

// "%*" → the sd-daemon(3) priority prefix "<N>" that journald turns into a log level.
class SyslogPriorityFlag final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    static constexpr const char* kPrefixes[] = {"<7>", "<7>", "<6>", "<4>", "<3>", "<2>", "<6>"};
    const auto level = static_cast<std::size_t>(msg.level);
    const char* prefix = kPrefixes[level < 7 ? level : 6];
    dest.append(prefix, prefix + 3);
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<SyslogPriorityFlag>(); }
};

spdlog::level::level_enum spdlog_level(LogLevel level) {
  switch (level) {
    case LogLevel::Trace: return spdlog::level::trace;
    case LogLevel::Debug: return spdlog::level::debug;
    case LogLevel::Warn: return spdlog::level::warn;
    case LogLevel::Error: return spdlog::level::err;
    case LogLevel::Critical: return spdlog::level::critical;
    case LogLevel::Off: return spdlog::level::off;
    case LogLevel::Info: break;
  }
  return spdlog::level::info;
}

}  // namespace

void setup_logging(LogTarget target, LogLevel level) {
  std::shared_ptr<spdlog::logger> logger;
  if (target == LogTarget::Syslog) {
    logger = std::make_shared<spdlog::logger>(
        "kewd", std::make_shared<spdlog::sinks::syslog_sink_mt>("kewd", LOG_PID, LOG_DAEMON, true));
    logger->set_pattern("%v");
  } else {
    logger = std::make_shared<spdlog::logger>("kewd", std::make_shared<spdlog::sinks::stderr_sink_mt>());
    auto formatter = std::make_unique<spdlog::pattern_formatter>();
    if (std::getenv("JOURNAL_STREAM")) {
      // The journal stamps time and unit itself.
      formatter->add_flag<SyslogPriorityFlag>('*').set_pattern("%*%v");
    } else {
      formatter->set_pattern("%Y-%m-%d %H:%M:%S.%e kewd %l: %v");
    }
    logger->set_formatter(std::move(formatter));
  }
  spdlog::set_default_logger(logger);
  set_log_level(level);
}

void set_log_level(LogLevel level) {
  spdlog::set_level(spdlog_level(level));
  spdlog::flush_on(spdlog::level::warn);
}

}  // namespace kew::daemon
