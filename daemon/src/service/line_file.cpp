#include "line_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <spdlog/spdlog.h>

namespace kew::daemon {

namespace {

// Queued this much without a flush (the recording between ticks), the file is written.
constexpr std::size_t kWriteAtBytes = 64 * 1024;
// Repeated failures (a retry per event while the disk is full) are logged this often.
constexpr auto kReportEvery = std::chrono::seconds(10);

}  // namespace

LineFile::LineFile(std::string path, std::uint64_t max_bytes, int keep, bool sync_every_flush,
                   std::uint64_t max_pending_bytes)
    // Absolute: the daemon changes directory to / after opening its files, and rotation
    // reopens by name.
    : path_(std::filesystem::absolute(path).string()),
      max_bytes_(max_bytes),
      keep_(keep),
      sync_every_flush_(sync_every_flush),
      max_pending_bytes_(max_pending_bytes) {
  open();
  cut_torn_tail();
}

LineFile::~LineFile() {
  if (fd_ >= 0) ::close(fd_);
}

void LineFile::open() {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0666);
  if (fd_ < 0) throw std::runtime_error(path_ + ": " + std::strerror(errno));
  struct stat st {};
  size_ = ::fstat(fd_, &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
}

void LineFile::cut_torn_tail() {
  if (size_ == 0) return;
  const int in = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) return;
  // Back from the end in blocks to the last line end.
  char block[4096];
  std::uint64_t end = size_;
  std::optional<std::uint64_t> keep;
  while (end > 0 && !keep) {
    const std::uint64_t start = end > sizeof block ? end - sizeof block : 0;
    const ssize_t n = ::pread(in, block, end - start, static_cast<off_t>(start));
    if (n != static_cast<ssize_t>(end - start)) {  // unreadable: leave the file as it is
      ::close(in);
      return;
    }
    for (std::uint64_t i = end - start; i > 0; --i) {
      if (block[i - 1] == '\n') {
        keep = start + i;
        break;
      }
    }
    if (keep == size_) {
      ::close(in);
      return;
    }
    end = start;
  }
  ::close(in);
  const std::uint64_t whole = keep.value_or(0);
  if (::ftruncate(fd_, static_cast<off_t>(whole)) != 0) {
    report_failure("cut the torn last line of", std::strerror(errno));
    return;
  }
  spdlog::warn("{}: cut a torn last line of {} bytes (an earlier writer stopped mid-line)", path_, size_ - whole);
  size_ = whole;
}

void LineFile::rotate() {
  ::close(fd_);
  fd_ = -1;
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
  if (pending_bytes() + lines.size() > max_pending_bytes_) drop_oldest(lines.size());
  pending_.append(lines);
  if (!failing_ && pending_bytes() >= kWriteAtBytes) flush();
}

void LineFile::drop_oldest(std::size_t incoming) {
  const std::uint64_t total = pending_bytes() + incoming;
  if (pending_bytes() == 0 || total <= max_pending_bytes_) return;
  const std::size_t excess =
      static_cast<std::size_t>(std::min<std::uint64_t>(total - max_pending_bytes_, pending_bytes()));
  // Whole lines only: the cut goes after the line end at or beyond `excess`.
  const std::size_t end = pending_.find('\n', head_ + excess - 1);
  const std::size_t cut = end == std::string::npos ? pending_.size() : end + 1;
  const auto lines = static_cast<std::uint64_t>(
      std::count(pending_.begin() + static_cast<long>(head_), pending_.begin() + static_cast<long>(cut), '\n'));
  if (dropped_lines_ == 0)
    spdlog::error("{}: more than {} bytes wait for the file: the oldest queued lines are dropped (counted in the "
                  "failure reports)", path_, max_pending_bytes_);
  dropped_lines_ += lines;
  consume(cut - head_);
}

void LineFile::consume(std::size_t bytes) {
  head_ += bytes;
  // Moving what remains costs at most what was consumed since the last move: constant
  // time per byte queued, however full the queue (a full disk under heavy traffic).
  if (head_ == pending_.size()) {
    pending_.clear();
    head_ = 0;
  } else if (head_ >= pending_.size() / 2) {
    pending_.erase(0, head_);
    head_ = 0;
  }
}

bool LineFile::flush() {
  if (pending_bytes() == 0) return true;
  if (truncate_to_ && fd_ >= 0) {
    if (::ftruncate(fd_, static_cast<off_t>(*truncate_to_)) != 0) {
      failing_ = true;
      report_failure("truncate", std::strerror(errno));
      return false;
    }
    truncate_to_.reset();
  }
  if (fd_ < 0 || (max_bytes_ > 0 && size_ > 0 && size_ + pending_bytes() > max_bytes_)) {
    try {
      if (fd_ < 0) open();
      else rotate();
    } catch (const std::exception& e) {
      truncate_to_.reset();  // the torn piece, if any, went with the renamed file
      report_failure("rotate", e.what());
      if (fd_ < 0) {
        failing_ = true;
        return false;
      }
    }
  }
  const std::string_view queued = std::string_view(pending_).substr(head_);
  std::size_t written = 0;
  int error = 0;
  while (written < queued.size()) {
    const ssize_t n = ::write(fd_, queued.data() + written, queued.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = n < 0 ? errno : ENOSPC;
      break;
    }
    written += static_cast<std::size_t>(n);
  }
  if (written > 0) unsynced_ = true;
  if (written == queued.size()) {
    size_ += written;
    consume(written);
    if (failing_) {
      spdlog::info("{}: writable again; every queued line written ({} failed attempts, {} lines dropped)", path_,
                   write_errors_, dropped_lines_);
      failing_ = false;
    }
    if (sync_every_flush_) sync();
    return true;
  }
  keep_whole_lines(written);
  failing_ = true;
  report_failure("write to", std::strerror(error));
  return false;
}

bool LineFile::keep_whole_lines(std::size_t written) {
  const std::string_view queued = std::string_view(pending_).substr(head_);
  const std::size_t last_end = written == 0 ? std::string::npos : queued.rfind('\n', written - 1);
  const std::size_t whole = last_end == std::string::npos ? 0 : last_end + 1;
  if (whole < written && ::ftruncate(fd_, static_cast<off_t>(size_ + whole)) != 0) {
    // The torn piece stays until a truncation succeeds; nothing is written after it.
    truncate_to_ = size_ + whole;
    report_failure("truncate", std::strerror(errno));
  }
  size_ += whole;
  consume(whole);
  return !truncate_to_;
}

bool LineFile::sync() {
  if (fd_ < 0 || !unsynced_) return true;
  if (::fdatasync(fd_) == 0) {
    unsynced_ = false;
    if (failing_ && pending_bytes() == 0 && !truncate_to_) failing_ = false;
    return true;
  }
  // The written pages may be lost (EIO): say so, and sync again next time.
  failing_ = true;
  report_failure("sync", std::strerror(errno));
  return false;
}

void LineFile::report_failure(std::string_view what, std::string_view reason) {
  ++write_errors_;
  ++errors_since_report_;
  const auto now = std::chrono::steady_clock::now();
  if (write_errors_ > 1 && now - last_report_ < kReportEvery) return;
  spdlog::error("cannot {} {}: {} ({} failures in all, {} since the last report; {} bytes queued, {} lines dropped)",
                what, path_, reason, write_errors_, errors_since_report_, pending_bytes(),
                dropped_lines_);
  errors_since_report_ = 0;
  last_report_ = now;
}

}  // namespace kew::daemon
