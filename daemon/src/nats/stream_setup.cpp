#include "stream_setup.hpp"

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

namespace {

// "stream name already in use with a different configuration"
constexpr jsErrCode kStreamNameInUse = static_cast<jsErrCode>(10058);

std::string failure(const std::string& doing, natsStatus s, jsErrCode error) {
  return fmt::format("{}: {}{}", doing, describe(s),
                     error ? fmt::format(" (JetStream error {})", static_cast<int>(error)) : "");
}

}  // namespace

StreamSetup ensure_stream(jsCtx* jetstream, const StreamSpec& spec, IfExists if_exists) {
  std::vector<const char*> subjects;
  for (const std::string& subject : spec.subjects) subjects.push_back(subject.c_str());
  jsStreamConfig stream;
  jsStreamConfig_Init(&stream);
  stream.Name = spec.name.c_str();
  stream.Subjects = subjects.data();
  stream.SubjectsLen = static_cast<int>(subjects.size());
  if (spec.max_age_s > 0) stream.MaxAge = static_cast<std::int64_t>(spec.max_age_s * 1e9);
  stream.MaxBytes = spec.max_bytes;
  stream.Storage = js_FileStorage;
  stream.Replicas = spec.replicas;

  jsStreamInfo* info = nullptr;
  jsErrCode error = static_cast<jsErrCode>(0);
  natsStatus s = js_GetStreamInfo(&info, jetstream, spec.name.c_str(), nullptr, &error);
  jsStreamInfo_Destroy(info);
  info = nullptr;
  bool exists = s == NATS_OK;
  if (!exists) {
    if (error != JSStreamNotFoundErr)
      return {false, false, failure(fmt::format("cannot read the JetStream stream {}", spec.name), s, error)};
    error = static_cast<jsErrCode>(0);
    s = js_AddStream(&info, jetstream, &stream, nullptr, &error);
    jsStreamInfo_Destroy(info);
    info = nullptr;
    if (s == NATS_OK) return {true, true, {}};
    if (error != kStreamNameInUse)  // not made by another meanwhile
      return {false, false, failure(fmt::format("cannot create the JetStream stream {}", spec.name), s, error)};
  }
  if (if_exists == IfExists::Keep) return {true, false, ensure_replicas(jetstream, spec.name, spec.replicas)};
  error = static_cast<jsErrCode>(0);
  s = js_UpdateStream(&info, jetstream, &stream, nullptr, &error);
  jsStreamInfo_Destroy(info);
  if (s == NATS_OK) return {true, false, {}};
  // It exists: it is used as it is, and the operator is told what differs.
  return {true, false,
          failure(fmt::format("the JetStream stream {} cannot take this configuration ({} replicas); used as it is",
                              spec.name, spec.replicas),
                  s, error)};
}

std::string bucket_stream(const std::string& bucket) { return "KV_" + bucket; }

}  // namespace kew::nats
