#pragma once
// ASTERIX CAT004 safety-net messages over UDP (design §5.4): STCA on new and updated
// alerts, End of conflict on ends, Alive periodically. Unicast or multicast.

#include <boost/asio/ip/udp.hpp>

#include "kew/daemon/config.hpp"
#include "kew/protocol/encoders/cat004.hpp"

namespace kew::daemon {

class Cat004Sender {
 public:
  Cat004Sender(boost::asio::io_context& io, const Cat004Config& config);
  void send_alert(const AlertEvent& event);
  void send_alive(const protocol::Cat004Alive& alive);
  std::uint64_t datagrams_sent() const { return datagrams_; }
  std::uint64_t send_errors() const { return errors_; }

 private:
  void flush();

  boost::asio::ip::udp::socket socket_;
  boost::asio::ip::udp::endpoint destination_;
  protocol::Cat004Encoder encoder_;
  std::uint64_t datagrams_ = 0;
  std::uint64_t errors_ = 0;
};

}  // namespace kew::daemon
