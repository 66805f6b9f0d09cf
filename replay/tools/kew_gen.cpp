// kew-gen: synthetic radar traffic in the canonical NDJSON track format (design §5.1, §5.6).
// Exit status: 0 done, 64 bad usage, 73 cannot create the output file, 74 write error.
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "kew/config/shared_config.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/protocol/version.hpp"
#include "kew/replay/traffic_generator.hpp"

namespace {

constexpr int kExitUsage = 64;       // EX_USAGE
constexpr int kExitCannotCreate = 73;  // EX_CANTCREAT
constexpr int kExitIoError = 74;     // EX_IOERR

// Records are appended to one buffer and written in blocks this large: no per-line
// flush, and few system calls for the ~150 bytes of a record.
constexpr std::size_t kWriteBlockBytes = 1 << 20;

bool parse_double(std::string_view text, double& out) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, out);
  return result.ec == std::errc() && result.ptr == end;
}

/// "LAT,LON" in degrees.
bool parse_center(std::string_view text, double& lat, double& lon) {
  const auto comma = text.find(',');
  return comma != std::string_view::npos && parse_double(text.substr(0, comma), lat) &&
         parse_double(text.substr(comma + 1), lon);
}

/// The command line that reproduces this output, as a '#' comment (skipped by kew's
/// NDJSON reader): every setting, so a recording says how it was made; the configuration
/// (`config_path`, "" for none) by its path.
std::string header_line(const kew::replay::GeneratorConfig& c, const std::string& config_path) {
  return fmt::format(
      "# kew-gen {} --scenario {} --aircraft {} --duration {} --seed {} --period {} --jitter {} "
      "--noise {} --alt-noise {} --alt-quantum {} --missed {} --termination {} --start {} "
      "--center {},{} --radius {}{}{}\n",
      kew::protocol::release(), kew::replay::to_string(c.scenario), c.aircraft, c.duration_s, c.seed,
      c.period_s, c.jitter_s, c.position_noise_m, c.altitude_noise_ft, c.altitude_quantum_ft,
      c.missed_update_probability, c.termination_probability_per_hour, c.start_time, c.center_lat_deg,
      c.center_lon_deg, c.radius_km, c.report_velocity ? "" : " --no-velocity",
      config_path.empty() ? "" : " --config " + config_path);
}

/// CLI11 2.1 reads "-5" into an unsigned option as 2⁶⁴ − 5: refuse a sign instead.
std::string reject_negative(const std::string& value) {
  return value.find('-') != std::string::npos ? "must not be negative" : "";
}

int usage_error(std::string_view message) {
  fmt::print(stderr, "kew-gen: {}\nRun 'kew-gen --help' for usage.\n", message);
  return kExitUsage;
}

class Output {
 public:
  explicit Output(std::FILE* file, std::string name) : file_(file), name_(std::move(name)) {
    buffer_.reserve(kWriteBlockBytes + 4096);
  }
  std::string& buffer() { return buffer_; }
  /// Writes the buffer once it holds a block (or always when `force`); false on error.
  bool drain(bool force) {
    if (buffer_.empty() || (!force && buffer_.size() < kWriteBlockBytes)) return true;
    const bool ok = std::fwrite(buffer_.data(), 1, buffer_.size(), file_) == buffer_.size();
    buffer_.clear();
    return ok;
  }
  const std::string& name() const { return name_; }

 private:
  std::FILE* file_;
  std::string name_;
  std::string buffer_;
};

}  // namespace

