// Sustained ingestion of a running kewd over loopback: records are streamed to
// a TCP, UDP or NATS input at a target rate (or as fast as possible) while a subscriber reads
// the alert stream. Reports the rate the daemon sustained and the record-to-alert latency
// percentiles: for every ALERT, the time from sending the record that triggered it (the
// record of track a or b at the alert's data time) to receiving the line.
//
//   kew_ingest_bench --kewd build/daemon/kewd --records traffic.ndjson --transport tcp [--rate R]
//                    [--map-clients N] [--json FILE]
//
// It starts its own kewd (loopback, ephemeral ports) and stops it with SIGTERM; with
// --transport nats, its own nats-server too (--nats-server), the records published to a
// subject kewd subscribes to (design §5.9), in messages as big as UDP's datagrams.
// --map-clients N connects N clients to kewd's HTTP server as the live map does:
// each reads the /ws WebSocket, polls /api/status every 2 s and /api/tracks every 10 s.

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/read_until.hpp>
#include <boost/asio/streambuf.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <nats/nats.h>

#include "free_port.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"

namespace {

namespace asio = boost::asio;
using asio::ip::tcp;
using asio::ip::udp;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string kewd;
  std::string records;
  std::string transport = "tcp";
  double rate = 0.0;  // records per second; 0 = as fast as possible
  std::size_t map_clients = 0;
  std::string json;
  std::string nats_server = "nats-server";
};

/// A child process, stopped with SIGTERM and waited for.
class Child {
 public:
  explicit Child(std::vector<std::string> argv) {
    pid_ = ::fork();
    if (pid_ == 0) {
      // Its log would interleave with the result on the terminal.
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
      std::vector<char*> args;
      for (std::string& a : argv) args.push_back(a.data());
      args.push_back(nullptr);
      ::execvp(args[0], args.data());
      std::_Exit(127);
    }
  }
  ~Child() {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

 private:
  pid_t pid_ = -1;
};

/// nats-server on a free loopback port (plain NATS: kewd's input subscribes to a subject).
class NatsServer {
 public:
  explicit NatsServer(const std::string& binary)
      : address_(kew::testing::free_loopback_address()),
        process_({binary, "-a", "127.0.0.1", "-p", address_.substr(address_.rfind(':') + 1)}) {
    for (int attempt = 0; attempt < 200; ++attempt) {
      if (natsConnection_ConnectTo(&connection_, url().c_str()) == NATS_OK) return;
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    }
    throw std::runtime_error("nats-server did not start");
  }
  ~NatsServer() { natsConnection_Destroy(connection_); }
  std::string url() const { return "nats://" + address_; }
  /// The publishing connection of the sender.
  natsConnection* connection() const { return connection_; }

 private:
  std::string address_;
  Child process_;
  natsConnection* connection_ = nullptr;
};

constexpr const char* kNatsSubject = "bench.feed";

struct Record {
  std::string line;  // with its '\n'
  std::string key;   // id + data time, to find the record an alert came from
};

std::string record_key(std::string_view id, double t) { return fmt::format("{}@{:.3f}", id, t); }

std::vector<Record> load_records(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::vector<Record> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    // Only "t" and "id" are needed; canonical lines start with them.
    const auto t_at = line.find("\"t\":");
    const auto id_at = line.find("\"id\":\"");
    if (t_at == std::string::npos || id_at == std::string::npos) continue;
    const double t = std::stod(line.substr(t_at + 4));
    const auto id_end = line.find('"', id_at + 6);
    out.push_back({line + "\n", record_key(std::string_view(line).substr(id_at + 6, id_end - id_at - 6), t)});
  }
  return out;
}

