#pragma once
// The bodies and headers of notifications (design §5.10), one function per template:
// json posts the stream's ALERT object as the stream writes it; the others write a few
// lines a person reads on a phone or in a chat.

#include <string>
#include <vector>

#include "kew/daemon/notify_config.hpp"
#include "outbox.hpp"

namespace kew::daemon {

struct NotifyMessage {
  std::string body;
  std::vector<std::string> headers;  ///< "Name: value" each, Content-Type included
};

/// The title a person reads first: "kew: LOSS DLH4AB / N907LP" (`title` the first word).
std::string message_title(const std::string& title, const OutboxEntry& entry);
/// The text under it: what the pair's separation is and will be, and the alert's story
/// when the message carries several of its events.
std::string message_text(const OutboxEntry& entry);

/// The request for `entry` in `format`; `token` ("" none) from the notifier's token file.
/// Every message carries `Kew-Seq` (its last event's seq) and `Kew-Alert` (the alert id),
/// so that a receiver can recognise a message it has had.
NotifyMessage render_message(const NotifyConfig& config, const OutboxEntry& entry, const std::string& token);

}  // namespace kew::daemon
