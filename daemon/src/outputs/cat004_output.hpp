#pragma once
// ASTERIX CAT004 (design §5.4) as an output: STCA or APW messages, by the alert's kind,
// and End Of Conflict for alert events, and Alive messages, to the destination the pair
// shares.

#include <boost/asio/io_context.hpp>

#include "../service/cat004_sender.hpp"
#include "output.hpp"

namespace kew::daemon {

class Cat004Output final : public Output {
 public:
  /// `area_warning`: volumes are configured, so Alive says the APW function runs (I004/060).
  Cat004Output(boost::asio::io_context& io, const Cat004Config& config, bool area_warning)
      : sender_(io, config), area_warning_(area_warning) {}

  std::string_view name() const override { return "cat004"; }
  Audience audience() const override { return Audience::Shared; }
  void alert(const AlertEvent& event, const SharedLine&) override { sender_.send_alert(event); }
  void acknowledgement(const protocol::Acknowledgement&, std::uint64_t, const SharedLine&) override {}
  void alive(const AliveEvent& alive, const SharedLine&) override;
  void report(protocol::ServiceStatistics& statistics) const override {
    statistics.cat004 = protocol::Cat004Statistics{sender_.datagrams_sent(), sender_.send_errors()};
  }

 private:
  Cat004Sender sender_;
  bool area_warning_;
};

}  // namespace kew::daemon
