#pragma once
// kew-eval's text and JSON formatting (replay/tools/kew_eval.cpp, kew_eval_apw.cpp): fixed
// decimals, UTC times, parties, class names, and JSON objects written member by member in
// call order, so that the same input gives the same bytes; and the figures that pair
// alerts and area proximity warnings share (kew_eval_format.cpp), written once for both.

#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "kew/alert/alert_event.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/replay/evaluation.hpp"
#include "kew/replay/truth.hpp"

namespace kew::replay::tools {

using kew::replay::Truth;

/// Fixed decimals, never "-0".
inline std::string fixed(double value, int decimals) {
  std::string s = fmt::format("{:.{}f}", value, decimals);
  if (s.front() == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

/// UTC ISO-8601 of a data time (UTC s), with milliseconds when `millis`.
inline std::string utc(double t, bool millis) {
  if (!std::isfinite(t)) return "null";
  double whole = std::floor(t);
  long ms = millis ? std::lround((t - whole) * 1000.0) : 0;
  if (ms == 1000) {
    whole += 1.0;
    ms = 0;
  }
  using namespace std::chrono;
  const sys_seconds s{seconds{static_cast<long long>(whole)}};
  const sys_days day = floor<days>(s);
  const year_month_day ymd{day};
  const hh_mm_ss<seconds> hms{s - day};
  std::string out = fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", static_cast<int>(ymd.year()),
                                static_cast<unsigned>(ymd.month()), static_cast<unsigned>(ymd.day()),
                                hms.hours().count(), hms.minutes().count(), hms.seconds().count());
  if (millis) out += fmt::format(".{:03}", ms);
  return out + "Z";
}

inline std::string party(const std::string& source, const std::string& id, const std::string& callsign) {
  std::string out = source.empty() ? id : source + ":" + id;
  if (!callsign.empty()) out += " (" + callsign + ")";
  return out;
}

inline std::string track_party(const Truth& truth, kew::replay::TruthTrackId t) {
  const kew::replay::TruthTrack& track = truth.track(t);
  return party(track.source, track.id, track.callsign);
}

inline std::string class_name(kew::replay::AlertClass cls, kew::replay::IneligibleReason reason) {
  std::string out(kew::replay::kAlertClassNames.name(cls));
  if (reason != kew::replay::IneligibleReason::None)
    out += "/" + std::string(kew::replay::kIneligibleReasonNames.name(reason));
  return out;
}

/// "ended <UTC>", or "active at end".
inline std::string ended_text(const kew::replay::AlertSpan& a) {
  return a.ended_t ? "ended " + utc(*a.ended_t, true) : std::string("active at end");
}

inline std::string json_string(std::string_view text) {
  std::string out;
  kew::protocol::append_json_string(out, text);
  return out;
}

template <class T>
inline std::string number_or_na(const std::optional<T>& value, int decimals, bool json) {
  if (!value) return json ? "\"n/a\"" : "n/a";
  return fixed(*value, decimals);
}

/// Appends one JSON object member by member, in call order (so the bytes are fixed).
class JsonObject {
 public:
  explicit JsonObject(std::string& out) : out_(out) { out_ += '{'; }
  /// `json` must already be a JSON value.
  JsonObject& raw(std::string_view key, std::string_view json) {
    if (!first_) out_ += ',';
    first_ = false;
    out_ += '"';
    out_ += key;
    out_ += "\":";
    out_ += json;
    return *this;
  }
  JsonObject& text(std::string_view key, std::string_view value) { return raw(key, json_string(value)); }
  JsonObject& count(std::string_view key, std::uint64_t value) { return raw(key, std::to_string(value)); }
  JsonObject& number(std::string_view key, double value, int decimals) { return raw(key, fixed(value, decimals)); }
  /// A number, or the string "n/a" when empty.
  JsonObject& number_or_na(std::string_view key, const std::optional<double>& value, int decimals) {
    return raw(key, tools::number_or_na(value, decimals, true));
  }
  JsonObject& count_or_null(std::string_view key, const std::optional<std::uint64_t>& value) {
    return raw(key, value ? std::to_string(*value) : "null");
  }
  void close() { out_ += '}'; }

 private:
  std::string& out_;
  bool first_ = true;
};

inline std::string json_party(const std::string& source, const std::string& id, const std::string& callsign) {
  std::string out;
  JsonObject(out).text("src", source).text("id", id).text("cs", callsign).close();
  return out;
}

/// "class", and "reason" (null unless ineligible).
void json_class(JsonObject& o, kew::replay::AlertClass cls, kew::replay::IneligibleReason reason);
/// "t_open", "opened", "t_end" and "ended" (null while active at the end).
void json_span_times(JsonObject& o, const kew::replay::AlertSpan& a);
/// An event's "eligible_for_s", "warning_s" and "alert" (`alerts`: those it was scored
/// against).
void json_event_score(JsonObject& o, const kew::replay::ScoredEvent& s,
                      const std::vector<kew::replay::AlertSpan>& alerts);
/// A list line's " warning <s> s alert <id>" of a detected or covered event; "" otherwise.
std::string event_warning_text(const kew::replay::ScoredEvent& s, const std::vector<kew::replay::AlertSpan>& alerts);

/// From "hit" to "undesirable_share": the alert classes.
void json_classes(JsonObject& o, const kew::replay::ScoreFigures& f);
/// From "detected" to "warning_s": the events' outcomes and warning times.
void json_outcomes(JsonObject& o, const kew::replay::ScoreFigures& f);

/// A row of a table: its label, then a cell per column.
struct Row {
  std::string label;
  std::vector<std::string> cells;
};
/// The figures of each column of a table; null where a column has none (its cells read
/// "-").
using ScoreColumns = std::vector<const kew::replay::ScoreFigures*>;

/// A row of `cell(figures)` for each column of `columns` (null: "-").
template <class Figures, class Cell>
void add_row(std::vector<Row>& rows, std::string label, const std::vector<const Figures*>& columns, Cell cell) {
  Row row{std::move(label), {}};
  for (const Figures* f : columns) row.cells.push_back(f ? cell(*f) : std::string("-"));
  rows.push_back(std::move(row));
}
/// From "hit" to "undesirable": the alert classes.
void add_class_rows(std::vector<Row>& rows, const ScoreColumns& columns);
/// From "detected" to "warning max (s)": the events' outcomes and warning times.
void add_outcome_rows(std::vector<Row>& rows, const ScoreColumns& columns);

/// The header line of the column names, then the rows: labels left-aligned, cells
/// right-aligned, each column as wide as its widest cell or name.
std::string table_text(const std::vector<std::string>& names, const std::vector<Row>& rows);

}  // namespace kew::replay::tools
