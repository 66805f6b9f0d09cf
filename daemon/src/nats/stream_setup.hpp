#pragma once
// The JetStream streams kewd relies on (design §5.9): the alert stream, the checkpoint
// stream, a durable input's feed stream, the lease bucket's stream. Each is made when
// missing; one made earlier (by an earlier run, or by an operator) either follows the
// configuration or keeps its own subjects and limits, and in either case its replica
// count is the configured one ([nats] replicas), so that one file says how many server
// failures the bus survives.

#include <cstdint>
#include <string>
#include <vector>

#include <nats/nats.h>

namespace kew::nats {

struct StreamSpec {
  std::string name;
  std::vector<std::string> subjects;
  double max_age_s = 0;         ///< messages older leave the stream; 0: kept for ever
  std::int64_t max_bytes = -1;  ///< the oldest leave beyond this size; -1: no limit
  int replicas = 1;             ///< 1–5
};

/// What becomes of a stream that exists already.
enum class IfExists {
  Update,  ///< it takes the spec's subjects, limits and replicas
  Keep,    ///< its subjects and limits stay; its replicas are scaled to the spec's
};

struct StreamSetup {
  bool ready = false;    ///< the stream exists (made, kept or updated): use it
  bool created = false;  ///< made by this call
  /// For the log: why it is not ready, or what differs from the spec in a stream that
  /// could not be changed (ready all the same), or how its replicas were scaled; "" when
  /// there is nothing to say.
  std::string note;
};

/// Makes stream `spec` in `jetstream`, or takes the one of that name as `if_exists` says.
StreamSetup ensure_stream(jsCtx* jetstream, const StreamSpec& spec, IfExists if_exists);

/// Sets the replicas of JetStream stream `stream` to `replicas` (1–5) when it has another
/// count, keeping the rest of its configuration. Returns what it did or why it could not
/// (a sentence for the log), or "" when the stream already has `replicas`. A stream that
/// cannot be read is left alone (""): its creator reports that.
std::string ensure_replicas(jsCtx* jetstream, const std::string& stream, int replicas);

/// "KV_<bucket>": the stream behind a key-value bucket.
std::string bucket_stream(const std::string& bucket);

}  // namespace kew::nats
