// The figures pair alerts and area proximity warnings share, in kew-eval's table and JSON
// (kew_eval_format.hpp).

#include "kew_eval_format.hpp"

#include <algorithm>

namespace kew::replay::tools {

using kew::replay::ScoreFigures;

void json_class(JsonObject& o, kew::replay::AlertClass cls, kew::replay::IneligibleReason reason) {
  o.text("class", kew::replay::kAlertClassNames.name(cls));
  if (reason == kew::replay::IneligibleReason::None)
    o.raw("reason", "null");
  else
    o.text("reason", kew::replay::kIneligibleReasonNames.name(reason));
}

void json_span_times(JsonObject& o, const kew::replay::AlertSpan& a) {
  o.number("t_open", a.opened_t, 3).text("opened", utc(a.opened_t, true));
  if (a.ended_t)
    o.number("t_end", *a.ended_t, 3).text("ended", utc(*a.ended_t, true));
  else
    o.raw("t_end", "null").raw("ended", "null");
}

void json_event_score(JsonObject& o, const kew::replay::ScoredEvent& s,
                      const std::vector<kew::replay::AlertSpan>& alerts) {
  o.raw("eligible_for_s", std::to_string(s.eligible_for_s));
  o.raw("warning_s", s.warning_s ? fixed(*s.warning_s, 3) : "null");
  o.raw("alert", s.alert ? json_string(alerts[*s.alert].id) : "null");
}

std::string event_warning_text(const kew::replay::ScoredEvent& s, const std::vector<kew::replay::AlertSpan>& alerts) {
  if (!s.alert) return "";
  return fmt::format(" warning {} s alert {}", fixed(*s.warning_s, 3), alerts[*s.alert].id);
}

void json_classes(JsonObject& o, const ScoreFigures& f) {
  o.count("hit", f.hits).count("close_call", f.close_calls).count("nuisance", f.nuisances);
  o.count("ineligible", f.ineligible);
  std::string reasons;
  JsonObject(reasons)
      .count("one_aircraft", f.ineligible_one_aircraft)
      .count("not_airborne", f.ineligible_not_airborne)
      .count("no_truth", f.ineligible_no_truth)
      .close();
  o.raw("ineligible_reasons", reasons);
  o.number_or_na("undesirable_share", f.undesirable_share, 4);
}

void json_outcomes(JsonObject& o, const ScoreFigures& f) {
  o.count("detected", f.detected).count("missed", f.missed);
  o.count("unwarnable", f.unwarnable);
  if (f.warning) {
    std::string warning;
    JsonObject(warning)
        .number("min", f.warning->min, 3)
        .number("p10", f.warning->p10, 3)
        .number("p50", f.warning->p50, 3)
        .number("p90", f.warning->p90, 3)
        .number("max", f.warning->max, 3)
        .close();
    o.raw("warning_s", warning);
  } else {
    o.raw("warning_s", "\"n/a\"");
  }
}

namespace {

auto count(std::size_t ScoreFigures::*field) {
  return [field](const ScoreFigures& f) { return std::to_string(f.*field); };
}

}  // namespace

void add_class_rows(std::vector<Row>& rows, const ScoreColumns& columns) {
  add_row(rows, "hit", columns, count(&ScoreFigures::hits));
  add_row(rows, "close call", columns, count(&ScoreFigures::close_calls));
  add_row(rows, "nuisance", columns, count(&ScoreFigures::nuisances));
  add_row(rows, "ineligible", columns, count(&ScoreFigures::ineligible));
  add_row(rows, "  one aircraft", columns, count(&ScoreFigures::ineligible_one_aircraft));
  add_row(rows, "  not airborne", columns, count(&ScoreFigures::ineligible_not_airborne));
  add_row(rows, "  no truth", columns, count(&ScoreFigures::ineligible_no_truth));
  add_row(rows, "undesirable", columns, [](const ScoreFigures& f) {
    return f.undesirable_share ? fixed(100.0 * *f.undesirable_share, 1) + " %" : std::string("n/a");
  });
}

void add_outcome_rows(std::vector<Row>& rows, const ScoreColumns& columns) {
  add_row(rows, "detected", columns, count(&ScoreFigures::detected));
  add_row(rows, "missed", columns, count(&ScoreFigures::missed));
  add_row(rows, "unwarnable", columns, count(&ScoreFigures::unwarnable));
  const auto warning = [](double kew::replay::WarningTimes::*field) {
    return [field](const ScoreFigures& f) { return f.warning ? fixed((*f.warning).*field, 1) : std::string("n/a"); };
  };
  add_row(rows, "warning min (s)", columns, warning(&kew::replay::WarningTimes::min));
  add_row(rows, "warning p10 (s)", columns, warning(&kew::replay::WarningTimes::p10));
  add_row(rows, "warning p50 (s)", columns, warning(&kew::replay::WarningTimes::p50));
  add_row(rows, "warning p90 (s)", columns, warning(&kew::replay::WarningTimes::p90));
  add_row(rows, "warning max (s)", columns, warning(&kew::replay::WarningTimes::max));
}

std::string table_text(const std::vector<std::string>& names, const std::vector<Row>& rows) {
  std::size_t label_width = 0;
  for (const Row& r : rows) label_width = std::max(label_width, r.label.size());
  std::vector<std::size_t> widths;
  for (std::size_t c = 0; c < names.size(); ++c) {
    std::size_t w = names[c].size();
    for (const Row& r : rows) w = std::max(w, r.cells[c].size());
    widths.push_back(w);
  }
  std::string out = fmt::format("{:<{}}", "", label_width);
  for (std::size_t c = 0; c < names.size(); ++c) out += fmt::format("  {:>{}}", names[c], widths[c]);
  out += '\n';
  for (const Row& r : rows) {
    out += fmt::format("{:<{}}", r.label, label_width);
    for (std::size_t c = 0; c < names.size(); ++c) out += fmt::format("  {:>{}}", r.cells[c], widths[c]);
    out += '\n';
  }
  return out;
}

}  // namespace kew::replay::tools
