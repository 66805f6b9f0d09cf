#include "kew/replay/recording_reader.hpp"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <optional>

#include "kew/protocol/gzip.hpp"
#include "trace_merge.hpp"

namespace kew::replay {

namespace {
constexpr std::size_t kChunkBytes = 256 * 1024;

bool is_pattern(const std::string& path) { return path.find_first_of("*?[") != std::string::npos; }

/// The regular files a directory (not its hidden ones, not below it) or a glob pattern
/// names, sorted by name.
std::vector<std::string> files_named(const std::string& path) {
  std::vector<std::string> files;
  if (is_pattern(path)) {
    glob_t found{};
    if (::glob(path.c_str(), 0, nullptr, &found) == 0)
      for (std::size_t i = 0; i < found.gl_pathc; ++i)
        if (std::filesystem::is_regular_file(found.gl_pathv[i])) files.emplace_back(found.gl_pathv[i]);
    ::globfree(&found);
  } else {
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(path, error))
      if (entry.is_regular_file() && !entry.path().filename().string().starts_with("."))
        files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

/// The start of a file (its first `limit` bytes after inflating, gzip or not), or the
/// whole of it when `limit` is 0; empty when it cannot be read.
std::string file_text(const std::string& path, std::size_t limit = 0) {
  std::string bytes;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    char buffer[65536];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) {
      bytes.append(buffer, n);
      if (limit && bytes.size() >= limit) break;  // enough for the head, even inflated
    }
    std::fclose(f);
  }
  const auto raw = std::as_bytes(std::span<const char>(bytes.data(), bytes.size()));
  if (!protocol::has_gzip_magic(raw)) return limit ? bytes.substr(0, limit) : bytes;
  // JSON compresses about tenfold: room for far more than that, not for a bomb.
  const std::size_t room = limit ? limit : std::min<std::size_t>(64 * bytes.size() + 65536, std::size_t{1} << 30);
  const std::vector<std::byte> inflated = protocol::gunzip_prefix(raw, room);
  return std::string(reinterpret_cast<const char*>(inflated.data()), inflated.size());
}

/// The value of the member "now" in `text`, milliseconds taken as such; nullopt without one.
std::optional<double> now_member(const std::string& text) {
  const auto key = text.find("\"now\"");
  if (key == std::string::npos) return std::nullopt;
  const auto colon = text.find(':', key);
  if (colon == std::string::npos) return std::nullopt;
  char* end = nullptr;
  const double now = std::strtod(text.c_str() + colon + 1, &end);
  if (end == text.c_str() + colon + 1) return std::nullopt;
  return now > 1e11 ? now / 1000.0 : now;  // the aggregators' milliseconds
}

/// The time of an aircraft.json snapshot file (its "now", UTC s), if it is one. readsb and
/// dump1090 write "now" first; the aggregators' answers may end with it, so the whole
/// file is read only when its head has none.
std::optional<double> snapshot_time(const std::string& path, protocol::Format format) {
  constexpr std::size_t kHeadBytes = 65536;
  const std::string head = file_text(path, kHeadBytes);
  const auto head_bytes = std::as_bytes(std::span<const char>(head.data(), head.size()));
  if (format != protocol::Format::AircraftJson &&
      (format != protocol::Format::Auto || protocol::detect_format(head_bytes) != protocol::Format::AircraftJson))
    return std::nullopt;
  if (const std::optional<double> now = now_member(head)) return now;
  return head.size() < kHeadBytes ? std::nullopt : now_member(file_text(path));
}

/// `files` ordered by their data (ties: by name): an aircraft.json snapshot by its time,
/// another file by the newest data time of its records read alone; a file without a
/// record goes first.
std::vector<std::string> in_data_order(std::vector<std::string> files, protocol::Format format,
                                       const protocol::DecoderOptions& options) {
  std::vector<std::pair<double, std::string>> timed;
  for (std::string& file : files) {
    double newest = -std::numeric_limits<double>::infinity();
    if (const std::optional<double> now = snapshot_time(file, format)) {
      newest = *now;
    } else {
      RecordingReader alone(file, format, options);
      for (TrackReport r; alone.next(r);) newest = std::max(newest, r.t);
    }
    timed.emplace_back(newest, std::move(file));
  }
  std::stable_sort(timed.begin(), timed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> ordered;
  for (auto& [t, file] : timed) ordered.push_back(std::move(file));
  return ordered;
}

/// A set of files: passes one file's inflated bytes on to the set's one decoder, noting
/// whether they end inside a line; the set's decoder ends only with the last file.
class Forwarder final : public protocol::Decoder {
 public:
  Forwarder(protocol::Decoder& decoder, bool& line_open) : decoder_(decoder), line_open_(line_open) {}
  void feed(std::span<const std::byte> bytes, const protocol::ReportSink& sink) override {
    if (!bytes.empty()) line_open_ = bytes.back() != std::byte{'\n'};
    decoder_.feed(bytes, sink);
  }
  void finish(const protocol::ReportSink& /*sink*/) override {}
  std::string_view format_name() const override { return decoder_.format_name(); }
  std::size_t max_message_bytes() const override { return decoder_.max_message_bytes(); }

 private:
  protocol::Decoder& decoder_;
  bool& line_open_;
};
}

std::string recording_path_problem(const std::string& path) {
  if (path == kStandardInput) return {};
  if (is_pattern(path)) return files_named(path).empty() ? "no file matches " + path : std::string();
  std::error_code error;
  if (std::filesystem::is_regular_file(path, error) || std::filesystem::is_directory(path, error)) return {};
  return std::filesystem::exists(path, error) ? path + " is not a file or a directory" : "no such file: " + path;
}

RecordingReader::RecordingReader(std::string path, protocol::Format format, const protocol::DecoderOptions& options)
    : path_(std::move(path)) {
  if (path_ != kStandardInput && (is_pattern(path_) || std::filesystem::is_directory(path_))) {
    file_set_ = true;
    files_ = files_named(path_);
    decoder_ = protocol::make_decoder(format, options);
    if (TraceMerge::wanted(files_, format)) {
      traces_ = std::make_unique<TraceMerge>(files_, format, options, decoder_->rejections());
      return;
    }
    files_ = in_data_order(std::move(files_), format, options);
    chunk_.resize(kChunkBytes);
    if (files_.empty()) {
      decoder_->rejections().reject("no_files", path_ + ": no file to read");
      finished_ = true;
    }
    return;
  }
  files_ = {path_};
  file_ = path_ == kStandardInput ? stdin : std::fopen(path_.c_str(), "rb");
  if (!file_) {
    own_rejections_.reject("file_unreadable", path_);
    finished_ = true;
    return;
  }
  decoder_ = protocol::make_decoder(format, options);
  chunk_.resize(kChunkBytes);
}

RecordingReader::~RecordingReader() {
  if (file_ && file_ != stdin) std::fclose(file_);
}

bool RecordingReader::refill() {
  const auto sink = [this](const TrackReport& r) { ready_.push_back(r); };
  while (ready_.empty() && !finished_) {
    if (file_set_ && !file_ && !open_next_file()) {
      decoder_->finish(sink);
      finished_ = true;
      break;
    }
    const std::size_t n = std::fread(chunk_.data(), 1, chunk_.size(), file_);
    bytes_read_ += n;
    const std::span<const std::byte> bytes(chunk_.data(), n);
    if (n > 0 && file_set_) feed_file_bytes(bytes);
    else if (n > 0) decoder_->feed(bytes, sink);
    if (n < chunk_.size()) {
      if (std::ferror(file_)) decoder_->rejections().reject("file_unreadable", file_set_ ? files_[next_file_ - 1] : path_);
      if (!file_set_) {
        decoder_->finish(sink);
        finished_ = true;
        break;
      }
      // The file ends; the stream goes on with the next one.
      unwrap_->finish(sink);
      decoder_->rejections().merge(unwrap_->rejections());
      if (line_open_) {
        decoder_->feed_text("\n", sink);
        line_open_ = false;
      }
      std::fclose(file_);
      file_ = nullptr;
    }
  }
  return !ready_.empty();
}

bool RecordingReader::open_next_file() {
  while (next_file_ < files_.size()) {
    const std::string& name = files_[next_file_++];
    file_ = std::fopen(name.c_str(), "rb");
    if (!file_) {
      decoder_->rejections().reject("file_unreadable", name);
      continue;
    }
    unwrap_ = protocol::make_gzip_decoder(std::make_unique<Forwarder>(*decoder_, line_open_));
    return true;
  }
  return false;
}

void RecordingReader::feed_file_bytes(std::span<const std::byte> bytes) {
  unwrap_->feed(bytes, [this](const TrackReport& r) { ready_.push_back(r); });
}

std::uint64_t RecordingReader::bytes_read() const { return traces_ ? traces_->bytes_read() : bytes_read_; }

bool RecordingReader::next(TrackReport& out) {
  if (traces_) {
    if (!traces_->next(out)) return false;
    ++records_;
    return true;
  }
  if (ready_.empty() && !refill()) return false;
  out = std::move(ready_.front());
  ready_.pop_front();
  ++records_;
  return true;
}

void MergedRecordings::add(std::unique_ptr<RecordingReader> reader) {
  readers_.push_back(std::move(reader));
  heads_.emplace_back();
  primed_ = false;
}

bool MergedRecordings::next(TrackReport& out) {
  if (!primed_) {
    for (std::size_t i = 0; i < readers_.size(); ++i)
      if (!heads_[i].valid) heads_[i].valid = readers_[i]->next(heads_[i].report);
    primed_ = true;
  }
  // A linear scan: recordings are few, and this keeps ties deterministic.
  std::size_t best = heads_.size();
  for (std::size_t i = 0; i < heads_.size(); ++i) {
    if (!heads_[i].valid) continue;
    if (best == heads_.size() || heads_[i].report.t < heads_[best].report.t) best = i;
  }
  if (best == heads_.size()) return false;
  out = std::move(heads_[best].report);
  heads_[best].valid = readers_[best]->next(heads_[best].report);
  return true;
}

Rejections MergedRecordings::rejections() const {
  Rejections total;
  for (const auto& reader : readers_) total.merge(reader->rejections());
  return total;
}

}  // namespace kew::replay
