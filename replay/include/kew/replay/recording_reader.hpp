#pragma once
// Reading recordings for replay (design §5.6): one file through its decoder, read in
// chunks on demand; a directory or a glob pattern of files (a receiver's history_N.json
// snapshots) as one stream through one decoder, the files in the order of their data;
// a directory or pattern of readsb traces (one aircraft a file, each spanning the day)
// merged record by record in data-time order (src/trace_merge.hpp); and several
// recordings merged into one stream in data-time order.

#include <cstdint>
#include <cstdio>
#include <deque>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "kew/protocol/formats.hpp"

namespace kew::replay {

class TraceMerge;

/// The path that names standard input (a recording piped in).
inline constexpr std::string_view kStandardInput = "-";

/// Why `path` names no recording RecordingReader can read ("" when it does): standard
/// input, an existing file, a directory, or a glob pattern that matches a file. For the
/// tools' command lines.
std::string recording_path_problem(const std::string& path);

class RecordingReader {
 public:
  /// Opens `path`, or reads standard input when it is kStandardInput (auto-detects the
  /// format when `format` is Auto; gzip is transparent). A directory, or a path with a
  /// glob pattern (`*`, `?`, `[`), is every regular file it names (a directory's hidden
  /// files aside), read one after another through one decoder in the order of their
  /// newest data time (a snapshot's time, its "now", read from its head unless it ends
  /// with it: readsb's history_N.json files are numbered round a ring), each file gzip
  /// or not; a line left without its newline at a file's
  /// end is ended there. A set of readsb traces (`format` readsb-trace, or auto and the
  /// files' first bytes say so) is instead merged record by record in data-time order
  /// across its files, in memory bounded by the segments under way
  /// (src/trace_merge.hpp); readsb's globe_history keeps them in 256 folders, named by
  /// a pattern such as `DAY/traces/*/trace_full_*.json`. A file that cannot be opened
  /// yields no records and counts "file_unreadable"; a pattern or directory that names
  /// no file counts "no_files".
  RecordingReader(std::string path, protocol::Format format, const protocol::DecoderOptions& options);
  ~RecordingReader();
  RecordingReader(const RecordingReader&) = delete;
  RecordingReader& operator=(const RecordingReader&) = delete;

  /// The next record in file order; false at the end of the file.
  bool next(TrackReport& out);

  const std::string& path() const { return path_; }
  /// The files read, in reading order (one, unless a directory or a pattern; a set of
  /// traces, merged, in name order).
  const std::vector<std::string>& files() const { return files_; }
  /// False when the file could not be opened (then counted "file_unreadable").
  bool is_open() const { return decoder_ != nullptr; }
  /// The decoder's rejections, plus file-level problems.
  Rejections& rejections() { return decoder_ ? decoder_->rejections() : own_rejections_; }
  const Rejections& rejections() const { return decoder_ ? decoder_->rejections() : own_rejections_; }
  std::uint64_t bytes_read() const;
  std::uint64_t records() const { return records_; }

 private:
  bool refill();
  /// A set of files: the next one opened (false when none is left).
  bool open_next_file();
  /// A set of files: the current one's bytes through its own gzip layer.
  void feed_file_bytes(std::span<const std::byte> bytes);

  std::string path_;
  std::vector<std::string> files_;
  std::unique_ptr<TraceMerge> traces_;  // a set of readsb traces
  std::size_t next_file_ = 0;
  bool file_set_ = false;
  std::unique_ptr<protocol::Decoder> unwrap_;  // a set's current file: gzip, then the decoder
  bool line_open_ = false;  // a set: the bytes fed so far do not end with a newline
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
