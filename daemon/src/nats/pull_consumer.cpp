#include "pull_consumer.hpp"

#include <fmt/format.h>

#include "nats_connection.hpp"

namespace kew::nats {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::string_view kAckPrefix = "$JS.ACK.";

bool from_the_stream(natsMsg* message) {
  const char* reply = natsMsg_GetReply(message);
  return reply != nullptr && std::string_view(reply).substr(0, kAckPrefix.size()) == kAckPrefix;
}

/// A status message's code ("404", "408", "409", "100", "503"), or "" when it has none.
std::string status_of(natsMsg* message) {
  const char* value = nullptr;
  if (natsMsgHeader_Get(message, "Status", &value) != NATS_OK || value == nullptr) return {};
  return std::string(std::string_view(value).substr(0, 3));
}

std::string description_of(natsMsg* message) {
  const char* value = nullptr;
  if (natsMsgHeader_Get(message, "Description", &value) != NATS_OK || value == nullptr) return {};
  return value;
}

/// The stream that stores `subject`, as the server names it.
std::string stream_of(jsCtx* jetstream, const std::string& subject) {
  jsOptions options;
  jsOptions_Init(&options);
  options.Stream.Info.SubjectsFilter = subject.c_str();
  jsStreamNamesList* names = nullptr;
  check(js_StreamNames(&names, jetstream, &options, nullptr), "listing the streams that store " + subject);
  std::string stream = names != nullptr && names->Count > 0 ? names->List[0] : "";
  jsStreamNamesList_Destroy(names);
  if (stream.empty()) throw NatsError("no JetStream stream stores " + subject, NATS_NOT_FOUND);
  return stream;
}

}  // namespace

PullConsumer::PullConsumer(NatsConnection& connection, const Options& options)
    : connection_(connection), durable_(options.durable) {
  bind(options);
  natsInbox* inbox = nullptr;
  check(natsInbox_Create(&inbox), "making an inbox");
  inbox_ = std::string(inbox) + ".";
  natsInbox_Destroy(inbox);
  // What waits here is bounded by the requests, each for at most one fetch's batch.
  check(natsConnection_SubscribeSync(&replies_, connection_.get(), (inbox_ + "*").c_str()),
        "subscribing to the pull requests' inbox");
}

PullConsumer::~PullConsumer() { natsSubscription_Destroy(replies_); }

void PullConsumer::bind(const Options& options) {
  jsCtx* jetstream = connection_.jetstream();
  stream_ = options.stream.empty() ? stream_of(jetstream, options.subject) : options.stream;
  jsErrCode error = static_cast<jsErrCode>(0);
  if (options.start_sequence) {
    // What this consumer took before belongs to a computation the reader no longer has:
    // it is made again from the sequence asked for.
    const natsStatus deleted = js_DeleteConsumer(jetstream, stream_.c_str(), durable_.c_str(), nullptr, &error);
    if (deleted != NATS_OK && deleted != NATS_NOT_FOUND && error != JSConsumerNotFoundErr)
      throw NatsError(fmt::format("making the JetStream consumer {} again", durable_), deleted);
  } else {
    jsConsumerInfo* info = nullptr;
    const natsStatus found = js_GetConsumerInfo(&info, jetstream, stream_.c_str(), durable_.c_str(), nullptr, &error);
    jsConsumerInfo_Destroy(info);
    if (found == NATS_OK) return;  // made by an earlier run: it resumes where that one was
    if (found != NATS_NOT_FOUND && error != JSConsumerNotFoundErr)
      throw NatsError(fmt::format("reading the JetStream consumer {}", durable_), found);
  }
  std::optional<std::uint64_t> start = options.start_sequence;
  if (start && *start > 1) {
    // A start past the stream's end: the stream was made anew since that sequence was
    // read (a server that lost its store), so all of the new one is unread.
    jsStreamInfo* info = nullptr;
    if (js_GetStreamInfo(&info, jetstream, stream_.c_str(), nullptr, nullptr) == NATS_OK) {
      if (*start > info->State.LastSeq + 1) start.reset();
      jsStreamInfo_Destroy(info);
    }
  }
  jsConsumerConfig config;
  jsConsumerConfig_Init(&config);
  config.Durable = durable_.c_str();
  config.FilterSubject = options.subject.c_str();
  config.AckPolicy = js_AckAll;
  config.AckWait = options.ack_wait_ns;
  config.DeliverPolicy = start ? js_DeliverByStartSequence : js_DeliverAll;
  if (start) config.OptStartSeq = *start;
  jsConsumerInfo* info = nullptr;
  error = static_cast<jsErrCode>(0);
  const natsStatus made = js_AddConsumer(&info, jetstream, stream_.c_str(), &config, nullptr, &error);
  jsConsumerInfo_Destroy(info);
  if (made != NATS_OK)
    throw NatsError(fmt::format("creating the JetStream consumer {} on {}{}", durable_, stream_,
                                error ? fmt::format(" (JetStream error {})", static_cast<int>(error)) : ""),
                    made);
}

