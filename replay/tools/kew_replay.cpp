// kew-replay (design §5.6): runs the whole pipeline over recordings as fast as possible
// and writes the ALERT objects as JSON lines, or streams the records to a running kewd
// paced like the recording.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "kew/config/shared_config.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "kew/protocol/version.hpp"
#include "kew/replay/recording_reader.hpp"
#include "kew/replay/stream_sender.hpp"
#include "tool_config.hpp"

namespace {

using kew::replay::tools::kUsageError;
constexpr int kAuditFailed = 1;
constexpr double kAuditEvery_s = 60.0;  // data time between audits with --audit

struct Options {
  std::string format = "auto";
  std::string config_path;
  double speed = 1.0;
  bool max_speed = false;
  std::string to;
  std::string alerts_path;
  std::string stats_path;
  bool audit = false;
  bool sort = false;
  std::string probe;
  std::vector<std::string> files;
};

// Buffered writer of the alert lines: one fwrite per 64 KiB, not per line.
class AlertWriter {
 public:
  explicit AlertWriter(std::FILE* out) : out_(out) {}
  ~AlertWriter() { flush(); }
  void write(const kew::AlertEvent& event) {
    kew::protocol::append_alert_json(buffer_, event, event.seq);
    if (buffer_.size() >= 64 * 1024) flush();
  }
  void flush() {
    if (!buffer_.empty()) std::fwrite(buffer_.data(), 1, buffer_.size(), out_);
    buffer_.clear();
    std::fflush(out_);
  }

