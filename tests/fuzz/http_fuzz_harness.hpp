#pragma once
// What the HTTP fuzz targets share: one kewd HTTP server (daemon/src/http) on a loopback
// port for the whole run, and one client connection per input that sends the input's
// bytes, ends its side and reads until the server closes. The server must answer or
// refuse every byte sequence, close the connection within its limits, and hold no
// session once the client has gone; a connection still open after the time-outs, a
// session left behind, a crash or a sanitizer report is a finding.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include <boost/asio/connect.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/buffers_iterator.hpp>
#include <boost/asio/read.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <spdlog/spdlog.h>

#include "http_server.hpp"

namespace kew::daemon::http::fuzz {

class LoopbackServer {
 public:
  LoopbackServer() : server_(io_, {boost::asio::ip::make_address("127.0.0.1"), 0}, limits(), source()) {
    spdlog::set_level(spdlog::level::off);  // refusals are counted; the log would flood the run
    server_.start();
  }

  /// On a new connection: sends `handshake` and, when it is not empty, waits for the
  /// header of the server's answer (a WebSocket client sends no frame before the 101,
  /// RFC 6455 §4.1); then sends `bytes`, ends the client's side and reads everything the
  /// server says until it closes. Returns what the server sent.
  std::string exchange(std::string_view handshake, std::string_view bytes) {
    // The port is a new one each run: "$PORT" in the input stands for it, so that inputs
    // can name this server in Host and Origin (an acknowledgement needs both right).
    const std::string input = with_port(bytes);
    using boost::asio::ip::tcp;
    tcp::socket client(io_);
    connect(client);
    const auto deadline = std::chrono::steady_clock::now() + kLongestExchange;
    boost::asio::streambuf reply;
    bool done = false;
    const auto run_until_done = [&] {
      while (!done) {
        if (std::chrono::steady_clock::now() > deadline) fail("the server did not answer or close in time");
        io_.run_one_for(std::chrono::milliseconds(100));
      }
      done = false;
    };
    if (!handshake.empty()) {
      write(client, handshake);
      boost::asio::async_read_until(client, reply, "\r\n\r\n",
                                    [&](const boost::system::error_code&, std::size_t) { done = true; });
      run_until_done();
    }
    // The loopback buffers hold a whole input (the run's max_len is 16 KiB): the write
    // completes before the server reads.
    write(client, input);
    client.shutdown(tcp::socket::shutdown_send);
    boost::asio::async_read(client, reply, [&](const boost::system::error_code&, std::size_t) { done = true; });
    run_until_done();
    client.close();
    // The server forgets the session once its side has closed too.
    while (server_.connections() != 0) {
      if (std::chrono::steady_clock::now() > deadline) fail("a session outlived its connection");
      io_.run_one_for(std::chrono::milliseconds(10));
    }
    const auto data = reply.data();
    return {boost::asio::buffers_begin(data), boost::asio::buffers_end(data)};
  }

 private:
  // Twice the request time-out and more: a connection the server keeps beyond that is held
  // open by nothing the limits allow.
  static constexpr auto kLongestExchange = std::chrono::seconds(5);

  // libFuzzer's timers interrupt system calls: a call cut short by a signal is made again.
  void connect(boost::asio::ip::tcp::socket& client) {
    boost::system::error_code ec;
    do {
      if (client.is_open()) client.close();
      client.connect({boost::asio::ip::make_address("127.0.0.1"), server_.port()}, ec);
    } while (ec == boost::asio::error::interrupted);
    if (ec) fail("cannot connect to the server");
  }

  /// Writes what the server takes: one that has closed already (a refusal) takes no more,
  /// and what it said is read all the same.
  static void write(boost::asio::ip::tcp::socket& client, std::string_view bytes) {
    while (!bytes.empty()) {
      boost::system::error_code ec;
      const std::size_t n = client.write_some(boost::asio::buffer(bytes), ec);
      if (ec && ec != boost::asio::error::interrupted) return;
      bytes.remove_prefix(n);
    }
  }

  std::string with_port(std::string_view bytes) const {
    static constexpr std::string_view kPort = "$PORT";
    const std::string port = std::to_string(server_.port());
    std::string out;
    for (std::size_t at = 0;;) {
      const std::size_t found = bytes.find(kPort, at);
      out.append(bytes.substr(at, found - at));
      if (found == std::string_view::npos) return out;
      out.append(port);
      at = found + kPort.size();
    }
  }

  [[noreturn]] static void fail(const char* why) {
    std::fprintf(stderr, "http fuzz harness: %s\n", why);
    std::abort();
  }

  static HttpConfig limits() {
    HttpConfig c;
    c.web_root = KEW_FUZZ_WEB_ROOT;
    c.request_timeout_s = 1.0;
    c.write_timeout_s = 1.0;
    c.client_queue_bytes = 65536;
    return c;
  }

  static HttpSource source() {
    HttpSource s;
    s.tracks = [] { return std::string("{\"class\":\"TRACKS\",\"tracks\":[]}"); };
    s.alerts = [] { return std::string("{\"class\":\"ALERTS\",\"alerts\":[]}"); };
    s.status = [] { return std::string("{\"class\":\"ALIVE\",\"health\":\"healthy\"}"); };
    s.zones = [] { return std::string("{\"class\":\"ZONES\",\"zones\":[]}"); };
    s.metrics = [] { return std::string("# kew\n"); };
    s.snapshot = [] { return std::string("[]"); };
    s.acknowledge = [](const protocol::AckRequest&, std::string_view) { return std::vector<std::string>{"1"}; };
    return s;
  }

  boost::asio::io_context io_;
  HttpServer server_;
};

}  // namespace kew::daemon::http::fuzz