/// kewd as a child process with its stderr in a pipe; learns its ports from its log.
class Daemon {
 public:
  /// `nats_url`: with transport nats, the server the input subscribes on.
  Daemon(const std::string& binary, const std::string& transport, const std::string& config_path,
         const std::string& nats_url = {})
      : http_address_(kew::testing::free_loopback_address()) {
    const bool nats = transport == "nats";
    // The map's clients are batched per service tick: 1 s, as kewd's default.
    std::ofstream(config_path) << fmt::format(
        "[service]\nalert_listen = \"{}\"\ntick_interval_s = 1\nsubscriber_queue = 1000000\n"
        "log_level = \"info\"\n[http]\nlisten = \"{}\"\n[[input]]\nname = \"bench\"\nformat = \"ndjson\"\n"
        "transport = \"{}\"\naddress = \"{}\"\n{}",
        kew::testing::free_loopback_address(), http_address_, nats ? "nats" : transport == "udp" ? "udp" : "tcp-server",
        nats ? kNatsSubject : kew::testing::free_loopback_address(),
        nats ? fmt::format("nats_url = \"{}\"\n", nats_url) : "");
    int err[2];
    if (::pipe(err) != 0) throw std::runtime_error("pipe");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(err[1], STDERR_FILENO);
      ::close(err[0]);
      ::execl(binary.c_str(), binary.c_str(), "-N", "-c", config_path.c_str(), static_cast<char*>(nullptr));
      std::_Exit(127);
    }
    ::close(err[1]);
    log_ = ::fdopen(err[0], "r");
    char buffer[1024];
    while ((alert_port_ == 0 || input_port_ == 0) && std::fgets(buffer, sizeof buffer, log_)) {
      const std::string line = buffer;
      if (nats && line.find("input bench: subscribed to") != std::string::npos) input_port_ = 1;  // no port
      if (const auto at = line.find("alerts on port "); at != std::string::npos)
        alert_port_ = static_cast<std::uint16_t>(std::stoi(line.substr(at + 15)));
      if (const auto at = line.find("(port "); at != std::string::npos && line.find("input bench") != std::string::npos)
        input_port_ = static_cast<std::uint16_t>(std::stoi(line.substr(at + 6)));
    }
    if (alert_port_ == 0 || input_port_ == 0) throw std::runtime_error("kewd did not start");
    // Keep draining the log so that kewd never blocks on a full pipe.
    drain_ = std::thread([this] {
      char sink[4096];
      while (std::fgets(sink, sizeof sink, log_)) {
      }
    });
  }
  ~Daemon() {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    drain_.join();
    std::fclose(log_);
  }
  std::uint16_t alert_port() const { return alert_port_; }
  /// HOST:PORT of kewd's HTTP server.
  const std::string& http_address() const { return http_address_; }
  std::uint16_t input_port() const { return input_port_; }

  /// Records the pipeline has been offered so far (from ?STATS).
  std::uint64_t records_processed() const {
    asio::io_context io;
    tcp::socket s(io);
    s.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), alert_port_));
    asio::write(s, asio::buffer(std::string("?STATS\n")));
    asio::streambuf buffer;
    for (;;) {
      const std::size_t n = asio::read_until(s, buffer, '\n');
      std::string line(asio::buffers_begin(buffer.data()), asio::buffers_begin(buffer.data()) + static_cast<long>(n));
      buffer.consume(n);
      if (line.find("\"class\":\"STATS\"") == std::string::npos) continue;
      const auto at = line.find("\"records\":");
      return std::stoull(line.substr(at + 10));
    }
  }

 private:
  std::string http_address_;
  pid_t pid_ = -1;
  std::FILE* log_ = nullptr;
  std::thread drain_;
  std::uint16_t alert_port_ = 0;
  std::uint16_t input_port_ = 0;
};

/// One client of kewd's HTTP server behaving as the live map: the /ws WebSocket read on
/// one thread, /api/status every 2 s and /api/tracks every 10 s on another.
class MapClient {
 public:
  explicit MapClient(const std::string& address) : address_(address) {
    const auto colon = address.rfind(':');
    host_ = address.substr(0, colon);
    port_ = address.substr(colon + 1);
    reader_ = std::thread([this] { read_websocket(); });
    poller_ = std::thread([this] { poll(); });
  }
  ~MapClient() {
    stop_ = true;
    {
      std::lock_guard lock(socket_mutex_);
      if (ws_) {
        boost::system::error_code ec;
        ws_->next_layer().shutdown(tcp::socket::shutdown_both, ec);
      }
    }
    reader_.join();
    poller_.join();
  }
  std::uint64_t messages() const { return messages_; }
  std::uint64_t bytes() const { return bytes_; }

