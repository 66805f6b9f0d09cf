#include "inputs.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/multicast.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nats_input.hpp"
#include "http_poll_input.hpp"
#include "watched_file_input.hpp"
#include "accept_guard.hpp"
#include "udp_receiver.hpp"
#include "kew/config/address.hpp"
#include "kew/config/utc_day.hpp"
#include "kew/replay/pacer.hpp"
#include "kew/replay/recording_reader.hpp"
#include "kew/util/clocks.hpp"

namespace kew::daemon {

namespace asio = boost::asio;
using asio::ip::tcp;
using asio::ip::udp;

namespace {

constexpr std::size_t kReadBytes = 64 * 1024;
constexpr int kUdpReceiveBuffer = 8 * 1024 * 1024;

// The UTC midnight of today, for ASTERIX time of day in live inputs.
double today_utc_midnight() {
  const double now = util::unix_now_s();
  return now - std::fmod(now, 86400.0);
}

protocol::DecoderOptions options_for(const InputConfig& config, protocol::DecoderOptions options) {
  const std::optional<double> day = config::parse_utc_day(config.asterix_day);
  if (day) {
    options.asterix.day_start_utc_s = *day;
    options.asterix.day_from_pcap = false;
  } else if (config.transport != Transport::File && config.transport != Transport::WatchedFile &&
             config.transport != Transport::Http) {
    options.asterix.day_start_utc_s = today_utc_midnight();
  }
  return options;
}

template <class Endpoint>
Endpoint resolve_endpoint(asio::io_context& io, const std::string& address) {
  const config::HostPort endpoint = config::require_host_port(address);
  typename Endpoint::protocol_type::resolver resolver(io);
  return *resolver.resolve(endpoint.host, std::to_string(endpoint.port)).begin();
}

class UdpInput final : public Input {
 public:
  UdpInput(asio::io_context& io, InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : Input(std::move(config), std::move(options), std::move(handler)), socket_(io), buffer_(kMaxDatagramBytes) {
    const udp::endpoint endpoint = resolve_endpoint<udp::endpoint>(io, config_.address);
    socket_.open(endpoint.protocol());
    socket_.set_option(udp::socket::reuse_address(true));
    socket_.set_option(asio::socket_base::receive_buffer_size(kUdpReceiveBuffer));
    if (endpoint.address().is_multicast()) {
      // Bind the group's port on every address, then join the group on the interface.
      socket_.bind(udp::endpoint(endpoint.protocol(), endpoint.port()));
      if (endpoint.address().is_v4())
        socket_.set_option(asio::ip::multicast::join_group(endpoint.address().to_v4(),
                                                           asio::ip::make_address_v4(config_.interface)));
      else
        socket_.set_option(asio::ip::multicast::join_group(endpoint.address()));
    } else {
      socket_.bind(endpoint);
    }
    receiver_.emplace(socket_.native_handle());
    decoder_ = make_stream_decoder();
  }
  void start() override { receive(); }
  void stop() override {
    boost::system::error_code ignored;
    socket_.close(ignored);
    if (decoder_) retire(*decoder_);
  }
  std::uint16_t bound_port() const override { return socket_.local_endpoint().port(); }

 private:
  // The largest UDP payload; a longer datagram cannot exist, one cut by a smaller
  // buffer would be counted oversized.
  static constexpr std::size_t kMaxDatagramBytes = 65536;
  // Datagrams read per wake-up: a flood on one input leaves the I/O thread to the other
  // handlers between rounds.
  static constexpr std::size_t kDatagramsPerRound = 64;

  void add_open_stream_rejections(Rejections& out) const override {
    if (decoder_ && socket_.is_open()) out.merge(decoder_->rejections());
  }
  std::uint64_t datagrams_dropped() const override { return receiver_ ? receiver_->dropped() : 0; }
  void receive() {
    socket_.async_wait(udp::socket::wait_read, [this](const boost::system::error_code& ec) {
      if (ec == asio::error::operation_aborted || !socket_.is_open()) return;
      if (!ec) read_waiting_datagrams();
      if (socket_.is_open()) receive();
    });
  }
  void read_waiting_datagrams() {
    for (std::size_t round = 0; round < kDatagramsPerRound && socket_.is_open(); ++round) {
      std::size_t n = 0;
      switch (receiver_->receive(buffer_, n)) {
        case UdpReceiver::Outcome::Datagram:
          // Each datagram is one message, decoded alone: one sender's garbage or missing
          // final newline never joins another's next datagram.
          feed_message(*decoder_, buffer_.data(), n);
          break;
        case UdpReceiver::Outcome::Truncated:
          ++figures_.oversized_datagrams;
          break;
        case UdpReceiver::Outcome::Empty:
          return;
        case UdpReceiver::Outcome::Failed:
          // An ICMP error queued on the socket and the like: the next read goes on.
          break;
      }
    }
  }

  udp::socket socket_;
  std::optional<UdpReceiver> receiver_;  // reads socket_, set once it is bound
  std::vector<char> buffer_;
  std::unique_ptr<protocol::Decoder> decoder_;
};

// One TCP byte stream with its decoder, reading until EOF, error or, when `idle` is not
// zero, that long without a byte (then on_idle is called and the stream ends).
class TcpStream : public std::enable_shared_from_this<TcpStream> {
 public:
  TcpStream(tcp::socket socket, std::unique_ptr<protocol::Decoder> decoder,
            std::function<void(protocol::Decoder&, const void*, std::size_t)> feed,
            std::function<void(TcpStream&)> on_end, std::chrono::steady_clock::duration idle = {},
            std::function<void(TcpStream&)> on_idle = {})
      : socket_(std::move(socket)), decoder_(std::move(decoder)), feed_(std::move(feed)), on_end_(std::move(on_end)),
        idle_(idle), on_idle_(std::move(on_idle)), idle_timer_(socket_.get_executor()), buffer_(kReadBytes) {}
  void start() { read(); }
  void close() {
    boost::system::error_code ignored;
    idle_timer_.cancel();
    socket_.close(ignored);
  }
  protocol::Decoder& decoder() { return *decoder_; }
  const protocol::Decoder& decoder() const { return *decoder_; }
  std::string peer() const {
    boost::system::error_code ec;
    const auto ep = socket_.remote_endpoint(ec);
    return ec ? std::string("?") : ep.address().to_string() + ":" + std::to_string(ep.port());
  }