 private:
  std::FILE* out_;
  std::string buffer_;
};

// One status line on a terminal, rewritten in place at most twice a second.
class Progress {
 public:
  Progress() : enabled_(::isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()) {}
  void update(const kew::Pipeline& pipeline) {
    const std::uint64_t records = pipeline.statistics().records;
    if (!enabled_ || (records & 0xfff) != 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(500)) return;
    last_ = now;
    const double wall = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r\033[Kkew-replay: %llu records, %zu tracks, %zu alerts active, %.0f records/s",
                 static_cast<unsigned long long>(pipeline.statistics().records), pipeline.live_tracks(), pipeline.alerts().active_count(),
                 wall > 0 ? static_cast<double>(records) / wall : 0.0);
  }
  void done() {
    if (enabled_) std::fprintf(stderr, "\r\033[K");
  }

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_{};
};

void report_rejection(const std::string& origin, std::string_view reason, std::string_view message) {
  std::fprintf(stderr, "kew-replay: %s: rejected (%.*s) %.*s\n", origin.c_str(), static_cast<int>(reason.size()),
               reason.data(), static_cast<int>(message.size()), message.data());
}

int stream_to(const Options& options, kew::replay::MergedRecordings& recordings) {
  std::string error;
  const std::optional<kew::replay::StreamTarget> target = kew::replay::parse_stream_target(options.to, &error);
  if (!target) {
    std::fprintf(stderr, "kew-replay: --to %s (expected [tcp://|udp://]HOST:PORT or nats://HOST:PORT[,HOST:PORT...]/SUBJECT)\n",
                 error.c_str());
    return kUsageError;
  }
  try {
    const auto figures = kew::replay::stream_records(recordings, *target, options.max_speed ? 0.0 : options.speed);
    std::fprintf(stderr, "kew-replay: sent %llu records (%llu bytes) to %s\n",
                 static_cast<unsigned long long>(figures.records), static_cast<unsigned long long>(figures.bytes),
                 options.to.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kew-replay: %s\n", e.what());
    return 1;
  }
  return 0;
}

int run_offline(const Options& options, const kew::config::SharedConfig& config,
                kew::replay::MergedRecordings& recordings) {
  std::FILE* out = stdout;
  if (!options.alerts_path.empty()) {
    out = std::fopen(options.alerts_path.c_str(), "wb");
    if (!out) {
      std::fprintf(stderr, "kew-replay: cannot write %s\n", options.alerts_path.c_str());
      return 1;
    }
  }
  const auto start = std::chrono::steady_clock::now();
  kew::Pipeline pipeline(config.pipeline);
  pipeline.rejections().set_reporter(
      [](std::string_view reason, std::string_view message) { report_rejection("pipeline", reason, message); });
  kew::protocol::ReplayStatistics figures;
  {
    AlertWriter writer(out);
    pipeline.set_alert_sink([&](const kew::AlertEvent& e) { writer.write(e); });
    Progress progress;
    kew::TrackReport report;
    double next_audit = 0.0;
    const auto audit = [&] {
      const kew::kinetic::KineticAudit a = pipeline.audit();
      ++figures.audits;
      figures.audit_violations_found += a.violations_found;
      figures.audit_violations_unrepaired += a.violations_unrepaired;
    };
    // --sort: the whole input in memory, in time order (stable: ties keep file order).
    std::vector<kew::TrackReport> sorted;
    std::size_t sorted_next = 0;
    if (options.sort) {
      while (recordings.next(report)) sorted.push_back(report);
      std::stable_sort(sorted.begin(), sorted.end(),
                       [](const kew::TrackReport& a, const kew::TrackReport& b) { return a.t < b.t; });
    }
    const auto next = [&](kew::TrackReport& record) {
      if (!options.sort) return recordings.next(record);
      if (sorted_next == sorted.size()) return false;
      record = std::move(sorted[sorted_next++]);
      return true;
    };
    while (next(report)) {
      pipeline.process(report);
      if (options.audit && pipeline.now() >= next_audit) {
        if (next_audit > 0.0) audit();
        next_audit = pipeline.now() + kAuditEvery_s;
      }
      progress.update(pipeline);
    }
    pipeline.end_of_input();
    if (options.audit) audit();
    progress.done();
  }
  if (out != stdout) std::fclose(out);
  figures.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const kew::Rejections decoding = recordings.rejections();
  const std::string stats = kew::protocol::run_statistics_json(pipeline, decoding, figures);
  if (!options.stats_path.empty()) {
    std::FILE* f = std::fopen(options.stats_path.c_str(), "wb");
    if (!f || std::fwrite(stats.data(), 1, stats.size(), f) != stats.size()) {
      std::fprintf(stderr, "kew-replay: cannot write %s\n", options.stats_path.c_str());
      if (f) std::fclose(f);
      return 1;
    }
    std::fclose(f);
  }
  const auto& counters = pipeline.alerts().counters();
  std::fprintf(stderr,
               "kew-replay: %llu records, %llu accepted, %llu rejected, %zu tracks at most, %llu alerts "
               "(%llu updates, %llu ended), %.2f s\n",
               static_cast<unsigned long long>(pipeline.statistics().records),
               static_cast<unsigned long long>(pipeline.statistics().accepted),
               static_cast<unsigned long long>(decoding.total() + pipeline.rejections().total()),
               pipeline.tracks().max_size(), static_cast<unsigned long long>(counters.opened),
               static_cast<unsigned long long>(counters.updated), static_cast<unsigned long long>(counters.ended),
               figures.wall_s);
  if (options.audit) {
    std::fprintf(stderr, "kew-replay: audit: %llu runs, %llu violations found, %llu unrepaired\n",
                 static_cast<unsigned long long>(figures.audits),
                 static_cast<unsigned long long>(figures.audit_violations_found),
                 static_cast<unsigned long long>(figures.audit_violations_unrepaired));
    if (figures.audit_violations_unrepaired > 0) return kAuditFailed;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"kew-replay: run kew's conflict detection over recordings, or stream them to kewd"};
  app.set_version_flag("--version", kew::protocol::version_line("kew-replay"));
  // Every format but the live-only asterix-datagram (one UDP datagram per read).
  const auto file_formats = {kew::protocol::Format::AsterixDatagram};
  app.add_option("--format", options.format, "input format: " + kew::protocol::kFormatNames.list(file_formats))
      ->default_val("auto")
      ->check(CLI::IsMember(kew::protocol::kFormatNames.names(file_formats)));
  app.add_option("-c,--config", options.config_path, "kew TOML configuration (as kewd's)");
  auto* speed = app.add_option("--speed", options.speed, "with --to: multiple of recorded speed")->check(
      CLI::PositiveNumber);
  app.add_flag("--max-speed", options.max_speed, "with --to: send as fast as possible")->excludes(speed);
  app.add_option("--to", options.to,
                 "stream records to a kewd input: [tcp://|udp://]HOST:PORT, or publish them: nats://HOST:PORT/SUBJECT (a cluster: nats://HOST:PORT,HOST:PORT/SUBJECT)");
  app.add_option("--alerts", options.alerts_path, "write ALERT lines here instead of stdout");
  app.add_option("--stats-json", options.stats_path, "write run statistics as one JSON object");
  app.add_flag("--sort", options.sort,
               "read everything first and replay in time order (recordings grouped by flight, not by time)");
  app.add_flag("--audit", options.audit, "audit the triangulation every 60 s of data and at the end");
  app.add_option("--probe", options.probe, "candidate search: " + kew::probe::kProbeModeNames.list())
      ->check(CLI::IsMember(kew::probe::kProbeModeNames.names()));
  app.add_option("files", options.files, "recordings (merged in time order; - reads standard input)")
      ->required()
      ->check(CLI::Validator([](std::string& path) { return kew::replay::recording_path_problem(path); }, "RECORDING"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }

  const kew::protocol::Format format = *kew::protocol::kFormatNames.parse(options.format);
  std::optional<kew::config::SharedConfig> loaded = kew::replay::tools::load_tool_config("kew-replay", options.config_path);
  if (!loaded) return kUsageError;
  kew::config::SharedConfig& config = *loaded;
  if (!options.probe.empty()) config.pipeline.probe_mode = *kew::probe::kProbeModeNames.parse(options.probe);

  kew::replay::MergedRecordings recordings;
  for (const std::string& file : options.files) {
    auto reader = std::make_unique<kew::replay::RecordingReader>(file, format, config.decoding);
    reader->rejections().set_reporter(
        [file](std::string_view reason, std::string_view message) { report_rejection(file, reason, message); });
    recordings.add(std::move(reader));
  }
  return options.to.empty() ? run_offline(options, config, recordings) : stream_to(options, recordings);
}
