#include "stream_replicas.hpp"

#include <fmt/format.h>

#include "nats_connection.hpp"

namespace kew::nats {

std::string ensure_replicas(jsCtx* jetstream, const std::string& stream, int replicas) {
  jsStreamInfo* info = nullptr;
  if (js_GetStreamInfo(&info, jetstream, stream.c_str(), nullptr, nullptr) != NATS_OK || !info->Config) {
    jsStreamInfo_Destroy(info);
    return {};
  }
  const std::int64_t had = info->Config->Replicas;
  std::string outcome;
  if (had != replicas) {
    info->Config->Replicas = replicas;
    jsStreamInfo* updated = nullptr;
    jsErrCode error = static_cast<jsErrCode>(0);
    const natsStatus s = js_UpdateStream(&updated, jetstream, info->Config, nullptr, &error);
    jsStreamInfo_Destroy(updated);
    outcome = s == NATS_OK
                  ? fmt::format("the JetStream stream {} had {} replicas: {} now", stream, had, replicas)
                  : fmt::format("the JetStream stream {} has {} replicas and cannot have {} ([nats] replicas): "
                                "{}{}; it is used as it is",
                                stream, had, replicas, describe(s),
                                error ? fmt::format(" (JetStream error {})", static_cast<int>(error)) : "");
  }
  jsStreamInfo_Destroy(info);
  return outcome;
}

std::string bucket_stream(const std::string& bucket) { return "KV_" + bucket; }

}  // namespace kew::nats