 private:
  void read() {
    if (idle_ > std::chrono::steady_clock::duration::zero()) {
      // Re-armed at every read: only a connection that sends nothing at all times out.
      idle_timer_.expires_after(idle_);
      idle_timer_.async_wait([weak = weak_from_this()](const boost::system::error_code& ec) {
        const auto self = weak.lock();
        if (ec || !self || self->ended_) return;
        // A completion already queued when a read re-armed the timer is not a time-out.
        if (self->idle_timer_.expiry() > std::chrono::steady_clock::now()) return;
        if (self->on_idle_) self->on_idle_(*self);
        self->close();
      });
    }
    socket_.async_read_some(asio::buffer(buffer_), [self = shared_from_this()](const boost::system::error_code& ec,
                                                                               std::size_t n) {
      if (n > 0) self->feed_(*self->decoder_, self->buffer_.data(), n);
      if (ec) {
        self->idle_timer_.cancel();
        if (!self->ended_) {
          self->ended_ = true;
          self->on_end_(*self);
        }
        return;
      }
      self->read();
    });
  }

  tcp::socket socket_;
  std::unique_ptr<protocol::Decoder> decoder_;
  std::function<void(protocol::Decoder&, const void*, std::size_t)> feed_;
  std::function<void(TcpStream&)> on_end_;
  std::chrono::steady_clock::duration idle_;
  std::function<void(TcpStream&)> on_idle_;
  asio::steady_timer idle_timer_;
  std::vector<char> buffer_;
  bool ended_ = false;
};

class TcpServerInput final : public Input {
 public:
  TcpServerInput(asio::io_context& io, InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : Input(std::move(config), std::move(options), std::move(handler)),
        acceptor_(io, resolve_endpoint<tcp::endpoint>(io, config_.address)),
        accept_guard_(acceptor_.get_executor(), "input " + config_.name) {
    log_.set_reporter([](std::string_view, std::string_view message) { spdlog::warn("{}", message); });
  }
  void start() override { accept(); }
  void stop() override {
    stopped_ = true;
    boost::system::error_code ignored;
    accept_guard_.cancel();
    acceptor_.close(ignored);
    const auto streams = streams_;
    for (const auto& s : streams) s->close();
  }
  std::uint16_t bound_port() const override { return acceptor_.local_endpoint().port(); }

 private:
  void add_open_stream_rejections(Rejections& out) const override {
    for (const auto& s : streams_) out.merge(s->decoder().rejections());
  }
  void accept() {
    acceptor_.async_accept([this](const boost::system::error_code& ec, tcp::socket socket) {
      if (stopped_ || ec == asio::error::operation_aborted) return;
      if (!accept_guard_.accepted(ec, figures_.accept_failures, [this] {
            if (!stopped_) accept();
          }))
        return;
      {
        if (streams_.size() >= config_.max_connections) {
          ++figures_.connections_refused;
          log_.reject("refused", fmt::format("input {}: refusing a feed connection (max_connections = {})",
                                             config_.name, config_.max_connections));
          boost::system::error_code ignored;
          socket.close(ignored);
        } else {
          ++figures_.connections;
          auto stream = std::make_shared<TcpStream>(
              std::move(socket), make_stream_decoder(),
              [this](protocol::Decoder& d, const void* data, std::size_t n) { feed(d, data, n); },
              [this](TcpStream& s) { end(s); },
              std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                  std::chrono::duration<double>(config_.idle_timeout_s)),
              [this](TcpStream& s) {
                ++figures_.connections_idle;
                log_.reject("idle", fmt::format("input {}: closing the feed connection from {}: no byte for {} s",
                                                config_.name, s.peer(), config_.idle_timeout_s));
              });
          streams_.push_back(stream);
          spdlog::info("input {}: feed connected from {}", config_.name, stream->peer());
          stream->start();
        }
      }
      accept();
    });
  }
  void end(TcpStream& stream) {
    retire(stream.decoder());
    spdlog::info("input {}: feed disconnected", config_.name);
    std::erase_if(streams_, [&](const auto& s) { return s.get() == &stream; });
  }

