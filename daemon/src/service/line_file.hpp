#pragma once
// An append-only file of lines, rotated by size (FILE → FILE.1 → ... → FILE.keep), used
// for the alert log and for the recording of input records (design §6.6).
//
// Lines are complete or absent in the file: they are queued in memory and written with
// write(2) on an O_APPEND descriptor; when a write is cut short (disk full, quota, I/O
// error) the piece of a line that reached the file is truncated away, and the lines not
// written stay queued and are written by the next flush(). The queue is bounded in
// bytes: beyond the bound the oldest lines are dropped, counted and logged; a line
// queued, written or dropped costs constant time however full the queue is, so a file
// that cannot be written never slows its writer. A torn last
// line found at open (a crash of another writer, a full disk before this class existed)
// is cut off too, so that the next line never joins it.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace kew::daemon {

class LineFile {
 public:
  /// Queued bytes kept while the file cannot be written (design §6.6: about a day of
  /// alert events of a busy sector; the oldest are dropped beyond it).
  static constexpr std::uint64_t kDefaultMaxPendingBytes = 64ull << 20;

  /// `max_bytes` = 0: never rotate. `sync_every_flush`: fdatasync after each flush that
  /// wrote something (alert_log_sync = "every"). Throws std::runtime_error when the file
  /// cannot be opened for appending.
  LineFile(std::string path, std::uint64_t max_bytes, int keep, bool sync_every_flush = false,
           std::uint64_t max_pending_bytes = kDefaultMaxPendingBytes);
  ~LineFile();
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  /// Queues text made of whole lines; writes when much is queued (64 KiB).
  void append(std::string_view lines);
  /// Writes everything queued. False when some lines are still queued (failing()).
  bool flush();
  /// fdatasync when something was written since the last one (alert_log_sync
  /// "interval"); false when it failed.
  bool sync();

  const std::string& path() const { return path_; }
  /// Failed writes, rotations and syncs.
  std::uint64_t write_errors() const { return write_errors_; }
  /// The last flush left lines queued: the file cannot take them now.
  bool failing() const { return failing_; }
  std::uint64_t pending_bytes() const { return pending_.size() - head_; }
  /// Lines dropped from the queue because it reached its bound.
  std::uint64_t dropped_lines() const { return dropped_lines_; }

 private:
  void open();
  void rotate();
  /// The file ends with a whole line: cuts off a torn last line.
  void cut_torn_tail();
  /// Keeps the first `written` queued bytes that reached the file up to the last whole
  /// line, truncating the file after it. False when the truncation failed.
  bool keep_whole_lines(std::size_t written);
  void drop_oldest(std::size_t incoming);
  /// The first `bytes` queued are gone (written or dropped).
  void consume(std::size_t bytes);
  /// Counts a failure; logs it, with the counts, at most every 10 s.
  void report_failure(std::string_view what, std::string_view reason);

  std::string path_;
  std::uint64_t max_bytes_;
  int keep_;
  bool sync_every_flush_;
  std::uint64_t max_pending_bytes_;
  int fd_ = -1;
  std::uint64_t size_ = 0;  // bytes of whole lines in the file
  std::string pending_;     // from head_: whole lines not yet in the file
  std::size_t head_ = 0;    // bytes of pending_ already written or dropped
  /// A truncation that failed: the file must be cut to this size before the next write.
  std::optional<std::uint64_t> truncate_to_;
  bool unsynced_ = false;
  bool failing_ = false;
  std::uint64_t write_errors_ = 0;
  std::uint64_t errors_since_report_ = 0;
  std::uint64_t dropped_lines_ = 0;
  std::chrono::steady_clock::time_point last_report_{};
};

}  // namespace kew::daemon
