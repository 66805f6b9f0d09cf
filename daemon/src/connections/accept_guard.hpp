#pragma once
// What an acceptor does when accept() fails. Out of file descriptors (EMFILE, ENFILE) or
// kernel memory (ENOBUFS, ENOMEM), the pending connection stays in the listen backlog and
// the socket stays readable: accepting again at once spins a core and starves every other
// handler. AcceptGuard waits instead, 100 ms doubling to 1 s, logs once when an episode
// begins and once when it ends, and counts the failures. Other errors (a connection reset
// while queued) are counted and accepting resumes at once.

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include <boost/asio/steady_timer.hpp>
#include <boost/system/error_code.hpp>

namespace kew::daemon {

class AcceptGuard {
 public:
  /// `listener` names the socket in the log ("subscribers", "input feed").
  AcceptGuard(boost::asio::any_io_executor executor, std::string listener);

  /// After an accept completed with `ec` (not operation_aborted): true when it succeeded;
  /// else counts the failure in `failures` as well, arranges failed()'s retry and is false.
  bool accepted(const boost::system::error_code& ec, std::uint64_t& failures, std::function<void()> accept_again) {
    if (!ec) {
      succeeded();
      return true;
    }
    ++failures;
    failed(ec, std::move(accept_again));
    return false;
  }
  /// After an accept completed with `ec` (not success, not operation_aborted): calls
  /// `accept_again` now or after the back-off. Counts one failure.
  void failed(const boost::system::error_code& ec, std::function<void()> accept_again);
  /// After a successful accept: ends an episode (logged) and resets the back-off.
  void succeeded();
  void cancel() { timer_.cancel(); }

  /// accept() calls that failed since start.
  std::uint64_t failures() const { return failures_; }

  static constexpr std::chrono::milliseconds kFirstWait{100};
  static constexpr std::chrono::milliseconds kLongestWait{1000};

 private:
  boost::asio::steady_timer timer_;
  std::string listener_;
  std::chrono::milliseconds wait_ = kFirstWait;
  std::uint64_t failures_ = 0;
  std::uint64_t episode_failures_ = 0;  // failures of the current episode; 0: none
};

/// Whether `ec` from accept() means the process or the system is out of descriptors or
/// memory (the error does not go away by retrying at once).
bool is_resource_exhaustion(const boost::system::error_code& ec);

}  // namespace kew::daemon
