#pragma once
// A notifier's outbox (design §5.10): the alert events waiting for delivery, bounded
// (beyond `limit` events the oldest is dropped and counted), kept in a file so that a
// restart delivers what was waiting and nothing twice. For the templates people read, an
// alert's events that arrive while a message about it waits, or within `coalesce_s` of
// its last message, go as one message.
//
// The file is a journal of lines: "E <state> <ALERT object>" for each event taken,
// "D <seq> …" for events delivered or dropped, "H <seq>" for the highest seq taken
// before the file was last rewritten. It is rewritten with only what waits when it has
// grown well past that, and emptied when nothing waits. Not thread-safe: its notifier
// guards it.

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "delivery_progress.hpp"
#include "kew/alert/alert_event.hpp"
#include "kew/daemon/notify_config.hpp"

namespace kew::daemon {

/// One message to send: one event, or an alert's coalesced events.
struct OutboxEntry {
  std::vector<std::uint64_t> seqs;   ///< ascending; the first is the entry's place in line
  std::vector<NotifyState> states;   ///< of each event
  std::vector<std::string> lines;    ///< each event's ALERT object, as the stream writes it
  AlertEvent latest;                 ///< the last event
  Severity highest = Severity::None; ///< the highest severity of its events
  double not_before_s = 0.0;         ///< held (coalescing) until then, steady seconds
  double queued_s = 0.0;             ///< when its first event came, steady seconds
  bool in_flight = false;
};

class Outbox {
 public:
  /// `path` "": in memory only (a replay keeps nothing).
  Outbox(std::string path, std::size_t limit, double coalesce_s);
  ~Outbox();
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;

  /// Reads the file of an earlier run: what it held and did not deliver waits again.
  /// Returns what the log should say ("" when there was no file); a line it cannot read
  /// (the torn end of a crash) is skipped and said.
  std::string load(double now_s);

  /// Takes an event classified `state`, `line` its ALERT object. False (nothing done) when
  /// its seq is not above every one taken before: an event computed again.
  bool add(const AlertEvent& event, NotifyState state, std::string line, double now_s);
  /// The first entry in line that is due at `now_s` and not in flight; nullptr when none,
  /// `wake_s` then the earliest moment one becomes due (infinity when none waits).
  /// `in_order`: only the first entry in line may go (every event, in order).
  OutboxEntry* next_due(double now_s, double& wake_s, bool in_order);
  /// The entry whose first seq is `first_seq` was not delivered: it waits again.
  void returned(std::uint64_t first_seq);
  /// The entry whose first seq is `first_seq` was delivered at `now_s`: removed.
  void delivered(std::uint64_t first_seq, double now_s);
  /// Drops what `progress` says was delivered (by this instance before, or another).
  void forget(const DeliveryProgress& progress);
  /// What this outbox has delivered or dropped: every seq up to the first waiting one.
  DeliveryProgress progress() const;

  std::size_t waiting_events() const { return events_; }
  std::uint64_t dropped() const { return dropped_; }
  /// Dropped since the last call (for the log).
  std::uint64_t take_new_drops();
  std::uint64_t write_errors() const { return write_errors_; }
  /// Kept in a file (not in memory only).
  bool persistent() const { return !path_.empty(); }
  /// When the oldest waiting event came (steady seconds); nullopt when none waits.
  std::optional<double> oldest_queued_s() const;
  /// Forces what was written to the disk (once a second, when something was).
  void sync();
  /// For sync() outside the caller's lock: a duplicate of the file's descriptor to
  /// fdatasync and close, or -1 when nothing was written since the last.
  int sync_handle();

 private:
  bool take(const AlertEvent& event, NotifyState state, std::string line, double now_s);
  void append(const OutboxEntry& entry, std::size_t event);
  void record_done(const std::vector<std::uint64_t>& seqs);
  void write(const std::string& text);
  void rewrite();
  void drop_oldest();
  std::deque<OutboxEntry>::iterator find(std::uint64_t first_seq);
  void remember_done(const std::vector<std::uint64_t>& seqs);

  std::string path_;
  std::size_t limit_;
  double coalesce_s_;
  int fd_ = -1;
  bool dirty_ = false;
  std::size_t file_bytes_ = 0;
  std::size_t live_bytes_ = 0;
  std::deque<OutboxEntry> entries_;  // in line (first seq ascending)
  std::size_t events_ = 0;
  std::uint64_t high_ = 0;
  DeliveryProgress done_;  // delivered or dropped
  std::unordered_map<std::string, double> last_sent_s_;  // alert id → its last message
  std::uint64_t dropped_ = 0;
  std::uint64_t new_drops_ = 0;
  std::uint64_t write_errors_ = 0;
};

}  // namespace kew::daemon