natsStatus PullConsumer::request_more(int max, std::int64_t wait_ms) {
  ++request_;
  const std::string reply = inbox_ + std::to_string(request_);
  const std::string subject = fmt::format("$JS.API.CONSUMER.MSG.NEXT.{}.{}", stream_, durable_);
  const std::string body = fmt::format(R"({{"batch":{},"expires":{}}})", max, wait_ms * 1'000'000);
  const natsStatus s = natsConnection_PublishRequest(connection_.get(), subject.c_str(), reply.c_str(), body.data(),
                                                     static_cast<int>(body.size()));
  if (s == NATS_OK) {
    open_ = max;
    open_until_ = Clock::now() + std::chrono::milliseconds(wait_ms);
  }
  return s;
}

natsStatus PullConsumer::fetch(std::vector<natsMsg*>& out, int max, std::int64_t wait_ms) {
  const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(wait_ms);
  const std::size_t first = out.size();
  const auto taken = [&] { return static_cast<int>(out.size() - first); };
  while (taken() < max) {
    const Clock::time_point now = Clock::now();
    if (open_ <= 0 || now >= open_until_) {
      // The last request is answered or expired: ask for what this fetch may still take,
      // for as long as it may still wait. Not while the connection is down: the client
      // would keep the requests and send them all at reconnection.
      if (!connection_.connected()) {
        open_ = 0;
        return taken() > 0 ? NATS_OK : NATS_CONNECTION_DISCONNECTED;
      }
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count();
      if (left <= 0) break;
      const natsStatus s = request_more(max - taken(), left);
      if (s != NATS_OK) return taken() > 0 ? NATS_OK : s;
    }
    // Once something is taken, only what has already arrived: a live feed is not held
    // back to fill a batch.
    const std::int64_t wait =
        taken() > 0 ? 0
                    : std::max<std::int64_t>(
                          1, std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count());
    natsMsg* message = nullptr;
    const natsStatus s = natsSubscription_NextMsg(&message, replies_, wait);
    if (s == NATS_TIMEOUT) break;
    if (s != NATS_OK) {
      open_ = 0;  // a 503 (no JetStream answering) or a closed connection ends the request
      return taken() > 0 ? NATS_OK : s;
    }
    if (from_the_stream(message)) {
      out.push_back(message);
      --open_;
      continue;
    }
    // A status answers a request: only the last one's ends it (an older one's can arrive late).
    const bool of_the_last = std::string_view(natsMsg_GetSubject(message)) == inbox_ + std::to_string(request_);
    const std::string status = status_of(message);
    const std::string description = description_of(message);
    natsMsg_Destroy(message);
    if (status == "100") continue;  // a heartbeat
    if (of_the_last) open_ = 0;
    if (status == "409" && description.find("Deleted") != std::string::npos) return NATS_NOT_FOUND;
    if (status == "503") return taken() > 0 ? NATS_OK : NATS_NO_RESPONDERS;
    // 409: the server ended the request (its leader changed, too many waiting): the next
    // fetch asks again. 404/408: nothing more for that request; the next pass asks again
    // while time is left.
    if (status == "409") break;
  }
  return taken() > 0 ? NATS_OK : NATS_TIMEOUT;
}

natsStatus PullConsumer::acknowledge(natsConnection* connection, natsMsg* last) {
  const char* reply = natsMsg_GetReply(last);
  if (reply == nullptr) return NATS_INVALID_ARG;
  return natsConnection_Publish(connection, reply, "+ACK", 4);
}

natsStatus PullConsumer::undelivered(std::uint64_t& count, std::int64_t wait_ms) {
  jsOptions options;
  jsOptions_Init(&options);
  options.Wait = wait_ms;
  jsConsumerInfo* info = nullptr;
  jsErrCode error = static_cast<jsErrCode>(0);
  natsStatus s = js_GetConsumerInfo(&info, connection_.jetstream(), stream_.c_str(), durable_.c_str(), &options, &error);
  if (s == NATS_OK) count = info->NumPending;
  jsConsumerInfo_Destroy(info);
  // Gone only on the server's word (the consumer or its stream not found): the caller
  // deletes and makes the consumer again on it.
  if (s != NATS_OK && (error == JSConsumerNotFoundErr || error == JSStreamNotFoundErr)) return NATS_NOT_FOUND;
  return s == NATS_NOT_FOUND ? NATS_ERR : s;
}

}  // namespace kew::nats
