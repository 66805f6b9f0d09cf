#pragma once
// What the HTTP fuzz targets share: one kewd HTTP server (daemon/src/http) on a loopback
// port for the whole run, and one client connection per input that sends the input's
// bytes, ends its side and reads until the server closes. The server must answer or
// refuse every byte sequence, close the connection within its limits, and hold no
// session once the client has gone; a connection still open after the time-outs, a
// session left behind, a crash or a sanitizer report is a finding.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
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
#include <stdlib.h>

#include "http_server.hpp"

namespace kew::daemon::http::fuzz {

class LoopbackServer {
 public:
  LoopbackServer()
      : files_(make_files()), server_(io_, {boost::asio::ip::make_address("127.0.0.1"), 0}, limits(files_), source()) {
    spdlog::set_level(spdlog::level::off);  // refusals are counted; the log would flood the run
    server_.start();
  }
  ~LoopbackServer() {
    server_.shutdown();
    std::error_code ignored;
    std::filesystem::remove_all(files_, ignored);
  }

  /// On a new connection: sends `handshake` and, when it is not empty, waits for the
  /// header of the server's answer (a WebSocket client sends no frame before the 101,
  /// RFC 6455 §4.1); then sends `bytes`, ends the client's side and reads everything the
  /// server says until it closes. Returns the first bytes the server sent (at most 64).
  std::string exchange(std::string_view handshake, std::string_view bytes) {
    // The port is a new one each run: "$PORT" in the input stands for it, so that inputs
    // can name this server in Host and Origin (an acknowledgement needs both right).
    const std::string input = with_port(bytes);
    using boost::asio::ip::tcp;
    tcp::socket client(io_);
    connect(client);
    // The server must make progress: each byte it sends gives it kQuietest more.
    auto deadline = std::chrono::steady_clock::now() + kQuietest;
    std::string first;
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
      boost::asio::streambuf header;
      boost::asio::async_read_until(client, header, "\r\n\r\n",
                                    [&](const boost::system::error_code&, std::size_t) { done = true; });
      run_until_done();
      const auto data = header.data();
      first.assign(boost::asio::buffers_begin(data), boost::asio::buffers_end(data));
      first.resize(std::min<std::size_t>(first.size(), kFirstBytes));
    }
    // The loopback buffers hold a whole input (the run's max_len is 16 KiB): the write
    // completes before the server reads.
    write(client, input);
    boost::system::error_code ignored;
    client.shutdown(tcp::socket::shutdown_send, ignored);
    std::array<char, 65536> chunk;
    std::function<void()> read_more = [&] {
      client.async_read_some(boost::asio::buffer(chunk), [&](const boost::system::error_code& ec, std::size_t n) {
        if (ec) {
          done = true;
          return;
        }
        if (first.size() < kFirstBytes) first.append(chunk.data(), std::min(n, kFirstBytes - first.size()));
        deadline = std::chrono::steady_clock::now() + kQuietest;
        read_more();
      });
    };
    read_more();
    run_until_done();
    client.close(ignored);
    // The server forgets the session once its side has closed too.
    deadline = std::chrono::steady_clock::now() + kQuietest;
    while (server_.connections() != 0) {
      if (std::chrono::steady_clock::now() > deadline) fail("a session outlived its connection");
      io_.run_one_for(std::chrono::milliseconds(10));
    }
    return first;
  }

 private:
  // Longer than the request and write time-outs (1 s) with room for a busy machine: a
  // server silent this long on an open connection is held by nothing the limits allow.
  static constexpr auto kQuietest = std::chrono::seconds(5);
  static constexpr std::size_t kFirstBytes = 64;

  /// A small web root and Leaflet directory (the real map's files include a 1.3 MB
  /// GeoJSON that pipelined requests would make every run slow).
  static std::filesystem::path make_files() {
    char name[] = "/tmp/kew-fuzz-web-XXXXXX";
    if (!mkdtemp(name)) fail("cannot create the web root");
    const std::filesystem::path root(name);
    std::filesystem::create_directories(root / "js");
    std::filesystem::create_directories(root / "leaflet");
    std::ofstream(root / "index.html") << "<!doctype html><title>kew</title>\n";
    std::ofstream(root / "js" / "kew-map.js") << "console.log('kew');\n";
    std::ofstream(root / "leaflet" / "leaflet.js") << "var L = {};\n";
    return root;
  }

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

  static HttpConfig limits(const std::filesystem::path& files) {
    HttpConfig c;
    c.web_root = files.string();
    c.leaflet_root = (files / "leaflet").string();
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

  std::filesystem::path files_;
  boost::asio::io_context io_;
  HttpServer server_;
};

}  // namespace kew::daemon::http::fuzz
