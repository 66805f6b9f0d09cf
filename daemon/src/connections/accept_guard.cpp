#include "accept_guard.hpp"

#include <algorithm>
#include <cerrno>

#include <spdlog/spdlog.h>

namespace kew::daemon {

bool is_resource_exhaustion(const boost::system::error_code& ec) {
  if (ec.category() != boost::system::system_category()) return false;
  const int e = ec.value();
  return e == EMFILE || e == ENFILE || e == ENOBUFS || e == ENOMEM;
}

AcceptGuard::AcceptGuard(boost::asio::any_io_executor executor, std::string listener)
    : timer_(std::move(executor)), listener_(std::move(listener)) {}

void AcceptGuard::failed(const boost::system::error_code& ec, std::function<void()> accept_again) {
  ++failures_;
  if (!is_resource_exhaustion(ec)) {
    // A connection that died in the backlog: the next one may be fine.
    spdlog::debug("{}: accept failed ({})", listener_, ec.message());
    accept_again();
    return;
  }
  if (episode_failures_++ == 0) {
    spdlog::error("{}: cannot accept connections ({}); retrying every {}-{} ms until descriptors are free",
                  listener_, ec.message(), kFirstWait.count(), kLongestWait.count());
  }
  timer_.expires_after(wait_);
  wait_ = std::min(wait_ * 2, kLongestWait);
  timer_.async_wait([again = std::move(accept_again)](const boost::system::error_code& tec) {
    if (!tec) again();
  });
}

void AcceptGuard::succeeded() {
  if (episode_failures_ > 0) {
    spdlog::warn("{}: accepting connections again after {} failed attempts", listener_, episode_failures_);
  }
  episode_failures_ = 0;
  wait_ = kFirstWait;
}

}  // namespace kew::daemon
