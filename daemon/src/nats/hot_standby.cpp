#include "hot_standby.hpp"

#include <unistd.h>

#include <boost/asio/post.hpp>
#include <fmt/format.h>

namespace kew::daemon {
namespace {

std::string instance_name(const NatsConfig& config) {
  if (!config.instance.empty()) return config.instance;
  char host[256] = "kewd";
  ::gethostname(host, sizeof host - 1);
  return fmt::format("{}-{}", host, ::getpid());
}

}  // namespace

HotStandby::HotStandby(boost::asio::io_context& io, const NatsConfig& config, Handlers handlers)
    : handlers_(std::move(handlers)) {
  LeaderLease::Handlers lease;
  lease.on_acquired = [this, &io](std::uint64_t published) {
    boost::asio::post(io, [this, published] { handlers_.on_acquired(published); });
  };
  lease.on_lost = [this, &io] { boost::asio::post(io, [this] { handlers_.on_lost(); }); };
  lease_ = std::make_unique<LeaderLease>(config, instance_name(config), std::move(lease));
  // The active's acknowledgements, kept by the standby for after a takeover.
  acks_ = std::make_unique<AckFollower>(config, [this, &io](std::vector<std::string> ids) {
    boost::asio::post(io, [this, ids = std::move(ids)] { handlers_.on_acknowledged(ids); });
  });
}

}  // namespace kew::daemon
