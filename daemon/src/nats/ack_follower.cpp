#include "ack_follower.hpp"

#include <chrono>

#include <spdlog/spdlog.h>

#include "kew/protocol/encoders/alert_json_reader.hpp"

namespace kew::daemon {

namespace {
constexpr std::int64_t kWaitMs = 200;  // a read waits this long, then looks at stopping_
}  // namespace

AckFollower::AckFollower(const NatsConfig& config, IdsHandler on_ids)
    : config_(config),
      on_ids_(std::move(on_ids)),
      connection_(config.servers, config.name + " acks",
                  [](std::string_view event) { spdlog::info("[nats] acknowledgements: {}", event); }) {
  thread_ = std::thread([this] { run(); });
}

AckFollower::~AckFollower() {
  stopping_ = true;
  thread_.join();
}

void AckFollower::run() {
  natsSubscription* subscription = nullptr;
  protocol::AlertStreamReader reader;
  while (!stopping_) {
    if (!subscription) {
      if (natsConnection_SubscribeSync(&subscription, connection_.get(), config_.acks_subject.c_str()) != NATS_OK) {
        subscription = nullptr;
        std::this_thread::sleep_for(std::chrono::milliseconds(kWaitMs));
      }
      continue;
    }
    natsMsg* message = nullptr;
    const natsStatus s = natsSubscription_NextMsg(&message, subscription, kWaitMs);
    if (s != NATS_OK) {
      if (s != NATS_TIMEOUT && s != NATS_SLOW_CONSUMER) std::this_thread::sleep_for(std::chrono::milliseconds(kWaitMs));
      continue;
    }
    std::string line(natsMsg_GetData(message), static_cast<std::size_t>(natsMsg_GetDataLength(message)));
    natsMsg_Destroy(message);
    line += '\n';
    if (!reader.read(line) || reader.object_class() != protocol::StreamObjectClass::Ack) {
      spdlog::warn("[nats] acknowledgements: an unreadable message on {} skipped", config_.acks_subject);
      continue;
    }
    on_ids_(reader.acknowledged());
  }
  natsSubscription_Destroy(subscription);
}

}  // namespace kew::daemon
