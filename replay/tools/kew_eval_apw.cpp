// kew-eval's area proximity warnings: the tables, list lines and JSON of kew_eval_apw.hpp.

#include "kew_eval_apw.hpp"

#include <algorithm>
#include <set>

#include "kew/util/units.hpp"
#include "kew_eval_format.hpp"

namespace kew::replay::tools {

namespace {

using volume::VolumeKind;

// The figures of `kind` in a run; empty when the run has no APW or not that kind.
const AreaFigures* figures_of(const AreaRun* run, VolumeKind kind) {
  if (!run || !run->truth) return nullptr;
  const auto it = run->evaluation.by_kind.find(kind);
  return it == run->evaluation.by_kind.end() ? nullptr : &it->second;
}

std::string band_text(volume::VerticalBand band) {
  return fmt::format("{}–{} ft", fixed(band.floor_ft, 0), fixed(band.ceiling_ft, 0));
}

// "NAME (circle 2.00 NM, 0–3000 ft, look-ahead 120 s, warning 60 s)"
std::string volume_text(const volume::WatchedVolume& w) {
  std::string shape;
  if (!w.area)
    shape = fmt::format("{} NM around {}, {} relative", fixed(w.follow_radius_m / units::kMetresPerNauticalMile, 2),
                        w.follow, band_text(w.follow_band));
  else if (w.area->is_circle())
    shape = fmt::format("circle {} NM, {}", fixed(w.area->extent_m() / units::kMetresPerNauticalMile, 2),
                        band_text(w.area->band()));
  else
    shape = fmt::format("polygon of {} vertices, {}", w.area->rings().front().size(), band_text(w.area->band()));
  return fmt::format("{} ({}, look-ahead {} s, warning {} s)", w.name, shape, fixed(w.lookahead_s, 0),
                     fixed(w.warning_s, 0));
}

std::string alert_volume(const AlertSpan& a) { return fmt::format("{} ({})", a.volume, a.volume_kind); }

std::string entry_volume(const AreaTruth& truth, const AreaEntry& e) {
  const volume::WatchedVolume& w = truth.volumes()[e.volume];
  return fmt::format("{} ({})", w.name, volume::kVolumeKindNames.name(w.kind));
}

std::string figures_json(const AreaFigures& f) {
  std::string out;
  JsonObject o(out);
  o.count("volumes", f.volumes).count("alerts", f.alerts);
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
  o.count("entries", f.entries).count("detected", f.detected).count("missed", f.missed);
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
  o.close();
  return out;
}

}  // namespace

std::string area_table(const std::vector<std::pair<std::string, const AreaRun*>>& columns) {
  struct Row {
    std::string label;
    std::vector<std::string> cells;
  };
  std::string out;
  for (const auto& [kind, kind_name] : volume::kVolumeKindNames.entries()) {
    bool shown = false;
    for (const auto& column : columns) shown = shown || figures_of(column.second, kind);
    if (!shown) continue;
    // The volumes of this kind, as the first column that has APW knows them.
    std::vector<std::string> volumes;
    for (const auto& column : columns) {
      if (!column.second || !column.second->truth) continue;
      for (const volume::WatchedVolume& w : column.second->truth->volumes())
        if (w.kind == kind) volumes.push_back(volume_text(w));
      break;
    }
    out += fmt::format("\narea proximity warnings, {} volumes\n", kind_name);
    for (const std::string& v : volumes) out += fmt::format("  {:<14}{}\n", "volume", v);
    out += '\n';

    std::vector<Row> rows;
    const auto add = [&](std::string label, auto cell) {
      Row row{std::move(label), {}};
      for (const auto& column : columns) {
        const AreaFigures* f = figures_of(column.second, kind);
        row.cells.push_back(f ? cell(*f) : std::string("-"));
      }
      rows.push_back(std::move(row));
    };
    const auto count = [](std::size_t AreaFigures::*field) {
      return [field](const AreaFigures& f) { return std::to_string(f.*field); };
    };
    add("alerts", count(&AreaFigures::alerts));
    add("hit", count(&AreaFigures::hits));
    add("close call", count(&AreaFigures::close_calls));
    add("nuisance", count(&AreaFigures::nuisances));
    add("ineligible", count(&AreaFigures::ineligible));
    add("  one aircraft", count(&AreaFigures::ineligible_one_aircraft));
    add("  not airborne", count(&AreaFigures::ineligible_not_airborne));
    add("  no truth", count(&AreaFigures::ineligible_no_truth));
    add("undesirable", [](const AreaFigures& f) {
      return f.undesirable_share ? fixed(100.0 * *f.undesirable_share, 1) + " %" : std::string("n/a");
    });
    add("entries", count(&AreaFigures::entries));
    add("detected", count(&AreaFigures::detected));
    add("missed", count(&AreaFigures::missed));
    add("unwarnable", count(&AreaFigures::unwarnable));
    const auto warning = [](double WarningTimes::*field) {
      return [field](const AreaFigures& f) { return f.warning ? fixed((*f.warning).*field, 1) : std::string("n/a"); };
    };
    add("warning min (s)", warning(&WarningTimes::min));
    add("warning p10 (s)", warning(&WarningTimes::p10));
    add("warning p50 (s)", warning(&WarningTimes::p50));
    add("warning p90 (s)", warning(&WarningTimes::p90));
    add("warning max (s)", warning(&WarningTimes::max));

    std::size_t label_width = 0;
    for (const Row& r : rows) label_width = std::max(label_width, r.label.size());
    std::vector<std::size_t> widths;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      std::size_t w = columns[c].first.size();
      for (const Row& r : rows) w = std::max(w, r.cells[c].size());
      widths.push_back(w);
    }
    out += fmt::format("{:<{}}", "", label_width);
    for (std::size_t c = 0; c < columns.size(); ++c) out += fmt::format("  {:>{}}", columns[c].first, widths[c]);
    out += '\n';
    for (const Row& r : rows) {
      out += fmt::format("{:<{}}", r.label, label_width);
      for (std::size_t c = 0; c < columns.size(); ++c) out += fmt::format("  {:>{}}", r.cells[c], widths[c]);
      out += '\n';
    }
  }
  return out;
}

