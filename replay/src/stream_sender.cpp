#include "kew/replay/stream_sender.hpp"

#include <stdexcept>
#include <thread>

#include <nats/nats.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/write.hpp>

#include "kew/config/address.hpp"
#include "kew/config/nats_subject.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/replay/pacer.hpp"

namespace kew::replay {

namespace asio = boost::asio;

std::optional<StreamTarget> parse_stream_target(std::string_view text, std::string* error) {
  StreamTarget target;
  if (text.starts_with("tcp://")) {
    text.remove_prefix(6);
  } else if (text.starts_with("udp://")) {
    target.protocol = StreamTarget::Protocol::Udp;
    text.remove_prefix(6);
  } else if (text.starts_with("nats://")) {
    target.protocol = StreamTarget::Protocol::Nats;
    text.remove_prefix(7);
    const std::size_t slash = text.find('/');
    target.subject = slash == std::string_view::npos ? std::string() : std::string(text.substr(slash + 1));
    if (!config::valid_nats_subject(target.subject, false)) {
      if (error) *error = "nats://HOST:PORT/SUBJECT needs a subject to publish to after the port";
      return std::nullopt;
    }
    text = text.substr(0, slash);
  }
  std::optional<config::HostPort> address = config::parse_host_port(text, error);
  if (!address) return std::nullopt;
  target.host = std::move(address->host);
  target.port = address->port;
  return target;
}

namespace {

// Collects lines that are due at the same moment and hands them to `send` in batches.
template <class Send>
StreamFigures pump(MergedRecordings& recordings, double speed, std::size_t batch_bytes, Send&& send) {
  StreamFigures figures;
  Pacer pacer(speed);
  std::string batch, line;
  TrackReport report;
  while (recordings.next(report)) {
    const auto due = pacer.due(report.t);
    if (!batch.empty() && std::chrono::steady_clock::now() < due) {
      send(batch);
      batch.clear();
    }
    std::this_thread::sleep_until(due);
    line.clear();
    protocol::append_ndjson(line, report);
    line += '\n';
    if (!batch.empty() && batch.size() + line.size() > batch_bytes) {
      send(batch);
      batch.clear();
    }
    batch += line;
    ++figures.records;
    figures.bytes += line.size();
  }
  if (!batch.empty()) send(batch);
  return figures;
}

/// The NATS C client's failure, as kew-replay reports it.
[[noreturn]] void nats_failure(std::string_view what, natsStatus status) {
  throw std::runtime_error(std::string(what) + ": " + natsStatus_GetText(status));
}

// One connection for the whole replay: a server that is not there is an error, as a TCP
// input that refuses the connection is.
StreamFigures stream_to_nats(MergedRecordings& recordings, const StreamTarget& target, double speed,
                             std::size_t message_bytes) {
  const std::string host = target.host.find(':') != std::string::npos ? "[" + target.host + "]" : target.host;
  const std::string url = "nats://" + host + ":" + std::to_string(target.port);
  natsConnection* connection = nullptr;
  if (const natsStatus s = natsConnection_ConnectTo(&connection, url.c_str()); s != NATS_OK)
    nats_failure("cannot connect to " + url, s);
  std::uint64_t messages = 0;
  natsStatus failed = NATS_OK;
  StreamFigures figures = pump(recordings, speed, message_bytes, [&](const std::string& batch) {
    if (failed != NATS_OK) return;
    failed = natsConnection_Publish(connection, target.subject.c_str(), batch.data(), static_cast<int>(batch.size()));
    ++messages;
  });
  // Every message with the server before the connection closes.
  if (failed == NATS_OK) failed = natsConnection_FlushTimeout(connection, 10000);
  natsConnection_Destroy(connection);
  if (failed != NATS_OK) nats_failure("publishing to " + url + " " + target.subject, failed);
  figures.datagrams = messages;
  return figures;
}

}  // namespace

StreamFigures stream_records(MergedRecordings& recordings, const StreamTarget& target, double speed,
                             std::size_t max_datagram_bytes) {
  if (target.protocol == StreamTarget::Protocol::Nats)
    return stream_to_nats(recordings, target, speed, max_datagram_bytes);
  asio::io_context io;
  const std::string port = std::to_string(target.port);
  if (target.protocol == StreamTarget::Protocol::Tcp) {
    asio::ip::tcp::socket socket(io);
    asio::ip::tcp::resolver resolver(io);
    boost::system::error_code error;
    asio::connect(socket, resolver.resolve(target.host, port), error);
    if (error) throw std::runtime_error("cannot connect to " + target.host + ":" + port + ": " + error.message());
    StreamFigures figures = pump(recordings, speed, 64 * 1024, [&](const std::string& batch) {
      asio::write(socket, asio::buffer(batch));
    });
    socket.shutdown(asio::ip::tcp::socket::shutdown_send, error);
    return figures;
  }
  asio::ip::udp::resolver resolver(io);
  const asio::ip::udp::endpoint destination = *resolver.resolve(target.host, port).begin();
  asio::ip::udp::socket socket(io, destination.protocol());
  std::uint64_t datagrams = 0;
  StreamFigures figures = pump(recordings, speed, max_datagram_bytes, [&](const std::string& batch) {
    socket.send_to(asio::buffer(batch), destination);
    ++datagrams;
  });
  figures.datagrams = datagrams;
  return figures;
}

}  // namespace kew::replay
