#include "line_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <spdlog/spdlog.h>

namespace kew::daemon {

LineFile::LineFile(std::string path, std::uint64_t max_bytes, int keep)
    // Absolute: the daemon changes directory to / after opening its files, and rotation
    // reopens by name.
    : path_(std::filesystem::absolute(path).string()), max_bytes_(max_bytes), keep_(keep) {
  open();
}

LineFile::~LineFile() {
  if (file_) std::fclose(file_);
}

void LineFile::open() {
  file_ = std::fopen(path_.c_str(), "ab");
  if (!file_) throw std::runtime_error(path_ + ": " + std::strerror(errno));
  std::error_code ec;
  size_ = std::filesystem::file_size(path_, ec);
  if (ec) size_ = 0;
}

void LineFile::rotate() {
  std::fclose(file_);
  file_ = nullptr;
  std::error_code ec;
  if (keep_ <= 0) {
    std::filesystem::remove(path_, ec);
  } else {
    std::filesystem::remove(path_ + "." + std::to_string(keep_), ec);
    for (int i = keep_ - 1; i >= 1; --i)
      std::filesystem::rename(path_ + "." + std::to_string(i), path_ + "." + std::to_string(i + 1), ec);
    std::filesystem::rename(path_, path_ + ".1", ec);
  }
  open();
}

void LineFile::append(std::string_view lines) {
  if (lines.empty()) return;
  if (max_bytes_ > 0 && size_ > 0 && size_ + lines.size() > max_bytes_) {
    try {
      rotate();
    } catch (const std::exception& e) {
      ++write_errors_;
      spdlog::error("cannot rotate {}: {}", path_, e.what());
      if (!file_) return;
    }
  }
  if (std::fwrite(lines.data(), 1, lines.size(), file_) != lines.size()) {
    if (++write_errors_ == 1) spdlog::error("write to {} failed: {}", path_, std::strerror(errno));
    return;
  }
  size_ += lines.size();
}

void LineFile::flush() {
  if (file_ && std::fflush(file_) != 0 && ++write_errors_ == 1)
    spdlog::error("flush of {} failed: {}", path_, std::strerror(errno));
}

}  // namespace kew::daemon