  tcp::acceptor acceptor_;
  AcceptGuard accept_guard_;
  Rejections log_;  // refusals and idle closes to the log, rate-limited (figures_ counts them)
  std::vector<std::shared_ptr<TcpStream>> streams_;
  bool stopped_ = false;
};

class TcpClientInput final : public Input {
 public:
  TcpClientInput(asio::io_context& io, InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : Input(std::move(config), std::move(options), std::move(handler)), io_(io), timer_(io),
        backoff_s_(config_.reconnect_min_s) {}
  void start() override { connect(); }
  void stop() override {
    stopped_ = true;
    timer_.cancel();
    if (socket_) {
      boost::system::error_code ignored;
      socket_->close(ignored);
    }
    if (stream_) stream_->close();
  }

 private:
  void add_open_stream_rejections(Rejections& out) const override {
    if (stream_) out.merge(stream_->decoder().rejections());
  }
  void connect() {
    if (stopped_) return;
    const config::HostPort remote = config::require_host_port(config_.address);
    socket_ = std::make_shared<tcp::socket>(io_);
    auto resolver = std::make_shared<tcp::resolver>(io_);
    resolver->async_resolve(remote.host, std::to_string(remote.port), [this, resolver](const boost::system::error_code& ec,
                                                                         tcp::resolver::results_type results) {
      if (stopped_) return;
      if (ec) return retry(ec.message());
      asio::async_connect(*socket_, results, [this](const boost::system::error_code& cec, const tcp::endpoint&) {
        if (stopped_) return;
        if (cec) return retry(cec.message());
        ++figures_.connections;
        backoff_s_ = config_.reconnect_min_s;
        spdlog::info("input {}: connected to {}", config_.name, config_.address);
        stream_ = std::make_shared<TcpStream>(
            std::move(*socket_), make_stream_decoder(),
            [this](protocol::Decoder& d, const void* data, std::size_t n) { feed(d, data, n); },
            [this](TcpStream& s) {
              retire(s.decoder());
              stream_.reset();
              retry("connection closed");
            });
        stream_->start();
      });
    });
  }
  void retry(const std::string& why) {
    if (stopped_) return;
    spdlog::warn("input {}: {} ({}); reconnecting in {:.1f} s", config_.name, config_.address, why, backoff_s_);
    timer_.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(backoff_s_)));
    backoff_s_ = std::min(backoff_s_ * 2.0, config_.reconnect_max_s);
    timer_.async_wait([this](const boost::system::error_code& ec) {
      if (!ec) connect();
    });
  }

  asio::io_context& io_;
  asio::steady_timer timer_;
  double backoff_s_;
  std::shared_ptr<tcp::socket> socket_;
  std::shared_ptr<TcpStream> stream_;
  bool stopped_ = false;
};

// Reads a recording through replay's RecordingReader (the reader kew-replay uses, with
// its read-error check) a batch of records per posted step, so that other inputs and
// subscribers are served in between; paced files release each record at its due time.
class FileInput final : public Input {
 public:
  FileInput(asio::io_context& io, InputConfig config, protocol::DecoderOptions options, ReportHandler handler)
      : Input(std::move(config), std::move(options), std::move(handler)), io_(io), timer_(io),
        pacer_(config_.pace ? config_.speed : 0.0) {}
  void start() override {
    reader_ = std::make_unique<replay::RecordingReader>(config_.address, config_.format, stream_options());
    log_rejections(reader_->rejections());
    if (!reader_->is_open()) {
      spdlog::error("input {}: cannot open {}", config_.name, config_.address);
      if (end_handler_) end_handler_();
      return;
    }
    asio::post(io_, [this] { step(); });
  }
  void stop() override {
    stopped_ = true;
    timer_.cancel();
  }

