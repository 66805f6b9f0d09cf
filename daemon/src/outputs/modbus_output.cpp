#include "modbus_output.hpp"

#include <spdlog/spdlog.h>

namespace kew::daemon {

ModbusOutput::ModbusOutput(const ModbusConfig& config, ModbusServer::AcknowledgeHandler on_acknowledge,
                           StateSource state, ModbusServer::SpeakingCheck may_speak)
    : server_(std::make_unique<ModbusServer>(config, std::move(on_acknowledge))),
      state_(std::move(state)),
      unit_id_(config.unit_id) {
  server_->set_speaking_check(std::move(may_speak));
  server_->set_reporter([](std::string_view reason, std::string_view message) {
    spdlog::warn("modbus: refused a request ({}){}{}", reason, message.empty() ? "" : ": ", message);
  });
}

void ModbusOutput::acknowledgement(const protocol::Acknowledgement&, std::uint64_t, const SharedLine&) {
  publish_now();
}

void ModbusOutput::role_changed(bool active) {
  changed_ = true;
  active_ = active;
  if (!active) {
    // The standby's state at once: a panel is told "standby" rather than "busy".
    if (started_) publish_now();
    return;
  }
  if (started_) return;
  publish_now();
  server_->start();
  started_ = true;
  spdlog::info("Modbus TCP alarm map on port {} (unit id {})", server_->bound_port(), unit_id_);
}

void ModbusOutput::publish() {
  // Unchanged alarms are republished once a second anyway: data age and uptime move.
  if (changed_ || std::chrono::steady_clock::now() - last_publish_ >= std::chrono::seconds(1)) publish_now();
}

void ModbusOutput::publish_now() {
  server_->publish(state_(), active_);
  changed_ = false;
  last_publish_ = std::chrono::steady_clock::now();
}

}  // namespace kew::daemon