 private:
  void read_websocket() {
    namespace websocket = boost::beast::websocket;
    boost::system::error_code ec;
    {
      std::lock_guard lock(socket_mutex_);
      ws_ = std::make_unique<websocket::stream<tcp::socket>>(ws_io_);
      tcp::resolver resolver(ws_io_);
      asio::connect(ws_->next_layer(), resolver.resolve(host_, port_), ec);
    }
    if (!ec) ws_->handshake(address_, "/ws", ec);
    if (ec) {
      std::fprintf(stderr, "map client: WebSocket: %s\n", ec.message().c_str());
      return;
    }
    boost::beast::flat_buffer buffer;
    while (!stop_) {
      ws_->read(buffer, ec);
      if (ec) return;
      ++messages_;
      bytes_ += buffer.size();
      buffer.consume(buffer.size());
    }
  }
  void get(const std::string& target) {
    namespace http = boost::beast::http;
    asio::io_context io;
    tcp::resolver resolver(io);
    tcp::socket socket(io);
    asio::connect(socket, resolver.resolve(host_, port_));
    http::request<http::empty_body> request{http::verb::get, target, 11};
    request.set(http::field::host, address_);
    http::write(socket, request);
    boost::beast::flat_buffer buffer;
    http::response<http::string_body> response;
    http::read(socket, buffer, response);
    bytes_ += response.body().size();
  }
  void poll() {
    for (int second = 0; !stop_; ++second) {
      try {
        if (second % 2 == 0) get("/api/status");
        if (second % 10 == 0) get("/api/tracks");
      } catch (const std::exception& e) {
        std::fprintf(stderr, "map client: HTTP: %s\n", e.what());
      }
      for (int i = 0; i < 10 && !stop_; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

  std::string address_, host_, port_;
  asio::io_context ws_io_;  // outlives ws_, which the destructor shuts down
  std::mutex socket_mutex_;
  std::unique_ptr<boost::beast::websocket::stream<tcp::socket>> ws_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> messages_{0}, bytes_{0};
  std::thread reader_, poller_;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"kew_ingest_bench: sustained ingestion and record-to-alert latency of kewd over loopback"};
  app.add_option("--kewd", options.kewd, "kewd binary")->required()->check(CLI::ExistingFile);
  app.add_option("--records", options.records, "canonical NDJSON to send (kew-gen output)")->required()->check(
      CLI::ExistingFile);
  app.add_option("--transport", options.transport, "tcp, udp or nats")
      ->check(CLI::IsMember({"tcp", "udp", "nats"}));
  app.add_option("--nats-server", options.nats_server, "with --transport nats: the nats-server binary")
      ->default_val(options.nats_server);
  app.add_option("--rate", options.rate, "records per second to send (0: as fast as possible)");
  app.add_option("--map-clients", options.map_clients,
                 "clients of the HTTP server acting as the live map (WebSocket + polling)");
  app.add_option("--json", options.json, "write the results as one JSON object");
  CLI11_PARSE(app, argc, argv);

  const std::vector<Record> records = load_records(options.records);
  const std::string config = fmt::format("/tmp/kew_ingest_bench_{}.toml", ::getpid());
  std::unique_ptr<NatsServer> nats;
  if (options.transport == "nats") nats = std::make_unique<NatsServer>(options.nats_server);
  Daemon daemon(options.kewd, options.transport, config, nats ? nats->url() : std::string());
  std::vector<std::unique_ptr<MapClient>> map_clients;
  for (std::size_t i = 0; i < options.map_clients; ++i)
    map_clients.push_back(std::make_unique<MapClient>(daemon.http_address()));

  // Subscriber: every ALERT line's receive time and the records it may come from.
  struct Received {
    Clock::time_point at;
    std::string key_a, key_b;
  };
  std::vector<Received> received;
  std::mutex received_mutex;
  std::atomic<bool> subscribed{false};
  asio::io_context io;
  tcp::socket subscriber(io);
  subscriber.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), daemon.alert_port()));
  asio::write(subscriber, asio::buffer(std::string("?WATCH={\"enable\":true}\n")));
  std::thread reader([&] {
    kew::protocol::AlertStreamReader parser;
    asio::streambuf buffer;
    boost::system::error_code ec;
    for (;;) {
      const std::size_t n = asio::read_until(subscriber, buffer, '\n', ec);
      if (ec) return;
      const auto now = Clock::now();
      std::string line(asio::buffers_begin(buffer.data()), asio::buffers_begin(buffer.data()) + static_cast<long>(n));
      buffer.consume(n);
      if (!parser.read(line)) continue;
      if (parser.object_class() == kew::protocol::StreamObjectClass::Alerts) subscribed = true;
      if (parser.object_class() != kew::protocol::StreamObjectClass::Alert) continue;
      const kew::AlertEvent& e = parser.alert();
      if (e.state == kew::AlertState::End) continue;  // ends may come from a timeout, not a record
      std::lock_guard lock(received_mutex);
      received.push_back({now, record_key(e.a.id, e.t), record_key(e.b.id, e.t)});
    }
  });
  while (!subscribed) std::this_thread::sleep_for(std::chrono::milliseconds(5));

  // Sender: batches of lines, each batch stamped with its send time.
  std::unordered_map<std::string, Clock::time_point> sent_at;
  sent_at.reserve(records.size());
  const auto start = Clock::now();
  {
    tcp::socket tcp_socket(io);
    udp::socket udp_socket(io);
    const auto address = asio::ip::make_address("127.0.0.1");
    if (options.transport == "tcp") {
      tcp_socket.connect(tcp::endpoint(address, daemon.input_port()));
      tcp_socket.set_option(tcp::no_delay(true));  // a live feed does not wait to fill segments
    }
    else udp_socket.open(udp::v4());
    // Paced runs send small batches, as a live feed would; a flat-out TCP run sends big
    // writes so that the sender is never the bottleneck.
    const std::size_t batch_bytes = options.transport == "tcp" && options.rate <= 0 ? 16384 : 1400;
    std::string batch;
    std::size_t sent = 0;
    std::size_t i = 0;
    while (i < records.size()) {
      batch.clear();
      const std::size_t first = i;
      while (i < records.size() && batch.size() + records[i].line.size() <= batch_bytes) batch += records[i++].line;
      if (i == first) batch += records[i++].line;  // a line longer than a batch goes alone
      if (options.rate > 0) {
        const auto due = start + std::chrono::duration_cast<Clock::duration>(
                                     std::chrono::duration<double>(static_cast<double>(sent) / options.rate));
        std::this_thread::sleep_until(due);
      }
      const auto now = Clock::now();
      for (std::size_t k = first; k < i; ++k) sent_at.emplace(records[k].key, now);
      if (options.transport == "tcp")
        asio::write(tcp_socket, asio::buffer(batch));
      else if (nats)
        natsConnection_Publish(nats->connection(), kNatsSubject, batch.data(), static_cast<int>(batch.size()));
      else
        udp_socket.send_to(asio::buffer(batch), udp::endpoint(address, daemon.input_port()));
      sent = i;
    }
  }
  const auto sent_all = Clock::now();
  // Wait until kewd has taken everything (UDP: until it stops progressing).
  std::uint64_t processed = 0, last = ~0ull;
  auto progressed = Clock::now();
  while (processed < records.size()) {
    processed = daemon.records_processed();
    if (processed != last) {
      last = processed;
      progressed = Clock::now();
    } else if (Clock::now() - progressed > std::chrono::seconds(2)) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const auto done = progressed;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // last alerts in flight
  subscriber.shutdown(tcp::socket::shutdown_both);
  reader.join();
  std::uint64_t map_messages = 0, map_bytes = 0;
  for (const auto& client : map_clients) {
    map_messages += client->messages();
    map_bytes += client->bytes();
  }
  map_clients.clear();
  std::remove(config.c_str());

  std::vector<double> latencies_us;
  for (const Received& r : received) {
    auto a = sent_at.find(r.key_a), b = sent_at.find(r.key_b);
    Clock::time_point from{};
    if (a != sent_at.end()) from = a->second;
    if (b != sent_at.end() && b->second > from) from = b->second;
    if (from == Clock::time_point{}) continue;
    latencies_us.push_back(std::chrono::duration<double, std::micro>(r.at - from).count());
  }
  const double seconds = std::chrono::duration<double>(done - start).count();
  const double send_seconds = std::chrono::duration<double>(sent_all - start).count();
  char host[256] = "?";
  ::gethostname(host, sizeof host);
  const std::string result = fmt::format(
      "{{\"bench\":\"ingest\",\"host\":\"{}\",\"transport\":\"{}\",\"target_rate\":{},\"records\":{},"
      "\"processed\":{},\"lost\":{},\"send_s\":{:.3f},\"seconds\":{:.3f},\"records_per_s\":{:.0f},"
      "\"alerts\":{},\"latency_us\":{{\"p50\":{:.0f},\"p90\":{:.0f},\"p99\":{:.0f},\"max\":{:.0f}}},"
      "\"map_clients\":{},\"map_messages\":{},\"map_bytes\":{}}}\n",
      host, options.transport, options.rate, records.size(), processed, records.size() - processed, send_seconds,
      seconds, static_cast<double>(processed) / seconds, latencies_us.size(), percentile(latencies_us, 0.5),
      percentile(latencies_us, 0.9), percentile(latencies_us, 0.99), percentile(latencies_us, 1.0),
      options.map_clients, map_messages, map_bytes);
  std::fputs(result.c_str(), stdout);
  if (!options.json.empty()) std::ofstream(options.json) << result;
  return 0;
}
