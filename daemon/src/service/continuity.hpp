#pragma once
// What one run of kewd hands to the next (design §4.7): the last sequence number and the
// next alert number, so that neither is reused, and the alerts the alert log leaves
// open, which the next run ends with reason "restart" before any alert of its own.
//
// Two sources, because neither is enough alone: the state file is written at most once
// a second and at shutdown (a SIGKILL loses its last second), and the alert log may be
// absent, rotated away or deleted. The next run continues from the later of the two.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kew/alert/alert_event.hpp"

namespace kew::daemon {

/// Where the numbering stands: the last `seq` emitted and the number the next alert gets.
struct Numbering {
  std::uint64_t last_seq = 0;
  std::uint16_t next_number = 1;
};

/// A fresh run id: 128 random bits (getrandom) as 32 hex digits.
std::string make_run_id();

/// The small state file `DIR/kewd.state`, replaced atomically (temporary file, fsync,
/// rename, fsync of the directory), so a crash leaves the old or the new one.
class StateFile {
 public:
  /// Creates `directory` when missing. Throws std::runtime_error when it cannot.
  explicit StateFile(const std::string& directory);

  /// The numbering last saved; nullopt when there is no file yet or it cannot be read
  /// (logged).
  std::optional<Numbering> load() const;
  /// False (logged by the caller) when the file could not be replaced.
  bool save(const Numbering& numbering, const std::string& run_id, std::string& error) const;
  const std::string& path() const { return path_; }

 private:
  std::string directory_;
  std::string path_;
};

/// What the alert log of the previous runs shows.
struct AlertLogTail {
  std::uint64_t last_seq = 0;
  /// Number after the last New event's (the seq of that event in `new_seq`); nullopt
  /// when the files read have no New event.
  std::optional<std::uint16_t> next_number;
  std::uint64_t new_seq = 0;
  /// Latest data time of an ALERT event (the End events of a restart carry it).
  double last_t = 0.0;
  /// The last event of every alert without an End, in the order they opened.
  std::vector<AlertEvent> open;
  std::uint64_t lines = 0;
  std::uint64_t unreadable_lines = 0;
};

/// Reads `path.1` (an alert open across the last rotation opened there) and `path`.
/// Unreadable lines are counted and skipped.
AlertLogTail read_alert_log_tail(const std::string& path);

/// The later of the saved numbering and the log's (by seq; numbers follow the source
/// that saw the last New).
Numbering resume_point(const std::optional<Numbering>& saved, const AlertLogTail& tail);

/// One run's continuity: its id, where its numbering resumes, and the state file kept
/// current while it runs.
class RunContinuity {
 public:
  /// A fresh run id; `state_directory` empty: no state file (a replay, or none set).
  /// Throws std::runtime_error when the directory cannot be created.
  explicit RunContinuity(const std::string& state_directory);

  const std::string& run_id() const { return run_id_; }
  /// The state file's path, "" without one.
  std::string state_path() const { return state_ ? state_->path() : std::string(); }

  /// Where the run begins (design §4.7).
  struct Beginning {
    /// The last seq before this run: its START object carries it.
    std::uint64_t start_seq = 0;
    /// The End (reason "restart") of every alert the last run left open, with the last
    /// data time it logged and seqs after start_seq: ended, not resumed under their ids,
    /// because this run does not know whether the pair is still in conflict until its
    /// tracks are rebuilt (if it is, the alert opens again under a new id).
    std::vector<AlertEvent> ended;
    /// The numbering after them, for the alert manager.
    Numbering numbering;
  };
  /// From the state file and the alert log at `alert_log_path` ("" none).
  Beginning begin(const std::string& alert_log_path);
  /// Saves `now` when it moved since the last save; a failure is counted and logged at
  /// the first and then once a minute of them (the alert log's tail still guards it).
  void save(const Numbering& now);

 private:
  std::string run_id_;
  std::unique_ptr<StateFile> state_;
  std::optional<Numbering> saved_;
  std::uint64_t errors_ = 0;
};

}  // namespace kew::daemon