 private:
  // Records handed over per step: a few milliseconds of pipeline work.
  static constexpr std::size_t kRecordsPerStep = 1024;

  void add_open_stream_rejections(Rejections& out) const override {
    if (reader_) out.merge(reader_->rejections());
  }
  void step() {
    if (stopped_) return;
    const auto now = std::chrono::steady_clock::now();
    for (std::size_t n = 0; n < kRecordsPerStep; ++n) {
      if (!pending_) {
        TrackReport report;
        const bool more = reader_->next(report);
        figures_.bytes = reader_->bytes_read();
        if (!more) {
          spdlog::info("input {}: {} read to the end ({} reports)", config_.name, config_.address, figures_.reports);
          if (end_handler_) end_handler_();
          return;
        }
        ++figures_.reports;
        pending_ = std::move(report);
      }
      const auto due = pacer_.due(pending_->t);
      if (due > now) {
        timer_.expires_at(due);
        timer_.async_wait([this](const boost::system::error_code& ec) {
          if (!ec) step();
        });
        return;
      }
      handler_(*pending_);
      pending_.reset();
    }
    asio::post(io_, [this] { step(); });
  }

  asio::io_context& io_;
  asio::steady_timer timer_;
  replay::Pacer pacer_;
  std::unique_ptr<replay::RecordingReader> reader_;
  std::optional<TrackReport> pending_;  // read, not yet due
  bool stopped_ = false;
};

}  // namespace

protocol::DecoderOptions Input::stream_options() const { return options_for(config_, options_); }

void Input::log_rejections(Rejections& rejections) const {
  rejections.set_reporter([name = config_.name](std::string_view reason, std::string_view message) {
    spdlog::warn("input {}: rejected ({}) {}", name, reason, message);
  });
}

std::unique_ptr<protocol::Decoder> Input::make_stream_decoder() {
  auto decoder = protocol::make_decoder(config_.format, stream_options());
  log_rejections(decoder->rejections());
  return decoder;
}

void Input::deliver(const TrackReport& report) {
  ++figures_.reports;
  handler_(report);
}

void Input::feed(protocol::Decoder& decoder, const void* data, std::size_t n) {
  figures_.bytes += n;
  // A socket's bytes are live: ASTERIX times of day are dated by when they arrived,
  // unless the input names its day (asterix_day: a recorded stream played into kewd).
  if (config_.asterix_day.empty()) {
    decoder.set_receive_time(util::unix_now_s());
  }
  decoder.feed(std::span<const std::byte>(static_cast<const std::byte*>(data), n),
               [this](const TrackReport& r) { deliver(r); });
}

void Input::feed_message(protocol::Decoder& decoder, const void* data, std::size_t n) {
  feed(decoder, data, n);
  decoder.end_message([this](const TrackReport& r) { deliver(r); });
}

void Input::retire(protocol::Decoder& decoder) {
  decoder.finish([this](const TrackReport& r) { deliver(r); });
  figures_.rejected.merge(decoder.rejections());
  decoder.rejections() = Rejections();
}

std::unique_ptr<Input> make_input(asio::io_context& io, const InputConfig& config,
                                  const protocol::DecoderOptions& options, Input::ReportHandler handler) {
  switch (config.transport) {
    case Transport::Udp: return std::make_unique<UdpInput>(io, config, options, std::move(handler));
    case Transport::TcpServer: return std::make_unique<TcpServerInput>(io, config, options, std::move(handler));
    case Transport::TcpClient: return std::make_unique<TcpClientInput>(io, config, options, std::move(handler));
    case Transport::Nats: return make_nats_input(io, config, options, std::move(handler));
    case Transport::WatchedFile: return make_watched_file_input(io, config, options, std::move(handler));
    case Transport::Http: return make_http_poll_input(io, config, options, std::move(handler));
    case Transport::File: break;
  }
  return std::make_unique<FileInput>(io, config, options, std::move(handler));
}

std::string describe(const Input& input) {
  const std::uint16_t port = input.bound_port();
  return fmt::format("input {}: {} {} {}{}", input.config().name, protocol::to_string(input.config().format),
                     to_string(input.config().transport), input.config().address,
                     port ? fmt::format(" (port {})", port) : std::string());
}

}  // namespace kew::daemon
