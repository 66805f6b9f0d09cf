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
    // The subject follows the first '/' that is not part of a later server's "nats://".
    std::size_t slash = text.find('/');
    while (slash != std::string_view::npos && slash > 0 && text[slash - 1] == ':' && slash + 1 < text.size() &&
           text[slash + 1] == '/')
      slash = text.find('/', slash + 2);
    target.subject = slash == std::string_view::npos ? std::string() : std::string(text.substr(slash + 1));
    if (!config::valid_nats_subject(target.subject, false)) {
      if (error) *error = "nats://HOST:PORT/SUBJECT needs a subject to publish to after the port";
      return std::nullopt;
    }
    text = text.substr(0, slash);
    // A cluster: its servers comma-separated, each HOST:PORT, with or without nats://.
    for (std::string_view rest = text;;) {
      const std::size_t comma = rest.find(',');
      std::string_view server = rest.substr(0, comma);
      if (server.starts_with("nats://")) server.remove_prefix(7);
      std::optional<config::HostPort> address = config::parse_host_port(server, error);
      if (!address) return std::nullopt;
      target.nats_servers.push_back("nats://" + config::to_string(*address));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    text = text.substr(0, text.find(','));
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
  std::string url;  // for messages
  std::vector<const char*> servers;
  for (const std::string& server : target.nats_servers) {
    url += (url.empty() ? "" : ",") + server;
    servers.push_back(server.c_str());
  }
  natsOptions* options = nullptr;
  natsStatus s = natsOptions_Create(&options);
  if (s == NATS_OK) s = natsOptions_SetServers(options, servers.data(), static_cast<int>(servers.size()));
  natsConnection* connection = nullptr;
  if (s == NATS_OK) s = natsConnection_Connect(&connection, options);
  natsOptions_Destroy(options);
  if (s != NATS_OK) nats_failure("cannot connect to " + url, s);
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
