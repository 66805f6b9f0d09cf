#include "nats_connection.hpp"

#include "stream_setup.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace kew::nats {

NatsError::NatsError(std::string_view what, natsStatus status)
    : std::runtime_error(fmt::format("{}: {}", what, describe(status))), status_(status) {}

void check(natsStatus status, std::string_view what) {
  if (status != NATS_OK) throw NatsError(what, status);
}

std::string describe(natsStatus status) {
  std::string text = natsStatus_GetText(status);
  natsStatus last = NATS_OK;
  const char* detail = nats_GetLastError(&last);
  if (detail && *detail && last == status && text != detail) text += fmt::format(" ({})", detail);
  return text;
}

std::uint64_t kept_seq(jsCtx* jetstream, const std::string& stream, std::uint64_t stream_seq) {
  natsMsg* message = nullptr;
  check(js_GetMsg(&message, jetstream, stream.c_str(), stream_seq, nullptr, nullptr),
        fmt::format("message {} of {}", stream_seq, stream));
  const char* value = nullptr;
  std::uint64_t seq = 0;
  if (natsMsgHeader_Get(message, kSeqHeader, &value) == NATS_OK) seq = std::strtoull(value, nullptr, 10);
  natsMsg_Destroy(message);
  return seq;
}

kvStore* bind_key_value(jsCtx* jetstream, const std::string& name, double ttl_s, int replicas, std::string& scaled) {
  kvConfig kv;
  kvConfig_Init(&kv);
  kv.Bucket = name.c_str();
  kv.History = 1;
  kv.TTL = static_cast<std::int64_t>(ttl_s * 1e9);
  kv.StorageType = js_FileStorage;
  kv.Replicas = replicas;
  kvStore* bucket = nullptr;
  if (js_CreateKeyValue(&bucket, jetstream, &kv) == NATS_OK) return bucket;
  if (js_KeyValue(&bucket, jetstream, name.c_str()) != NATS_OK) return nullptr;
  scaled = ensure_replicas(jetstream, bucket_stream(name), replicas);
  return bucket;
}

namespace {

// The options live only through Connect: the connection keeps a copy.
struct Options {
  natsOptions* options = nullptr;
  Options() { check(natsOptions_Create(&options), "NATS options"); }
  ~Options() { natsOptions_Destroy(options); }
};

/// The server the connection is on now (of the list, or one its cluster announced).
std::string connected_url(natsConnection* connection) {
  char url[256] = "";
  if (natsConnection_GetConnectedUrl(connection, url, sizeof url) != NATS_OK || url[0] == 0) return "?";
  return url;
}

}  // namespace

