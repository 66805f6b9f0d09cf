#pragma once
// The replica count of a JetStream stream kewd relies on ([nats] replicas, design §5.9):
// the alert stream, a durable input's feed stream, the lease bucket's stream. A stream
// made earlier (by an earlier run with another count, or by an operator) is scaled to
// the configured count, so that one file says how many server failures the bus survives.

#include <string>

#include <nats/nats.h>

namespace kew::nats {

/// Sets the replicas of JetStream stream `stream` to `replicas` (1–5) when it has another
/// count, keeping the rest of its configuration. Returns what it did or why it could not
/// (a sentence for the log), or "" when the stream already has `replicas`. A stream that
/// cannot be read is left alone (""): its creator reports that.
std::string ensure_replicas(jsCtx* jetstream, const std::string& stream, int replicas);

/// "KV_<bucket>": the stream behind a key-value bucket.
std::string bucket_stream(const std::string& bucket);

}  // namespace kew::nats
