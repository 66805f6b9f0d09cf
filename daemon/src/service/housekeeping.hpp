#pragma once
// The one owner of kewd's periodic work (design §3.3): each task runs on the service's
// I/O thread at its period, read again before each wait so that a reloaded interval
// applies from the next one, until stop().

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>

namespace kew::daemon {

class Housekeeping {
 public:
  using Period = std::function<std::chrono::steady_clock::duration()>;
  using Task = std::function<void()>;

  explicit Housekeeping(boost::asio::io_context& io) : io_(io) {}
  Housekeeping(const Housekeeping&) = delete;
  Housekeeping& operator=(const Housekeeping&) = delete;

  /// Runs `task` every `period()` (> 0) from now on.
  void every(Period period, Task task);
  void every(std::chrono::steady_clock::duration period, Task task) {
    every([period] { return period; }, std::move(task));
  }
  /// Cancels every task; none runs again.
  void stop();

 private:
  struct Job {
    boost::asio::steady_timer timer;
    Period period;
    Task task;
  };
  void schedule(Job& job);

  boost::asio::io_context& io_;
  std::vector<std::unique_ptr<Job>> jobs_;
  bool stopped_ = false;
};

/// `s` seconds as a timer duration.
inline std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace kew::daemon
