#include "kew/daemon/modbus_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <fcntl.h>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "libmodbus_context.hpp"
#include "kew/config/address.hpp"
#include "slot_policy.hpp"

namespace kew::daemon {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::chrono::seconds kHeartbeatPeriod{1};
/// Bytes read from one client per poll round: a client that floods is served a chunk at a
/// time, taking turns with the others.
constexpr std::size_t kReadChunkBytes = 1024;

/// Owns one file descriptor.
class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) : fd_(fd) {}
  UniqueFd(UniqueFd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept {
    if (this != &other) {
      reset();
      fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
  }
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  ~UniqueFd() { reset(); }

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  void reset() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_ = -1;
};

/// The self-pipe that interrupts poll() when stop() is called, so stopping never waits
/// for the heartbeat timeout.
class WakePipe {
 public:
  WakePipe() {
    int fds[2];
    if (::pipe2(fds, O_NONBLOCK | O_CLOEXEC) != 0) {
      throw std::runtime_error("modbus: cannot create the wake-up pipe");
    }
    read_end_ = UniqueFd(fds[0]);
    write_end_ = UniqueFd(fds[1]);
  }
  int read_fd() const { return read_end_.get(); }
  void notify() {
    const char byte = 1;
    // A full pipe already holds a pending wake-up: nothing is lost when this fails.
    [[maybe_unused]] const auto written = ::write(write_end_.get(), &byte, 1);
  }
  void drain() {
    std::array<char, 64> sink;
    while (::read(read_end_.get(), sink.data(), sink.size()) > 0) {
    }
  }

 private:
  UniqueFd read_end_;
  UniqueFd write_end_;
};

struct Client {
  UniqueFd socket;
  protocol::MbapFramer framer;
  Clock::time_point last_request;
  std::string peer;          ///< "HOST:PORT", for acknowledgements and logs
  std::string address;       ///< the peer's HOST alone, as the slot policy compares them
  bool may_write = true;     ///< in acknowledge_from, or that list is empty
  bool requested = false;    ///< has completed a request (a panel, not a silent socket)
};

/// The peer of a connected socket as "HOST:PORT" (canonical_ip form), or "?".
config::HostPort peer_of(int fd) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (::getpeername(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) return {"?", 0};
  std::array<char, INET6_ADDRSTRLEN> text{};
  std::uint16_t port = 0;
  if (address.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&address);
    ::inet_ntop(AF_INET, &v4->sin_addr, text.data(), text.size());
    port = ntohs(v4->sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&address);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, text.data(), text.size());
    port = ntohs(v6->sin6_port);
  }
  return {config::canonical_ip(text.data()).value_or("?"), port};
}

LibmodbusContext open_context(const ModbusConfig& config) {
  std::string error;
  const std::optional<config::HostPort> listen = config::parse_host_port(config.listen, &error);
  if (!listen) throw std::runtime_error("modbus: listen address " + error);
  if (config.unit_id < 0 || config.unit_id > 247) {
    throw std::runtime_error("modbus: unit_id must be in 0-247");
  }
  if (config.table_entries < 0 || config.table_entries > protocol::kModbusMaxTableEntries) {
    throw std::runtime_error("modbus: table_entries must be in 0-64");
  }
  if (config.max_connections < 1) {
    throw std::runtime_error("modbus: max_connections must be at least 1");
  }
  return LibmodbusContext(listen->host, listen->port, config.max_connections,
                          protocol::modbus_register_count(config.table_entries));
}

}  // namespace

class ModbusServer::Impl {
 public:
  Impl(const ModbusConfig& config, AcknowledgeHandler on_acknowledge)
      : config_(config), on_acknowledge_(std::move(on_acknowledge)), modbus_(open_context(config)) {
    shape_.registers = protocol::modbus_register_count(config.table_entries);
    shape_.read_only = config.read_only;
    modbus_.load(protocol::build_register_map(current_, config_.table_entries, heartbeat_));
  }

  ~Impl() { stop(); }

  void start() {
    if (thread_.joinable() || stopping_) return;
    thread_ = std::thread([this] { run(); });
  }

  void stop() {
    stopping_ = true;
    wake_.notify();
    if (thread_.joinable()) thread_.join();
    modbus_.close_listener();
  }

