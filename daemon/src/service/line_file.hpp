#pragma once
// An append-only file of lines, rotated by size (FILE → FILE.1 → ... → FILE.keep), used
// for the alert log (flushed per alert, so no alert is lost without subscribers) and
// for the recording of input records (flushed each tick).

#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace kew::daemon {

class LineFile {
 public:
  /// `max_bytes` = 0: never rotate. Throws std::runtime_error when the file cannot be
  /// opened for appending.
  LineFile(std::string path, std::uint64_t max_bytes, int keep);
  ~LineFile();
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  /// Appends text made of whole lines; rotates first when it would exceed max_bytes.
  void append(std::string_view lines);
  void flush();
  const std::string& path() const { return path_; }
  std::uint64_t write_errors() const { return write_errors_; }

 private:
  void open();
  void rotate();

  std::string path_;
  std::uint64_t max_bytes_;
  int keep_;
  std::FILE* file_ = nullptr;
  std::uint64_t size_ = 0;
  std::uint64_t write_errors_ = 0;
};

}  // namespace kew::daemon
