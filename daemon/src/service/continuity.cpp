#include "continuity.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "kew/protocol/encoders/alert_json_reader.hpp"

namespace kew::daemon {

namespace {

constexpr const char* kStateFileName = "kewd.state";

std::uint16_t number_after(std::uint16_t number) {
  return static_cast<std::uint16_t>(number == 0xffff ? 1 : number + 1);
}

/// write(2) of all of `text`; false with errno set when it could not.
bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace

std::string make_run_id() {
  unsigned char bytes[16];
  std::size_t have = 0;
  while (have < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + have, sizeof bytes - have, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(std::string("getrandom: ") + std::strerror(errno));
    have += static_cast<std::size_t>(n);
  }
  std::string id;
  for (unsigned char b : bytes) id += fmt::format("{:02x}", b);
  return id;
}

StateFile::StateFile(const std::string& directory)
    : directory_(directory), path_((std::filesystem::path(directory) / kStateFileName).string()) {
  std::error_code ec;
  std::filesystem::create_directories(directory_, ec);
  if (ec) throw std::runtime_error("state directory " + directory_ + ": " + ec.message());
}

std::optional<Numbering> StateFile::load() const {
  std::ifstream in(path_);
  if (!in) return std::nullopt;
  // "KEY VALUE" lines; '#' comments; unknown keys are ignored (a later release may add).
  Numbering n;
  bool have_seq = false, have_number = false;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string key;
    std::uint64_t value = 0;
    if (!(fields >> key >> value)) continue;
    if (key == "seq") {
      n.last_seq = value;
      have_seq = true;
    } else if (key == "next_number" && value >= 1 && value <= 0xffff) {
      n.next_number = static_cast<std::uint16_t>(value);
      have_number = true;
    }
  }
  if (!have_seq || !have_number) {
    spdlog::warn("{}: not a state file kewd wrote (ignored)", path_);
    return std::nullopt;
  }
  return n;
}

bool StateFile::save(const Numbering& numbering, const std::string& run_id, std::string& error) const {
  const std::string temporary = path_ + ".tmp";
  const std::string text = fmt::format(
      "# kewd's numbering (design §4.7), replaced atomically; kewd continues from it and the alert log\n"
      "seq {}\nnext_number {}\nrun {}\n",
      numbering.last_seq, numbering.next_number, run_id);
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = temporary + ": " + std::strerror(errno);
    return false;
  }
  // fsync before the rename: otherwise a power cut may leave the new name on an empty file.
  const bool written = write_all(fd, text) && ::fsync(fd) == 0;
  const int saved_errno = errno;
  ::close(fd);
  if (!written) {
    error = temporary + ": " + std::strerror(saved_errno);
    ::unlink(temporary.c_str());
    return false;
  }
  if (::rename(temporary.c_str(), path_.c_str()) != 0) {
    error = path_ + ": " + std::strerror(errno);
    ::unlink(temporary.c_str());
    return false;
  }
  // The rename itself is durable once the directory is synced.
  const int dir = ::open(directory_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
  return true;
}

AlertLogTail read_alert_log_tail(const std::string& path) {
  AlertLogTail tail;
  protocol::AlertStreamReader reader;
  // id → (seq of its New, last event): the alerts not ended so far.
  std::map<std::string, std::pair<std::uint64_t, AlertEvent>> open;
  for (const std::string& file : {path + ".1", path}) {
    std::ifstream in(file, std::ios::binary);
    if (!in) continue;
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      ++tail.lines;
      if (!reader.read(line)) {
        ++tail.unreadable_lines;
        continue;
      }
      tail.last_seq = std::max(tail.last_seq, reader.seq());
      if (reader.object_class() != protocol::StreamObjectClass::Alert) continue;
      const AlertEvent& e = reader.alert();
      tail.last_t = std::max(tail.last_t, e.t);
      if (e.state == AlertState::New) {
        tail.next_number = number_after(e.number);
        tail.new_seq = e.seq;
        open[e.id] = {e.seq, e};
      } else if (e.state == AlertState::Update) {
        auto it = open.find(e.id);
        // An Update whose New is in a file rotated away: open since before it.
        if (it == open.end()) open[e.id] = {e.seq, e};
        else it->second.second = e;
      } else {
        open.erase(e.id);
      }
    }
  }
  std::vector<std::pair<std::uint64_t, AlertEvent>> ordered;
  for (auto& [id, entry] : open) ordered.push_back(std::move(entry));
  std::sort(ordered.begin(), ordered.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  for (auto& entry : ordered) tail.open.push_back(std::move(entry.second));
  return tail;
}

Numbering resume_point(const std::optional<Numbering>& saved, const AlertLogTail& tail) {
  Numbering n = saved.value_or(Numbering{});
  n.last_seq = std::max(n.last_seq, tail.last_seq);
  // The log saw a New the state file had not (a SIGKILL between state writes).
  if (tail.next_number && (!saved || tail.new_seq > saved->last_seq)) n.next_number = *tail.next_number;
  return n;
}

RunContinuity::RunContinuity(const std::string& state_directory) : run_id_(make_run_id()) {
  if (!state_directory.empty()) state_ = std::make_unique<StateFile>(state_directory);
}

RunContinuity::Beginning RunContinuity::begin(const std::string& alert_log_path) {
  const std::optional<Numbering> saved = state_ ? state_->load() : std::nullopt;
  AlertLogTail tail;
  if (!alert_log_path.empty()) tail = read_alert_log_tail(alert_log_path);
  if (tail.unreadable_lines)
    spdlog::warn("alert log {}: {} of {} lines unreadable (skipped while looking for open alerts)", alert_log_path,
                 tail.unreadable_lines, tail.lines);
  Beginning beginning;
  beginning.numbering = resume_point(saved, tail);
  beginning.start_seq = beginning.numbering.last_seq;
  for (AlertEvent event : tail.open) {
    event.state = AlertState::End;
    event.end_reason = AlertEndReason::Restart;
    event.t = tail.last_t;
    event.seq = ++beginning.numbering.last_seq;
    beginning.ended.push_back(std::move(event));
  }
  return beginning;
}

void RunContinuity::save(const Numbering& now) {
  if (!state_) return;
  if (saved_ && now.last_seq == saved_->last_seq && now.next_number == saved_->next_number) return;
  std::string error;
  if (state_->save(now, run_id_, error)) {
    saved_ = now;
    if (errors_) spdlog::info("state file {} written again", state_->path());
    errors_ = 0;
    return;
  }
  // One failure a second at most (the housekeeping's period): the first, then each minute.
  if (errors_++ % 60 == 0)
    spdlog::error("cannot save the numbering: {} ({} failures; the alert log's tail still guards it)", error,
                  errors_);
}

}  // namespace kew::daemon
