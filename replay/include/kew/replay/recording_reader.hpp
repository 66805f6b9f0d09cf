#pragma once
// Reading recordings for replay (design §5.6): one file through its decoder, read in
// chunks on demand, and several files merged into one stream in data-time order.

#include <cstdint>
#include <cstdio>
#include <deque>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "kew/protocol/formats.hpp"

namespace kew::replay {

/// The path that names standard input (a recording piped in).
inline constexpr std::string_view kStandardInput = "-";

class RecordingReader {
 public:
  /// Opens `path`, or reads standard input when it is kStandardInput (auto-detects the
  /// format when `format` is Auto; gzip is transparent).
  /// A file that cannot be opened yields no records and counts "file_unreadable".
  RecordingReader(std::string path, protocol::Format format, const protocol::DecoderOptions& options);
  ~RecordingReader();
  RecordingReader(const RecordingReader&) = delete;
  RecordingReader& operator=(const RecordingReader&) = delete;

  /// The next record in file order; false at the end of the file.
  bool next(TrackReport& out);

  const std::string& path() const { return path_; }
  /// False when the file could not be opened (then counted "file_unreadable").
  bool is_open() const { return decoder_ != nullptr; }
  /// The decoder's rejections, plus file-level problems.
  Rejections& rejections() { return decoder_ ? decoder_->rejections() : own_rejections_; }
  const Rejections& rejections() const { return decoder_ ? decoder_->rejections() : own_rejections_; }
  std::uint64_t bytes_read() const { return bytes_read_; }
  std::uint64_t records() const { return records_; }

 private:
  bool refill();

  std::string path_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<protocol::Decoder> decoder_;
  Rejections own_rejections_;
  std::deque<TrackReport> ready_;
  std::vector<std::byte> chunk_;
  bool finished_ = false;
  std::uint64_t bytes_read_ = 0;
  std::uint64_t records_ = 0;
};

/// Several recordings as one stream ordered by data time (ties: the earlier file in
/// the argument list first, then file order), as a receiver fed by all of them at once
/// would have seen them. Each file is assumed to be in time order on its own.
class MergedRecordings {
 public:
  void add(std::unique_ptr<RecordingReader> reader);
  bool next(TrackReport& out);
  std::vector<std::unique_ptr<RecordingReader>>& readers() { return readers_; }
  /// Every reader's rejections added up.
  Rejections rejections() const;

 private:
  struct Head {
    bool valid = false;
    TrackReport report;
  };
  std::vector<std::unique_ptr<RecordingReader>> readers_;
  std::vector<Head> heads_;
  bool primed_ = false;
};

}  // namespace kew::replay
