#include "housekeeping.hpp"

namespace kew::daemon {

void Housekeeping::every(Period period, Task task) {
  if (stopped_) return;
  jobs_.push_back(std::make_unique<Job>(Job{boost::asio::steady_timer(io_), std::move(period), std::move(task)}));
  schedule(*jobs_.back());
}

void Housekeeping::schedule(Job& job) {
  job.timer.expires_after(job.period());
  job.timer.async_wait([this, &job](const boost::system::error_code& ec) {
    if (ec || stopped_) return;
    job.task();
    if (!stopped_) schedule(job);
  });
}

void Housekeeping::stop() {
  stopped_ = true;
  for (const auto& job : jobs_) job->timer.cancel();
}

}  // namespace kew::daemon
