// [[notify]] tables (design §5.10).
#include "notify.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace kew::daemon {

namespace {

bool is_name(std::string_view name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
  });
}

}  // namespace

void read_notify(config::TableReader& r, NotifyConfig& n) {
  r.string("name", n.name);
  if (!is_name(n.name))
    r.fail(r.node("name") ? r.node("name") : r.table_node(),
           fmt::format("name = \"{}\": a notifier needs a name of letters, digits, '-' and '_' (it names its "
                       "outbox file and its metrics)",
                       n.name));
  r.http_url("url", n.url);
  r.path("url_file", n.url_file);
  if (n.url.empty() == n.url_file.empty())
    r.fail(r.table_node(), "a notifier needs url or url_file (a web hook whose URL is its secret), one of the two");
  r.choice("template", n.format, kNotifyTemplateNames);
  // What people read is rate-limited and coalesced unless the table says otherwise; a
  // program's web hook takes every event as it comes.
  if (for_people(n.format)) {
    n.max_per_minute = 20.0;
    n.coalesce_s = 30.0;
  }
  r.path("token_file", n.token_file);
  if (!n.token_file.empty() && (n.format == NotifyTemplate::Slack || n.format == NotifyTemplate::Mattermost ||
                                n.format == NotifyTemplate::Discord))
    r.fail(r.node("token_file"), fmt::format("template {} takes no token: its secret is the URL (url_file)",
                                             to_string(n.format)));
  r.http_header_list("headers", n.headers);
  r.path("ca_file", n.ca_file);
  r.string("title", n.title);
  r.choice("min_severity", n.min_severity, kSeverityNames, {Severity::None});
  r.choice_list("states", n.states, kNotifyStateNames);
  if (!r.node("states")) {
    n.states = for_people(n.format) ? std::vector{NotifyState::New, NotifyState::Escalated, NotifyState::Ended}
                                    : std::vector{NotifyState::New, NotifyState::Escalated, NotifyState::Updated,
                                                  NotifyState::Ended};
  } else if (n.states.empty()) {
    r.fail(r.node("states"), "states = []: a notifier that passes no state would never send; give at least one");
  }
  r.choice_list("kinds", n.kinds, kAlertKindNames);
  if (r.node("kinds") && n.kinds.empty())
    r.fail(r.node("kinds"), "kinds = []: a notifier that passes no kind of alert would never send; give at least one");
  r.word_list("regions", n.regions);
  r.word_list("callsigns", n.callsigns);
  r.word_list("addresses", n.addresses);
  r.word_list("volumes", n.volumes);
  r.number("timeout_s", n.timeout_s, 0.1, 600.0);
  r.number("backoff_min_s", n.backoff_min_s, 0.01, 3600.0);
  r.number("backoff_max_s", n.backoff_max_s, 0.01, 86400.0);
  if (n.backoff_max_s < n.backoff_min_s)
    r.fail(r.node("backoff_max_s"), fmt::format("backoff_max_s = {} is below backoff_min_s = {}", n.backoff_max_s,
                                                n.backoff_min_s));
  r.number("max_per_minute", n.max_per_minute, 0.0, 60000.0);
  r.number("coalesce_s", n.coalesce_s, 0.0, 86400.0);
  if (n.format == NotifyTemplate::Json && n.coalesce_s > 0)
    r.fail(r.node("coalesce_s"), "template json delivers every event: coalesce_s is for the templates people read");
  r.integer("outbox", n.outbox, 1, 10'000'000);
  r.number("failing_after_s", n.failing_after_s, 0.0, 86400.0);
}

}  // namespace kew::daemon
