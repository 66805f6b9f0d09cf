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

HotStandby::HotStandby(boost::asio::io_context& io, const NatsConfig& config, const std::string& feed_stream,
                       std::uint64_t last_seq, std::uint16_t next_number, Handlers handlers,
                       std::shared_ptr<SpeakingRight> right)
    : handlers_(std::move(handlers)), instance_(instance_name(config)) {
  PairFollower::Handlers pair;
  pair.on_origin = [this, &io](const PairOrigin& start, std::shared_ptr<const PairCheckpoint> checkpoint) {
    boost::asio::post(io, [this, start, checkpoint = std::move(checkpoint)] { handlers_.on_origin(start, checkpoint); });
  };
  pair.usable = handlers_.usable;
  pair.on_alert = [this, &io](const AlertEvent& event) {
    boost::asio::post(io, [this, event] { handlers_.on_active_alert(event); });
  };
  pair.on_acknowledgement = [this, &io](std::uint64_t seq, std::vector<std::string> ids) {
    boost::asio::post(io, [this, seq, ids = std::move(ids)]() mutable {
      handlers_.on_active_acknowledgement(seq, std::move(ids));
    });
  };
  pair.on_read_up_to = [this, &io](std::uint64_t seq) {
    boost::asio::post(io, [this, seq] { handlers_.on_stream_read_up_to(seq); });
  };
  follower_ = std::make_unique<PairFollower>(config, feed_stream, instance_, last_seq, next_number, std::move(pair));

  LeaderLease::Handlers lease;
  lease.on_acquired = [this, &io](std::uint64_t published) {
    boost::asio::post(io, [this, published] { handlers_.on_acquired(published); });
  };
  lease.on_lost = [this, &io] { boost::asio::post(io, [this] { handlers_.on_lost(); }); };
  lease.readiness = [this] {
    if (!origin_known_) return LeaderLease::Readiness::NotReady;
    return in_step_ ? LeaderLease::Readiness::InStep : LeaderLease::Readiness::Unsynced;
  };
  if (handlers_.usable && config.checkpoint_interval_s > 0) checkpoints_ = std::make_unique<CheckpointPublisher>(config, right);
  lease_ = std::make_unique<LeaderLease>(config, instance_, std::move(lease), std::move(right));
}

}  // namespace kew::daemon
