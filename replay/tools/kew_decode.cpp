// kew-decode (design §5.6): any input format kew reads, to canonical NDJSON track records
// (design §5.1) on standard output, as gpsd's gpsdecode does for gpsd. What a decoder
// refuses is counted by reason on standard error; replaying the output gives the same
// alerts as replaying the input (tests/e2e/test_kew_decode.py).

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "kew/config/shared_config.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/protocol/version.hpp"
#include "kew/replay/recording_reader.hpp"
#include "tool_config.hpp"

namespace {

using kew::replay::tools::kUsageError;
constexpr int kIoError = 1;
constexpr std::size_t kFlushBytes = 64 * 1024;

struct Options {
  std::string format = "auto";
  std::string config_path;
  bool quiet = false;
  std::vector<std::string> files;
};

std::string refusal_summary(const kew::Rejections& refused) {
  std::string text;
  for (const auto& [reason, count] : refused.by_reason()) {
    text += text.empty() ? " (" : ", ";
    text += fmt::format("{} {}", reason, count);
  }
  if (!text.empty()) text += ')';
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"kew-decode: convert recordings in any format kew reads to canonical NDJSON on standard output"};
  app.set_version_flag("--version", kew::protocol::version_line("kew-decode"));
  const auto file_formats = {kew::protocol::Format::AsterixDatagram};  // live-only
  app.add_option("--format", options.format, "input format: " + kew::protocol::kFormatNames.list(file_formats))
      ->default_val("auto")
      ->check(CLI::IsMember(kew::protocol::kFormatNames.names(file_formats)));
  app.add_option("-c,--config", options.config_path,
                 "kew TOML configuration: its [[radar]] sites project CAT048 plots ([decoding] applies too)");
  app.add_flag("-q,--quiet", options.quiet, "no message per refused record, only the summary");
  app.add_option("files", options.files, "recordings, merged in time order (none or -: standard input)")
      ->check(CLI::Validator([](std::string& path) { return kew::replay::recording_path_problem(path); }, "RECORDING"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }
  if (options.files.empty()) options.files.emplace_back(kew::replay::kStandardInput);

  kew::config::SharedConfig config;
  if (!options.config_path.empty()) {
    std::optional<kew::config::SharedConfig> loaded = kew::replay::tools::load_tool_config("kew-decode", options.config_path);
    if (!loaded) return kUsageError;
    config = std::move(*loaded);
  }

  const kew::protocol::Format format = *kew::protocol::kFormatNames.parse(options.format);
  kew::replay::MergedRecordings recordings;
  for (const std::string& file : options.files) {
    auto reader = std::make_unique<kew::replay::RecordingReader>(file, format, config.decoding);
    if (!options.quiet) {
      const std::string origin = file == kew::replay::kStandardInput ? "stdin" : file;
      reader->rejections().set_reporter([origin](std::string_view reason, std::string_view message) {
        std::fprintf(stderr, "kew-decode: %s: refused (%.*s) %.*s\n", origin.c_str(), static_cast<int>(reason.size()),
                     reason.data(), static_cast<int>(message.size()), message.data());
      });
    }
    recordings.add(std::move(reader));
  }

  std::string buffer;
  std::uint64_t written = 0;
  bool output_failed = false;
  const auto flush = [&] {
    if (!output_failed && !buffer.empty() && std::fwrite(buffer.data(), 1, buffer.size(), stdout) != buffer.size())
      output_failed = true;
    buffer.clear();
  };
  kew::TrackReport report;
  while (!output_failed && recordings.next(report)) {
    kew::protocol::append_ndjson(buffer, report);
    buffer += '\n';
    ++written;
    if (buffer.size() >= kFlushBytes) flush();
  }
  flush();
  if (!output_failed && std::fflush(stdout) != 0) output_failed = true;
  if (output_failed) {
    std::fprintf(stderr, "kew-decode: cannot write standard output: %s\n", std::strerror(errno));
    return kIoError;
  }

  const kew::Rejections refused = recordings.rejections();
  std::fprintf(stderr, "kew-decode: %llu records written, %llu refused%s\n", static_cast<unsigned long long>(written),
               static_cast<unsigned long long>(refused.total()), refusal_summary(refused).c_str());
  return refused.count("file_unreadable") > 0 ? kIoError : 0;
}