std::string area_list(const Truth& truth, const std::string& name, const AreaRun& run) {
  std::string out;
  if (!run.truth) return out;
  for (std::size_t i = 0; i < run.alerts.size(); ++i) {
    const AlertSpan& a = run.alerts[i];
    const ScoredAreaAlert& s = run.evaluation.alerts[i];
    out += fmt::format("[{}] apw alert {} {} opened {} {} {} in {} max {}", name, a.id,
                       class_name(ScoredAlert{s.cls, s.reason, std::nullopt}), utc(a.opened_t, true),
                       a.ended_t ? "ended " + utc(*a.ended_t, true) : std::string("active at end"),
                       party(a.a_source, a.a_id, a.a_callsign), alert_volume(a), kew::to_string(a.max_severity));
    if (s.entry_s) out += " entry " + utc(static_cast<double>(*s.entry_s), false);
    out += '\n';
  }
  const std::vector<AreaEntry>& entries = run.truth->entries();
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const AreaEntry& e = entries[k];
    const ScoredAreaEntry& s = run.evaluation.entries[k];
    out += fmt::format("[{}] apw entry {} to {} {} {} in {} inside {} s eligible for {} s", name,
                       utc(static_cast<double>(e.start_s), false), utc(static_cast<double>(e.end_s), false),
                       kLossOutcomeNames.name(s.outcome), track_party(truth, e.track), entry_volume(*run.truth, e),
                       e.inside_seconds, s.eligible_for_s);
    if (s.alert) out += fmt::format(" warning {} s alert {}", fixed(*s.warning_s, 3), run.alerts[*s.alert].id);
    out += '\n';
  }
  return out;
}

std::string area_json(const Truth& truth, const AreaRun& run, bool list) {
  std::string out;
  JsonObject o(out);
  std::string volumes = "[";
  for (std::size_t v = 0; v < run.truth->volumes().size(); ++v) {
    const volume::WatchedVolume& w = run.truth->volumes()[v];
    std::string one;
    JsonObject(one)
        .text("name", w.name)
        .text("kind", volume::kVolumeKindNames.name(w.kind))
        .raw("follow", w.area ? "null" : json_string(w.follow))
        .number("lookahead_s", w.lookahead_s, 3)
        .number("warning_s", w.warning_s, 3)
        .close();
    volumes += (v ? "," : "") + one;
  }
  o.raw("volumes", volumes + "]");
  std::string kinds = "{";
  bool first = true;
  for (const auto& [kind, f] : run.evaluation.by_kind) {
    kinds += (first ? "" : ",") + json_string(volume::kVolumeKindNames.name(kind)) + ":" + figures_json(f);
    first = false;
  }
  o.raw("kinds", kinds + "}");
  if (list) {
    std::string alerts = "[";
    for (std::size_t i = 0; i < run.alerts.size(); ++i) {
      const AlertSpan& a = run.alerts[i];
      const ScoredAreaAlert& s = run.evaluation.alerts[i];
      std::string one;
      JsonObject a_json(one);
      a_json.text("id", a.id).text("class", kAlertClassNames.name(s.cls));
      if (s.reason == IneligibleReason::None)
        a_json.raw("reason", "null");
      else
        a_json.text("reason", kIneligibleReasonNames.name(s.reason));
      a_json.text("volume", a.volume).text("volume_kind", a.volume_kind);
      a_json.number("t_open", a.opened_t, 3).text("opened", utc(a.opened_t, true));
      if (a.ended_t)
        a_json.number("t_end", *a.ended_t, 3).text("ended", utc(*a.ended_t, true));
      else
        a_json.raw("t_end", "null").raw("ended", "null");
      a_json.raw("a", json_party(a.a_source, a.a_id, a.a_callsign));
      a_json.text("max_severity", kew::to_string(a.max_severity));
      a_json.raw("entry_t", s.entry_s ? std::to_string(*s.entry_s) : "null");
      a_json.close();
      alerts += (i ? "," : "") + one;
    }
    o.raw("alert_list", alerts + "]");
    std::string entries = "[";
    for (std::size_t k = 0; k < run.truth->entries().size(); ++k) {
      const AreaEntry& e = run.truth->entries()[k];
      const ScoredAreaEntry& s = run.evaluation.entries[k];
      const TruthTrack& t = truth.track(e.track);
      std::string one;
      JsonObject(one)
          .text("volume", run.truth->volumes()[e.volume].name)
          .raw("start_t", std::to_string(e.start_s))
          .text("start", utc(static_cast<double>(e.start_s), false))
          .raw("end_t", std::to_string(e.end_s))
          .raw("inside_seconds", std::to_string(e.inside_seconds))
          .text("outcome", kLossOutcomeNames.name(s.outcome))
          .raw("a", json_party(t.source, t.id, t.callsign))
          .raw("eligible_for_s", std::to_string(s.eligible_for_s))
          .raw("warning_s", s.warning_s ? fixed(*s.warning_s, 3) : "null")
          .raw("alert", s.alert ? json_string(run.alerts[*s.alert].id) : "null")
          .close();
      entries += (k ? "," : "") + one;
    }
    o.raw("entry_list", entries + "]");
  }
  o.close();
  return out;
}

}  // namespace kew::replay::tools
