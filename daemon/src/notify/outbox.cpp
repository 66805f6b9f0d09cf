#include "outbox.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "kew/protocol/encoders/alert_json_reader.hpp"

namespace kew::daemon {

Outbox::Outbox(std::string path, std::size_t limit, double coalesce_s)
    : path_(std::move(path)), limit_(std::max<std::size_t>(limit, 1)), coalesce_s_(coalesce_s) {}

Outbox::~Outbox() {
  if (fd_ >= 0) ::close(fd_);
}

std::string Outbox::load(double now_s) {
  if (path_.empty()) return {};
  std::ifstream in(path_);
  std::string said;
  if (in) {
    protocol::AlertStreamReader reader;
    struct Kept {
      AlertEvent event;
      NotifyState state;
      std::string line;
    };
    std::vector<Kept> kept;
    std::vector<std::uint64_t> done;
    std::size_t unreadable = 0;
    std::string line;
    while (std::getline(in, line)) {
      const std::string_view text(line);
      if (text.starts_with("H ")) {
        high_ = std::max<std::uint64_t>(high_, std::strtoull(line.c_str() + 2, nullptr, 10));
      } else if (text.starts_with("D ")) {
        for (std::size_t at = 2; at < line.size();) {
          char* end = nullptr;
          done.push_back(std::strtoull(line.c_str() + at, &end, 10));
          at = static_cast<std::size_t>(end - line.c_str()) + 1;
        }
      } else if (text.starts_with("E ") && text.find(' ', 2) != std::string_view::npos) {
        const std::size_t space = text.find(' ', 2);
        const auto state = kNotifyStateNames.parse(text.substr(2, space - 2));
        if (state && reader.read(text.substr(space + 1)) && reader.object_class() == protocol::StreamObjectClass::Alert)
          kept.push_back({reader.alert(), *state, std::string(text.substr(space + 1)) + "\n"});
        else
          ++unreadable;
      } else {
        ++unreadable;
      }
    }
    std::sort(done.begin(), done.end());
    std::size_t waiting = 0;
    for (Kept& k : kept) {
      if (std::binary_search(done.begin(), done.end(), k.event.seq)) continue;
      if (take(k.event, k.state, std::move(k.line), now_s)) ++waiting;
    }
    remember_done(done);
    said = fmt::format("{} events waiting from the last run", waiting);
    if (unreadable) said += fmt::format(", {} unreadable lines skipped", unreadable);
  }
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0640);
  if (fd_ < 0) throw std::runtime_error(fmt::format("cannot open {}: {}", path_, std::strerror(errno)));
  rewrite();
  return said;
}

bool Outbox::add(const AlertEvent& event, NotifyState state, std::string line, double now_s) {
  if (event.seq <= high_ || done_.covers(event.seq)) return false;
  return take(event, state, std::move(line), now_s);
}

bool Outbox::take(const AlertEvent& event, NotifyState state, std::string line, double now_s) {
  high_ = std::max(high_, event.seq);
  OutboxEntry* entry = nullptr;
  bool in_flight = false;  // a message about this alert is being sent
  if (coalesce_s_ > 0) {
    for (auto it = entries_.rbegin(); it != entries_.rend() && !entry; ++it) {
      if (it->latest.id != event.id) continue;
      if (it->in_flight) in_flight = true;
      else entry = &*it;
    }
  }
  if (!entry) {
    OutboxEntry fresh;
    fresh.queued_s = now_s;
    fresh.not_before_s = now_s;
    if (in_flight) fresh.not_before_s = now_s + coalesce_s_;
    else if (const auto sent = last_sent_s_.find(event.id); coalesce_s_ > 0 && sent != last_sent_s_.end())
      fresh.not_before_s = std::max(now_s, sent->second + coalesce_s_);
    entries_.push_back(std::move(fresh));
    entry = &entries_.back();
  }
  entry->seqs.push_back(event.seq);
  entry->states.push_back(state);
  entry->lines.push_back(std::move(line));
  entry->latest = event;
  entry->highest = std::max(entry->highest, event.severity);
  ++events_;
  append(*entry, entry->lines.size() - 1);
  while (events_ > limit_) drop_oldest();
  return true;
}

void Outbox::drop_oldest() {
  auto victim = std::find_if(entries_.begin(), entries_.end(), [](const OutboxEntry& e) { return !e.in_flight; });
  if (victim == entries_.end()) return;
  // The oldest event goes first: from a coalesced entry, only its first event.
  const std::uint64_t seq = victim->seqs.front();
  victim->seqs.erase(victim->seqs.begin());
  victim->states.erase(victim->states.begin());
  live_bytes_ -= std::min(live_bytes_, victim->lines.front().size() + 16);
  victim->lines.erase(victim->lines.begin());
  if (victim->seqs.empty()) entries_.erase(victim);
  --events_;
  ++dropped_;
  ++new_drops_;
  remember_done({seq});
  record_done({seq});
}

OutboxEntry* Outbox::next_due(double now_s, double& wake_s, bool in_order) {
  wake_s = std::numeric_limits<double>::infinity();
  for (OutboxEntry& entry : entries_) {
    if (entry.in_flight) {
      if (in_order) return nullptr;
      continue;
    }
    if (entry.not_before_s <= now_s) return &entry;
    wake_s = std::min(wake_s, entry.not_before_s);
    if (in_order) return nullptr;
  }
  return nullptr;
}

std::deque<OutboxEntry>::iterator Outbox::find(std::uint64_t first_seq) {
  return std::find_if(entries_.begin(), entries_.end(), [&](const OutboxEntry& e) { return e.seqs.front() == first_seq; });
}