NatsConnection::NatsConnection(const std::vector<std::string>& servers, const std::string& name,
                               EventHandler on_event, double reconnect_wait_s, double request_wait_s,
                               LinkHandler on_link)
    : servers_(fmt::format("{}", fmt::join(servers, ","))), on_event_(std::move(on_event)), on_link_(std::move(on_link)) {
  Options o;
  // A list, never one comma-separated URL: natsOptions_SetURL would take that as one
  // server and never reach any.
  std::vector<const char*> urls;
  for (const std::string& server : servers) urls.push_back(server.c_str());
  check(natsOptions_SetServers(o.options, urls.data(), static_cast<int>(urls.size())),
        fmt::format("NATS servers \"{}\"", servers_));
  check(natsOptions_SetName(o.options, name.c_str()), "NATS connection name");
  // For ever: a safety net outlives its bus's restarts.
  check(natsOptions_SetMaxReconnect(o.options, -1), "NATS reconnect");
  const auto wait_ms = static_cast<std::int64_t>(std::llround(std::max(reconnect_wait_s, 0.01) * 1000.0));
  check(natsOptions_SetReconnectWait(o.options, wait_ms), "NATS reconnect wait");
  check(natsOptions_SetRetryOnFailedConnect(o.options, true, &NatsConnection::on_connected, this),
        "NATS retry on failed connect");
  check(natsOptions_SetDisconnectedCB(o.options, &NatsConnection::on_disconnected, this), "NATS callbacks");
  check(natsOptions_SetReconnectedCB(o.options, &NatsConnection::on_reconnected, this), "NATS callbacks");
  check(natsOptions_SetErrorHandler(o.options, &NatsConnection::on_error, this), "NATS callbacks");
  check(natsOptions_SetClosedCB(o.options, &NatsConnection::on_closed, this), "NATS callbacks");
  const auto request_wait_ms = static_cast<std::int64_t>(std::llround(std::max(request_wait_s, 0.01) * 1000.0));
  // Two unanswered pings and the connection counts as lost.
  check(natsOptions_SetPingInterval(o.options, request_wait_ms), "NATS ping interval");
  check(natsOptions_SetMaxPingsOut(o.options, 2), "NATS pings");
  const natsStatus status = natsConnection_Connect(&connection_, o.options);
  if (status == NATS_OK) {
    ++connects_;
  } else if (status == NATS_NOT_YET_CONNECTED) {
    if (on_event_) on_event_(fmt::format("no NATS server at {} yet: connecting in the background", servers_));
  } else {
    throw NatsError(fmt::format("NATS connection to {}", servers_), status);
  }
  jsOptions js_options;
  jsOptions_Init(&js_options);
  js_options.Wait = request_wait_ms;
  const natsStatus js = natsConnection_JetStream(&jetstream_, connection_, &js_options);
  if (js != NATS_OK) {
    closing_ = true;
    natsConnection_Close(connection_);
    std::unique_lock lock(closed_mutex_);
    closed_changed_.wait_for(lock, std::chrono::seconds(5), [this] { return closed_; });
    lock.unlock();
    natsConnection_Destroy(connection_);
    throw NatsError("JetStream context", js);
  }
}

NatsConnection::~NatsConnection() {
  closing_ = true;
  jsCtx_Destroy(jetstream_);
  natsConnection_Close(connection_);
  {
    // Bounded: a client that never calls back must not hang kewd's exit.
    std::unique_lock lock(closed_mutex_);
    closed_changed_.wait_for(lock, std::chrono::seconds(5), [this] { return closed_; });
  }
  natsConnection_Destroy(connection_);
}

void NatsConnection::on_closed(natsConnection*, void* self) {
  auto* c = static_cast<NatsConnection*>(self);
  {
    const std::lock_guard lock(c->closed_mutex_);
    c->closed_ = true;
  }
  c->closed_changed_.notify_all();
}

bool NatsConnection::connected() const { return natsConnection_Status(connection_) == NATS_CONN_STATUS_CONNECTED; }

void NatsConnection::on_connected(natsConnection* connection, void* self) {
  auto* c = static_cast<NatsConnection*>(self);
  ++c->connects_;
  if (c->on_link_) c->on_link_(true);
  if (c->on_event_) c->on_event_(fmt::format("connected to NATS at {}", connected_url(connection)));
}

void NatsConnection::on_disconnected(natsConnection*, void* self) {
  auto* c = static_cast<NatsConnection*>(self);
  // Called also when a first connection attempt fails: only a lost connection counts.
  if (c->connects_.load() == 0 || c->closing_) return;
  ++c->disconnects_;
  if (c->on_link_) c->on_link_(false);
  if (c->on_event_) c->on_event_(fmt::format("lost the NATS server: reconnecting to one of {}", c->servers_));
}

void NatsConnection::on_reconnected(natsConnection* connection, void* self) {
  auto* c = static_cast<NatsConnection*>(self);
  ++c->connects_;
  if (c->on_link_) c->on_link_(true);
  if (c->on_event_) c->on_event_(fmt::format("reconnected to NATS at {}", connected_url(connection)));
}

void NatsConnection::on_error(natsConnection*, natsSubscription*, natsStatus status, void* self) {
  auto* c = static_cast<NatsConnection*>(self);
  if (c->on_event_ && !c->closing_) c->on_event_(fmt::format("NATS: {}", describe(status)));
}

}  // namespace kew::nats
