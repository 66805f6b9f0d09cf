#include "message_template.hpp"

#include <cmath>

#include <fmt/format.h>

#include "kew/protocol/ndjson_writer.hpp"
#include "kew/protocol/utc_text.hpp"
#include "kew/util/units.hpp"

namespace kew::daemon {

namespace {

std::string party_name(const AlertParty& party) { return party.callsign.empty() ? party.id : party.callsign; }

std::string duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s < 60) return fmt::format("{} s", s);
  return s % 60 == 0 ? fmt::format("{} min", s / 60) : fmt::format("{} min {} s", s / 60, s % 60);
}

std::string apart(double horizontal_m, double vertical_ft) {
  return fmt::format("{:.1f} NM / {:.0f} ft", horizontal_m / units::kMetresPerNauticalMile, vertical_ft);
}

std::string upper(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

/// ntfy's priorities 1 (min) … 5 (max) and tags (emoji short codes), from
/// https://docs.ntfy.sh/publish/ ("Message priority", "Tags & emojis").
int ntfy_priority(const OutboxEntry& e) {
  if (e.latest.state == AlertState::End) return 2;
  return e.highest == Severity::Loss ? 5 : e.highest == Severity::Warning ? 4 : 3;
}
std::string_view ntfy_tag(const OutboxEntry& e) {
  if (e.latest.state == AlertState::End) return "white_check_mark";
  return e.highest == Severity::Loss ? "rotating_light" : e.highest == Severity::Warning ? "warning" : "airplane";
}
/// Gotify's priorities 0 … 10; its Android client rings from 8 (https://gotify.net/docs/msgextras).
int gotify_priority(const OutboxEntry& e) {
  if (e.latest.state == AlertState::End) return 2;
  return e.highest == Severity::Loss ? 10 : e.highest == Severity::Warning ? 8 : 5;
}

/// What a volume is to a reader: "restricted area EDR-114". A kind kewd does not know
/// (a newer server's) still reads as an area.
std::string area_name(const AlertEvent& e) {
  return e.volume_kind.empty() ? fmt::format("area {}", e.volume) : fmt::format("{} area {}", e.volume_kind, e.volume);
}

/// What the alert says about its subject, first line of the text.
std::string situation(const OutboxEntry& entry) {
  const AlertEvent& e = entry.latest;
  const bool area = e.kind == AlertKind::Apw;
  if (e.state == AlertState::End)
    return fmt::format("{} ended ({}) after {}; highest severity {}.\n", area ? "Area warning" : "Alert",
                       to_string(e.end_reason), duration(e.t - e.opened_t), to_string(entry.highest));
  const bool now = e.severity == Severity::Loss || e.t_los_s <= 0;
  if (area)
    return now ? fmt::format("Inside {} now.\n", area_name(e))
               : fmt::format("Enters {} in {}.\n", area_name(e), duration(e.t_los_s));
  if (now) return fmt::format("Separation lost: {} apart now.\n", apart(e.sep_h_m, e.sep_v_ft));
  return fmt::format("Loss of separation predicted in {}; {} apart now.\n", duration(e.t_los_s),
                     apart(e.sep_h_m, e.sep_v_ft));
}

std::string json_text(std::string_view text) {
  std::string out;
  protocol::append_json_string(out, text);
  return out;
}

}  // namespace

std::string message_title(const std::string& title, const OutboxEntry& entry) {
  const AlertEvent& e = entry.latest;
  const std::string what = e.state == AlertState::End ? "ended" : upper(to_string(e.severity));
  if (e.kind == AlertKind::Apw) {
    const std::string kind = e.volume_kind.empty() ? "" : fmt::format(" ({})", e.volume_kind);
    return fmt::format("{}: {} {} → {}{}", title, what, party_name(e.a), e.volume, kind);
  }
  return fmt::format("{}: {} {} / {}", title, what, party_name(e.a), party_name(e.b));
}

std::string message_text(const OutboxEntry& entry) {
  const AlertEvent& e = entry.latest;
  std::string text = situation(entry);
  if (e.state != AlertState::End && e.kind == AlertKind::Stca)
    text += fmt::format("Closest in {}: {}.\n", duration(e.t_cpa_s), apart(e.cpa_h_m, e.cpa_v_ft));
  for (const AlertParty* p : {&e.a, &e.b}) {
    if (p->id.empty()) continue;  // an area warning's b
    const std::string who = p->callsign.empty() ? p->id : fmt::format("{} ({})", p->callsign, p->id);
    text += fmt::format("{} {:.0f} ft, {:.0f} kt, track {:03.0f}.\n", who, p->alt_ft, p->gs_kt, p->trk_deg);
  }
  if (entry.states.size() > 1) {
    text += "Events:";
    for (std::size_t i = 0; i < entry.states.size(); ++i) text += (i ? ", " : " ") + std::string(to_string(entry.states[i]));
    text += ".\n";
  }
  text += fmt::format("Alert {} opened {}", e.number, protocol::utc_time_of_day(e.opened_t));
  if (!e.region.empty()) text += fmt::format(", region {}", e.region);
  text += ".";
  return text;
}

NotifyMessage render_message(const NotifyConfig& config, const OutboxEntry& entry, const std::string& token) {
  NotifyMessage m;
  const std::string title = message_title(config.title, entry);
  switch (config.format) {
    case NotifyTemplate::Json:
      // One event per message: the stream's object, newline and all.
      m.body = entry.lines.back();
      m.headers.push_back("Content-Type: application/json");
      break;
    case NotifyTemplate::Ntfy:
      m.body = message_text(entry);
      m.headers.push_back("Content-Type: text/plain; charset=utf-8");
      m.headers.push_back("Title: " + title);
      m.headers.push_back(fmt::format("Priority: {}", ntfy_priority(entry)));
      m.headers.push_back(fmt::format("Tags: {}", ntfy_tag(entry)));
      break;
    case NotifyTemplate::Gotify:
      m.body = fmt::format("{{\"title\":{},\"message\":{},\"priority\":{}}}", json_text(title),
                           json_text(message_text(entry)), gotify_priority(entry));
      m.headers.push_back("Content-Type: application/json");
      break;
    case NotifyTemplate::Slack:
    case NotifyTemplate::Mattermost:
      m.body = fmt::format("{{\"text\":{}}}", json_text("*" + title + "*\n" + message_text(entry)));
      m.headers.push_back("Content-Type: application/json");
      break;
    case NotifyTemplate::Discord:
      m.body = fmt::format("{{\"content\":{}}}", json_text("**" + title + "**\n" + message_text(entry)));
      m.headers.push_back("Content-Type: application/json");
      break;
  }
  if (!token.empty()) {
    if (config.format == NotifyTemplate::Gotify) m.headers.push_back("X-Gotify-Key: " + token);
    else m.headers.push_back("Authorization: Bearer " + token);
  }
  m.headers.push_back(fmt::format("Kew-Seq: {}", entry.seqs.back()));
  m.headers.push_back("Kew-Alert: " + entry.latest.id);
  for (const std::string& header : config.headers) m.headers.push_back(header);
  return m;
}

}  // namespace kew::daemon