void Outbox::returned(std::uint64_t first_seq) {
  if (const auto it = find(first_seq); it != entries_.end()) it->in_flight = false;
}

void Outbox::delivered(std::uint64_t first_seq, double now_s) {
  const auto it = find(first_seq);
  if (it == entries_.end()) return;
  if (it->latest.state == AlertState::End) last_sent_s_.erase(it->latest.id);
  else last_sent_s_[it->latest.id] = now_s;
  const std::vector<std::uint64_t> seqs = it->seqs;
  events_ -= seqs.size();
  for (const std::string& line : it->lines) live_bytes_ -= std::min(live_bytes_, line.size() + 16);
  entries_.erase(it);
  remember_done(seqs);
  record_done(seqs);
}

void Outbox::forget(const DeliveryProgress& progress) {
  bool changed = false;
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (it->in_flight) {
      ++it;
      continue;
    }
    for (std::size_t i = it->seqs.size(); i-- > 0;) {
      if (!progress.covers(it->seqs[i])) continue;
      it->seqs.erase(it->seqs.begin() + static_cast<std::ptrdiff_t>(i));
      it->states.erase(it->states.begin() + static_cast<std::ptrdiff_t>(i));
      it->lines.erase(it->lines.begin() + static_cast<std::ptrdiff_t>(i));
      --events_;
      changed = true;
    }
    it = it->seqs.empty() ? entries_.erase(it) : std::next(it);
  }
  done_.merge(progress);
  high_ = std::max(high_, progress.through);
  done_ = this->progress();
  if (changed) rewrite();
}

void Outbox::remember_done(const std::vector<std::uint64_t>& seqs) {
  DeliveryProgress delivered;
  delivered.also = seqs;
  delivered.also.erase(std::unique(delivered.also.begin(), delivered.also.end()), delivered.also.end());
  done_.merge(delivered);
  // Only what lies above the first waiting event need be remembered.
  done_ = progress();
}

DeliveryProgress Outbox::progress() const {
  DeliveryProgress progress;
  progress.through = entries_.empty() ? high_ : entries_.front().seqs.front() - 1;
  for (const OutboxEntry& entry : entries_) progress.through = std::min(progress.through, entry.seqs.front() - 1);
  for (const std::uint64_t seq : done_.also)
    if (seq > progress.through) progress.also.push_back(seq);
  return progress;
}

std::uint64_t Outbox::take_new_drops() { return std::exchange(new_drops_, 0); }

std::optional<double> Outbox::oldest_queued_s() const {
  if (entries_.empty()) return std::nullopt;
  double oldest = entries_.front().queued_s;
  for (const OutboxEntry& entry : entries_) oldest = std::min(oldest, entry.queued_s);
  return oldest;
}

void Outbox::append(const OutboxEntry& entry, std::size_t event) {
  if (fd_ < 0) return;
  std::string text = fmt::format("E {} ", to_string(entry.states[event]));
  text += entry.lines[event];
  live_bytes_ += entry.lines[event].size() + 16;
  write(text);
}

void Outbox::record_done(const std::vector<std::uint64_t>& seqs) {
  if (fd_ < 0) return;
  if (entries_.empty()) {
    rewrite();
    return;
  }
  write(fmt::format("D {}\n", fmt::join(seqs, " ")));
  // A journal that has grown well past what waits is written again with only that.
  if (file_bytes_ > 4 * live_bytes_ + (1u << 20)) rewrite();
}

void Outbox::write(const std::string& text) {
  // One write per record: a crash leaves at most its last line torn, which load() skips.
  const ssize_t n = ::write(fd_, text.data(), text.size());
  if (n != static_cast<ssize_t>(text.size())) ++write_errors_;
  file_bytes_ += text.size();
  dirty_ = true;
}

void Outbox::rewrite() {
  if (fd_ < 0) return;
  std::string text = fmt::format("H {}\n", high_);
  std::size_t live = 0;
  std::vector<std::pair<std::uint64_t, std::string>> records;
  for (const OutboxEntry& entry : entries_)
    for (std::size_t i = 0; i < entry.seqs.size(); ++i) {
      records.emplace_back(entry.seqs[i], fmt::format("E {} {}", to_string(entry.states[i]), entry.lines[i]));
      live += entry.lines[i].size() + 16;
    }
  std::sort(records.begin(), records.end());
  for (const auto& record : records) text += record.second;
  // Delivered above the first waiting event (coalesced messages): not to be sent again.
  if (!done_.also.empty()) text += fmt::format("D {}\n", fmt::join(done_.also, " "));
  const std::string temporary = path_ + ".new";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0640);
  // Not forced to the disk here (the caller holds its notifier's lock): sync_handle()
  // does that outside the lock once a second; a crash of kewd alone loses nothing.
  const bool written = fd >= 0 && ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  if (fd >= 0) ::close(fd);
  if (!written || ::rename(temporary.c_str(), path_.c_str()) != 0) {
    ++write_errors_;
    return;
  }
  ::close(fd_);
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) ++write_errors_;
  file_bytes_ = text.size();
  live_bytes_ = live;
  dirty_ = true;
}

int Outbox::sync_handle() {
  if (fd_ < 0 || !dirty_) return -1;
  dirty_ = false;
  return ::dup(fd_);
}

void Outbox::sync() {
  if (const int fd = sync_handle(); fd >= 0) {
    if (::fdatasync(fd) != 0) ++write_errors_;
    ::close(fd);
  }
}

}  // namespace kew::daemon
