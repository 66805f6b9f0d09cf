#pragma once
// [[notify]]: alert events posted over HTTP(S) to a person's phone, a chat or a web hook
// (design §5.10). Every key, its unit and its default is documented in deploy/kew.toml.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "kew/alert/alert_event.hpp"
#include "kew/util/name_table.hpp"

namespace kew::daemon {

/// What a notification's body looks like, for the services people run.
enum class NotifyTemplate : std::uint8_t {
  Json,        ///< the stream's ALERT object, byte for byte (a web hook of one's own)
  Ntfy,        ///< ntfy: a text body, Title, Priority and Tags headers
  Gotify,      ///< Gotify's POST /message: {"title", "message", "priority"}
  Slack,       ///< Slack incoming web hook: {"text"}
  Mattermost,  ///< Mattermost incoming web hook: {"text"} (Slack's form)
  Discord,     ///< Discord web hook: {"content"}
};
inline constexpr util::NameTable<NotifyTemplate, 6> kNotifyTemplateNames({{
    {NotifyTemplate::Json, "json"},
    {NotifyTemplate::Ntfy, "ntfy"},
    {NotifyTemplate::Gotify, "gotify"},
    {NotifyTemplate::Slack, "slack"},
    {NotifyTemplate::Mattermost, "mattermost"},
    {NotifyTemplate::Discord, "discord"},
}});
constexpr std::string_view to_string(NotifyTemplate t) { return kNotifyTemplateNames.name(t); }
/// Templates written for people (all but json): coalesced and rate-limited by default.
constexpr bool for_people(NotifyTemplate t) { return t != NotifyTemplate::Json; }

/// What an alert event means to a notifier (the `states` filter).
enum class NotifyState : std::uint8_t {
  New,        ///< the alert opened
  Escalated,  ///< its severity rose (or first reached min_severity)
  Updated,    ///< any other update (figures, a lower severity)
  Ended,      ///< it ended
};
inline constexpr util::NameTable<NotifyState, 4> kNotifyStateNames({{
    {NotifyState::New, "new"},
    {NotifyState::Escalated, "escalated"},
    {NotifyState::Updated, "updated"},
    {NotifyState::Ended, "ended"},
}});
constexpr std::string_view to_string(NotifyState s) { return kNotifyStateNames.name(s); }

/// One `[[notify]]` table.
struct NotifyConfig {
  /// Names the notifier in logs, ?STATS, /metrics and its outbox file: letters, digits,
  /// '-' and '_'; unique.
  std::string name;
  /// Where each message is posted (http:// or https://). Web hook URLs that carry their
  /// secret (Slack, Discord, Mattermost) go in url_file instead: one of the two.
  std::string url;
  std::string url_file;
  NotifyTemplate format = NotifyTemplate::Json;  ///< key `template`
  /// A file holding the token: json, ntfy: "Authorization: Bearer TOKEN"; gotify:
  /// "X-Gotify-Key: TOKEN". "" none.
  std::string token_file;
  std::vector<std::string> headers;  ///< sent with every message, "Name: value"
  std::string ca_file;               ///< PEM certificates trusted besides the system's
  std::string title = "kew";         ///< the first word of a message for people

  // Which events: all of these must pass.
  Severity min_severity = Severity::Caution;
  /// Default: every state for json; new, escalated and ended for the other templates.
  std::vector<NotifyState> states;
  /// Which safety nets: conflicts between aircraft (stca), aircraft and volumes (apw).
  std::vector<AlertKind> kinds{AlertKind::Stca, AlertKind::Apw};
  /// [[region]] names of the pairs (stca); a pair judged by the defaults (no region)
  /// passes only when empty. Apw alerts are judged by their volume, never a region: this
  /// filter leaves them to `kinds` and `volumes`.
  std::vector<std::string> regions;
  /// An alert passes when one of these matches (patterns: '*' any run, '?' one character,
  /// case-insensitive): an aircraft's callsign one of `callsigns`, its track id (ICAO
  /// address) one of `addresses`, or an apw alert's volume name one of `volumes`; all
  /// three empty: every alert.
  std::vector<std::string> callsigns;
  std::vector<std::string> addresses;
  std::vector<std::string> volumes;

  // Delivery.
  double timeout_s = 10.0;        ///< one request, connection and transfer together
  double backoff_min_s = 1.0;     ///< after a failure, doubling up to backoff_max_s
  double backoff_max_s = 60.0;
  /// Messages per minute at most (0: no limit); default 0 for json, 20 for people.
  double max_per_minute = 0.0;
  /// People: after a message about an alert, its next events wait this long and go as
  /// one message (0: each at once); default 30 for people; json: 0, every event.
  double coalesce_s = 0.0;
  std::size_t outbox = 10000;     ///< events waiting at most; beyond, the oldest is dropped
  /// notify_failing once the oldest waiting event has waited this long without delivery.
  double failing_after_s = 60.0;
};

}  // namespace kew::daemon
