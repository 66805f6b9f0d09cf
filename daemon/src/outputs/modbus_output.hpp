#pragma once
// The Modbus TCP alarm map (design §5.5) as an output: the server (its own thread) serves
// a copy of the alarm state, published when an event changed it and at least once a
// second (data age, uptime); served only once this instance is active.

#include <chrono>
#include <functional>
#include <memory>

#include "kew/daemon/modbus_server.hpp"
#include "output.hpp"

namespace kew::daemon {

class ModbusOutput final : public Output {
 public:
  /// The alarm state now, as the panel is to read it.
  using StateSource = std::function<protocol::AlarmSnapshot()>;
  /// Alarm state goes to the server thread at most this often (a copy of every active
  /// alert per publish).
  static constexpr auto kPublishPeriod = std::chrono::milliseconds(200);

  /// Binds (see ModbusServer); `on_acknowledge` is called on the server thread.
  /// `may_speak`: hot standby's right to speak (SpeakingRight::may_speak), asked by the
  /// server thread before it answers from a state published while active; empty without
  /// hot standby.
  ModbusOutput(const ModbusConfig& config, ModbusServer::AcknowledgeHandler on_acknowledge, StateSource state,
               ModbusServer::SpeakingCheck may_speak = {});

  std::string_view name() const override { return "modbus"; }
  Audience audience() const override { return Audience::Shared; }
  void alert(const AlertEvent&, const SharedLine&) override { changed_ = true; }
  /// Published at once: the panel that acknowledged sees its lamp go out.
  void acknowledgement(const protocol::Acknowledgement&, std::uint64_t, const SharedLine&) override;
  void alive(const AliveEvent&, const SharedLine&) override {}
  /// Active: the server starts (once); a standby's panel port stays closed.
  void role_changed(bool active) override;
  void report(protocol::ServiceStatistics& statistics) const override { statistics.modbus = server_->stats(); }

  /// The alarm state changed outside an event (an acknowledgement followed on standby).
  void mark_changed() { changed_ = true; }
  /// Every kPublishPeriod: publishes when changed, or when a second has passed.
  void publish();
  void stop() { server_->stop(); }
  std::uint16_t port() const { return server_->bound_port(); }

 private:
  void publish_now();

  std::unique_ptr<ModbusServer> server_;
  StateSource state_;
  int unit_id_;
  bool started_ = false;
  bool active_ = false;
  bool changed_ = true;
  std::chrono::steady_clock::time_point last_publish_{};
};

}  // namespace kew::daemon