int main(int argc, char** argv) {
  kew::replay::GeneratorConfig config;
  std::string scenario = std::string(kew::replay::to_string(config.scenario));
  std::string center;
  std::string output_path;
  std::string config_path;
  bool no_velocity = false;
  bool no_header = false;

  CLI::App app{
      "Synthetic air traffic with radar-like sampling and noise, written as canonical NDJSON "
      "track records (one JSON object per line) to stdout or -o FILE. The same options give "
      "byte-identical output.",
      "kew-gen"};
  app.set_version_flag("--version", kew::protocol::version_line("kew-gen"));
  app.add_option("--scenario", scenario, kew::replay::kScenarioNames.list())->capture_default_str();
  app.add_option("--aircraft", config.aircraft, "aircraft airborne at every instant, 1 to 1000000")
      ->check(reject_negative)
      ->capture_default_str();
  app.add_option("--duration", config.duration_s, "seconds of traffic")->capture_default_str();
  app.add_option("--seed", config.seed, "random seed (unsigned 64-bit)")
      ->check(reject_negative)
      ->capture_default_str();
  app.add_option("--period", config.period_s, "radar period, seconds (0.1 to 3600)")->capture_default_str();
  app.add_option("--jitter", config.jitter_s, "uniform jitter of each sample time, ± seconds")
      ->capture_default_str();
  app.add_option("--noise", config.position_noise_m, "position noise σ, metres east and north")
      ->capture_default_str();
  app.add_option("--alt-noise", config.altitude_noise_ft, "altitude noise σ, feet")->capture_default_str();
  app.add_option("--alt-quantum", config.altitude_quantum_ft,
                 "altitude resolution, feet (25 Mode S, 100 Mode C, 0 none)")
      ->capture_default_str();
  app.add_option("--missed", config.missed_update_probability, "probability of a missed update, [0, 1)")
      ->capture_default_str();
  app.add_option("--termination", config.termination_probability_per_hour,
                 "early track terminations per aircraft-hour (each replaced by a new aircraft)")
      ->capture_default_str();
  app.add_option("--start", config.start_time, "UTC seconds of the first radar period")
      ->default_str(fmt::format("{}", config.start_time));
  app.add_option("--center", center, "region centre LAT,LON in degrees (default 50,8; not used by global)");
  app.add_option("--radius", config.radius_km, "region radius, km (20 to 2000; not used by global)")
      ->capture_default_str();
  app.add_flag("--no-velocity", no_velocity, "write positions only (no gs_kt, trk_deg, vr_fpm)");
  app.add_flag("--no-header", no_header, "omit the first line, a '#' comment with every setting");
  app.add_option("-o,--output", output_path, "output file (default stdout); replaced if it exists");
  app.add_option("-c,--config", config_path,
                 "kew TOML configuration whose [eligibility] aerodromes_file global flies between "
                 "(default: the installed aerodrome table)")
      ->check(CLI::ExistingFile);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return usage_error(e.what());
  }

  const std::optional<kew::replay::Scenario> parsed = kew::replay::kScenarioNames.parse(scenario);
  if (!parsed)
    return usage_error(fmt::format("unknown scenario '{}' (one of {})", scenario, kew::replay::kScenarioNames.list()));
  config.scenario = *parsed;
  if (!center.empty() && !parse_center(center, config.center_lat_deg, config.center_lon_deg))
    return usage_error(fmt::format("--center wants LAT,LON in degrees (got '{}')", center));
  config.report_velocity = !no_velocity;
  // The aerodromes of the global scenario are those the lower limit of alerting stands on:
  // the configuration's table, as kewd and kew-replay read it.
  try {
    const kew::config::SharedConfig shared = config_path.empty() ? kew::config::default_shared_config()
                                                                 : kew::config::load_shared_config(config_path);
    config.aerodromes = shared.pipeline.eligibility.aerodromes;
  } catch (const kew::config::ConfigError& e) {
    return usage_error(e.what());
  }
  if (const std::string problem = kew::replay::validate(config); !problem.empty()) return usage_error(problem);

  std::FILE* file = stdout;
  if (!output_path.empty()) {
    file = std::fopen(output_path.c_str(), "wb");
    if (file == nullptr) {
      fmt::print(stderr, "kew-gen: cannot create {}: {}\n", output_path, std::strerror(errno));
      return kExitCannotCreate;
    }
  }
  Output out(file, output_path.empty() ? "stdout" : output_path);

  kew::replay::TrafficGenerator generator(config);
  if (!no_header) out.buffer() += header_line(config, config_path);
  kew::TrackReport record;
  bool ok = true;
  while (ok && generator.next(record)) {
    kew::protocol::append_ndjson(out.buffer(), record);
    out.buffer() += '\n';
    ok = out.drain(false);
  }
  ok = ok && out.drain(true);
  ok = (std::fflush(file) == 0) && ok;
  if (file != stdout) ok = (std::fclose(file) == 0) && ok;
  if (!ok) {
    fmt::print(stderr, "kew-gen: writing {} failed: {}\n", out.name(), std::strerror(errno));
    return kExitIoError;
  }
  return 0;
}
