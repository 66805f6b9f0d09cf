#include "cat004_sender.hpp"

#include <boost/asio/ip/multicast.hpp>
#include <spdlog/spdlog.h>

#include "kew/config/address.hpp"

namespace kew::daemon {

namespace asio = boost::asio;
using asio::ip::udp;

namespace {
protocol::Cat004Options encoder_options(const Cat004Config& config) {
  protocol::Cat004Options options;
  options.sac = config.sac;
  options.sic = config.sic;
  return options;
}
}  // namespace

Cat004Sender::Cat004Sender(asio::io_context& io, const Cat004Config& config)
    : socket_(io), encoder_(encoder_options(config)) {
  const config::HostPort address = config::require_host_port(config.destination);
  udp::resolver resolver(io);
  destination_ = *resolver.resolve(address.host, std::to_string(address.port)).begin();
  socket_.open(destination_.protocol());
  if (destination_.address().is_multicast()) {
    socket_.set_option(asio::ip::multicast::hops(config.ttl));
    if (destination_.address().is_v4())
      socket_.set_option(asio::ip::multicast::outbound_interface(asio::ip::make_address_v4(config.interface)));
  }
}

void Cat004Sender::send_alert(const AlertEvent& event) {
  encoder_.add_alert(event);
  flush();
}

void Cat004Sender::send_alive(const protocol::Cat004Alive& alive) {
  encoder_.add_alive(alive);
  flush();
}

void Cat004Sender::flush() {
  for (const auto& datagram : encoder_.take_datagrams()) {
    boost::system::error_code ec;
    socket_.send_to(asio::buffer(datagram), destination_, 0, ec);
    if (ec) {
      if (++errors_ == 1 || (errors_ & (errors_ - 1)) == 0)
        spdlog::warn("CAT004 to {}: {} ({} errors)", destination_.address().to_string(), ec.message(), errors_);
    } else {
      ++datagrams_;
    }
  }
}

}  // namespace kew::daemon