  void publish(const protocol::AlarmSnapshot& snapshot, bool as_active) {
    std::lock_guard lock(snapshot_mutex_);
    published_ = snapshot;
    published_as_active_ = as_active;
    ++published_generation_;
  }

  void set_speaking_check(ModbusServer::SpeakingCheck check) { speaking_check_ = std::move(check); }

  std::uint16_t bound_port() const { return modbus_.bound_port(); }

  void set_reporter(Rejections::Reporter reporter) {
    std::lock_guard lock(stats_mutex_);
    stats_.rejected.set_reporter(std::move(reporter));
  }

  protocol::ModbusStatistics stats() const {
    std::lock_guard lock(stats_mutex_);
    return stats_;
  }

 private:
  void run() {
    next_heartbeat_ = Clock::now() + kHeartbeatPeriod;
    std::vector<pollfd> fds;
    while (!stopping_) {
      const Clock::time_point now = Clock::now();
      const bool beat = advance_heartbeat(now);
      refresh_map(beat);
      drop_idle_clients(now);

      fds.clear();
      fds.push_back({wake_.read_fd(), POLLIN, 0});
      // While accepting is paused (no descriptors) the listener is not watched: it would
      // stay readable and spin the loop.
      const bool accepting = now >= accept_resume_;
      fds.push_back({accepting ? modbus_.listen_fd() : -1, POLLIN, 0});
      for (const Client& c : clients_) fds.push_back({c.socket.get(), POLLIN, 0});
      const Clock::time_point wake_at = accepting ? next_heartbeat_ : std::min(next_heartbeat_, accept_resume_);
      const auto wait = std::chrono::ceil<std::chrono::milliseconds>(wake_at - now);
      const int ready = ::poll(fds.data(), fds.size(), static_cast<int>(std::max<long>(wait.count(), 0)));
      if (ready <= 0) continue;  // heartbeat due, or EINTR
      if (fds[0].revents != 0) wake_.drain();
      if (stopping_) break;
      // Requests are answered from the newest snapshot, even one published during poll().
      refresh_map(false);
      for (std::size_t i = 0; i < clients_.size(); ++i) {
        if (fds[i + 2].revents != 0) serve(clients_[i]);
      }
      std::erase_if(clients_, [](const Client& c) { return !c.socket.valid(); });
      if (fds[1].revents != 0) accept_clients();
      set_open_connections();
    }
    clients_.clear();
    set_open_connections();
  }

  /// True when the heartbeat register changed. A stalled thread resumes counting from
  /// now rather than catching up in a burst: the register says "alive", not "elapsed".
  bool advance_heartbeat(Clock::time_point now) {
    if (now < next_heartbeat_) return false;
    ++heartbeat_;  // wraps 65535 → 0
    next_heartbeat_ += kHeartbeatPeriod;
    if (next_heartbeat_ <= now) next_heartbeat_ = now + kHeartbeatPeriod;
    return true;
  }

  void refresh_map(bool heartbeat_changed) {
    bool snapshot_changed = false;
    {
      std::lock_guard lock(snapshot_mutex_);
      if (published_generation_ != served_generation_) {
        current_ = published_;
        current_as_active_ = published_as_active_;
        served_generation_ = published_generation_;
        snapshot_changed = true;
      }
    }
    if (snapshot_changed || heartbeat_changed) {
      modbus_.load(protocol::build_register_map(current_, config_.table_entries, heartbeat_));
    }
  }

  void accept_clients() {
    for (;;) {
      errno = 0;
      const int fd = modbus_.accept_client();
      if (fd < 0) break;
      accept_backoff_ = kAcceptBackoff;
      const Clock::time_point now = Clock::now();
      const config::HostPort peer = peer_of(fd);
      make_room(peer.host, now);
      std::erase_if(clients_, [](const Client& c) { return !c.socket.valid(); });
      std::lock_guard lock(stats_mutex_);
      if (clients_.size() >= static_cast<std::size_t>(config_.max_connections)) {
        ::close(fd);
        ++stats_.connections_refused;
        stats_.rejected.reject("modbus_connection_refused", "max_connections reached, every client active");
        continue;
      }
      ++stats_.connections_accepted;
      const auto& allowed = config_.acknowledge_from;
      const bool may_write = allowed.empty() || std::find(allowed.begin(), allowed.end(), peer.host) != allowed.end();
      clients_.push_back(Client{UniqueFd(fd), {}, now, config::to_string(peer), peer.host, may_write});
    }
    if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
      // The connection stays in the backlog; try again later, not at once.
      accept_resume_ = Clock::now() + accept_backoff_;
      accept_backoff_ = std::min<std::chrono::milliseconds>(accept_backoff_ * 2, std::chrono::seconds(1));
      std::lock_guard lock(stats_mutex_);
      stats_.rejected.reject("modbus_accept_failed", "cannot accept a client: out of file descriptors");
    }
  }

  /// Makes room for a new client from `address` by the rule every listener follows
  /// (design §6.6, slot_policy.hpp): a client that has completed no request is silent
  /// since it connected; one address holds at most silent_per_address silent clients,
  /// and when every slot is taken the longest-silent client of the address holding the
  /// most gives way. A client once answered is a panel and never silent: a reconnecting
  /// flood cannot push it out. When every slot holds one, the one quiet longest gives way
  /// if quiet half the idle timeout, so that clients which asked once and went quiet do
  /// not hold every slot for the whole idle timeout.
  void make_room(std::string_view address, Clock::time_point now) {
    std::vector<SlotHolder> holders;
    holders.reserve(clients_.size());
    std::size_t open = 0;
    for (const Client& c : clients_) {
      holders.push_back({c.address, c.socket.valid() && !c.requested, c.last_request});
      open += c.socket.valid() ? 1 : 0;
    }
    const bool every_slot_taken = open >= static_cast<std::size_t>(config_.max_connections);
    if (const auto i = connection_to_evict(holders, address, static_cast<std::size_t>(config_.silent_per_address),
                                               every_slot_taken)) {
      drop(clients_[*i], "modbus_evicted");
      return;
    }
    if (!every_slot_taken) return;
    auto quietest = clients_.end();
    for (auto it = clients_.begin(); it != clients_.end(); ++it) {
      if (it->socket.valid() && (quietest == clients_.end() || it->last_request < quietest->last_request)) quietest = it;
    }
    if (quietest != clients_.end() && now - quietest->last_request >= idle_timeout_ / 2) drop(*quietest, "modbus_evicted");
  }

  void drop_idle_clients(Clock::time_point now) {
    for (Client& c : clients_) {
      if (now - c.last_request >= idle_timeout_) drop(c, "modbus_idle_timeout");
    }
    std::erase_if(clients_, [](const Client& c) { return !c.socket.valid(); });
    set_open_connections();
  }

  /// Reads what the client sent and answers every complete request in it.
  void serve(Client& client) {
    std::array<std::uint8_t, kReadChunkBytes> buffer;
    const ssize_t received = ::recv(client.socket.get(), buffer.data(), buffer.size(), 0);
    if (received == 0 || (received < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      client.socket.reset();  // the client hung up
      return;
    }
    if (received < 0) return;
    Rejections framing;
    bool answered = true;
    const bool framed = client.framer.feed(
        std::span<const std::uint8_t>(buffer.data(), static_cast<std::size_t>(received)), framing,
        [&](std::span<const std::uint8_t> adu) {
          if (answered) answered = answer(client, adu);
        });
    if (!framed) {
      std::lock_guard lock(stats_mutex_);
      stats_.rejected.merge(framing);
    }
    if (!framed) {
      drop(client, {});
    } else if (!answered && client.socket.valid()) {
      drop(client, "modbus_send_failed");
    }
  }

  /// Answers one ADU; false when the client must be dropped.
  bool answer(Client& client, std::span<const std::uint8_t> adu) {
    client.last_request = Clock::now();
    client.requested = true;
    const std::uint8_t unit = adu[protocol::MbapFramer::kHeaderBytes - 1];
    const auto pdu = adu.subspan(protocol::MbapFramer::kHeaderBytes);
    protocol::ModbusVerdict verdict;
    std::string message;
    if (!protocol::modbus_unit_is_ours(unit, config_.unit_id)) {
      verdict.exception = protocol::ModbusException::GatewayTargetFailedToRespond;
      verdict.reason = "modbus_unit_id_mismatch";
    } else if (current_as_active_ && speaking_check_ && !speaking_check_()) {
      // Woken from a stall after the lease passed on: what this snapshot says (and an
      // acknowledgement of it) is no longer this instance's to give.
      verdict.exception = protocol::ModbusException::ServerDeviceBusy;
      verdict.reason = "modbus_not_speaking";
    } else if (!client.may_write && !pdu.empty() && protocol::modbus_function_writes(pdu[0])) {
      // Refused like a write to a read-only map (the function is not available to it).
      verdict.exception = protocol::ModbusException::IllegalFunction;
      verdict.reason = "modbus_write_not_permitted";
      message = "a write from " + client.peer + ", which is not in acknowledge_from";
    } else {
      verdict = protocol::check_modbus_request(pdu, shape_);
    }
    count_request(verdict, message);
    if (verdict.drop_connection) {
      drop(client, {});
      return false;
    }
    if (verdict.exception != protocol::ModbusException::None) {
      return modbus_.reply_exception(client.socket.get(), adu, verdict.exception);
    }
    if (verdict.acknowledge) acknowledge(client.peer);
    return modbus_.reply(client.socket.get(), adu);
  }

  void acknowledge(const std::string& client) {
    {
      std::lock_guard lock(stats_mutex_);
      ++stats_.acknowledgements;
    }
    // The callback belongs to the daemon; whatever it throws must not end this thread.
    try {
      if (on_acknowledge_) on_acknowledge_(client);
    } catch (...) {
      std::lock_guard lock(stats_mutex_);
      stats_.rejected.reject("modbus_acknowledge_callback_failed");
    }
  }

  void count_request(const protocol::ModbusVerdict& verdict, std::string_view message) {
    std::lock_guard lock(stats_mutex_);
    ++stats_.requests;
    if (verdict.exception != protocol::ModbusException::None && !verdict.drop_connection) {
      ++stats_.exceptions;
    }
    if (!verdict.reason.empty()) stats_.rejected.reject(verdict.reason, message);
  }

  /// Closes a client kew gives up on, counting `reason` unless it was counted already.
  void drop(Client& client, std::string_view reason) {
    client.socket.reset();
    std::lock_guard lock(stats_mutex_);
    ++stats_.connections_dropped;
    if (!reason.empty()) stats_.rejected.reject(reason);
  }

  void set_open_connections() {
    std::lock_guard lock(stats_mutex_);
    stats_.connections_open = clients_.size();
  }

  const ModbusConfig config_;
  const AcknowledgeHandler on_acknowledge_;
  LibmodbusContext modbus_;
  protocol::ModbusMapShape shape_;
  WakePipe wake_;
  std::thread thread_;
  std::atomic<bool> stopping_{false};

  // Written by publish(), read by the server thread.
  mutable std::mutex snapshot_mutex_;
  protocol::AlarmSnapshot published_;
  bool published_as_active_ = false;  // guarded by snapshot_mutex_
  std::uint64_t published_generation_ = 0;

  // Set before start().
  ModbusServer::SpeakingCheck speaking_check_;

  // The server thread's own state.
  protocol::AlarmSnapshot current_;
  bool current_as_active_ = false;
  std::uint64_t served_generation_ = 0;
  std::uint16_t heartbeat_ = 0;
  Clock::time_point next_heartbeat_;
  std::vector<Client> clients_;
  const Clock::duration idle_timeout_ = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(config_.idle_timeout_s));
  Clock::time_point accept_resume_{};  // accepting paused until then (out of descriptors)
  std::chrono::milliseconds accept_backoff_ = kAcceptBackoff;

  mutable std::mutex stats_mutex_;
  protocol::ModbusStatistics stats_;
};

ModbusServer::ModbusServer(const ModbusConfig& config, AcknowledgeHandler on_acknowledge)
    : impl_(std::make_unique<Impl>(config, std::move(on_acknowledge))) {}

ModbusServer::~ModbusServer() = default;

void ModbusServer::set_reporter(Rejections::Reporter reporter) { impl_->set_reporter(std::move(reporter)); }
void ModbusServer::start() { impl_->start(); }
void ModbusServer::stop() { impl_->stop(); }
void ModbusServer::publish(const protocol::AlarmSnapshot& snapshot, bool as_active) {
  impl_->publish(snapshot, as_active);
}
void ModbusServer::set_speaking_check(SpeakingCheck check) { impl_->set_speaking_check(std::move(check)); }
std::uint16_t ModbusServer::bound_port() const { return impl_->bound_port(); }
protocol::ModbusStatistics ModbusServer::stats() const { return impl_->stats(); }

}  // namespace kew::daemon
