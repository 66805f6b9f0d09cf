// kew-eval's area proximity warnings: the tables, list lines and JSON of kew_eval_apw.hpp.

#include "kew_eval_apw.hpp"

#include <algorithm>

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
  json_classes(o, f);
  o.count("entries", f.entries);
  json_outcomes(o, f);
  o.close();
  return out;
}

}  // namespace

std::string area_table(const std::vector<std::pair<std::string, const AreaRun*>>& columns) {
  std::string out;
  for (const auto& [kind, kind_name] : volume::kVolumeKindNames.entries()) {
    std::vector<std::string> names;
    std::vector<const AreaFigures*> figures;
    for (const auto& column : columns) {
      names.push_back(column.first);
      figures.push_back(figures_of(column.second, kind));
    }
    if (std::none_of(figures.begin(), figures.end(), [](const AreaFigures* f) { return f != nullptr; })) continue;
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

    const ScoreColumns scores(figures.begin(), figures.end());
    std::vector<Row> rows;
    add_row(rows, "alerts", figures, [](const AreaFigures& f) { return std::to_string(f.alerts); });
    add_class_rows(rows, scores);
    add_row(rows, "entries", figures, [](const AreaFigures& f) { return std::to_string(f.entries); });
    add_outcome_rows(rows, scores);
    out += table_text(names, rows);
  }
  return out;
}

std::string area_list(const Truth& truth, const std::string& name, const AreaRun& run) {
  std::string out;
  if (!run.truth) return out;
  for (std::size_t i = 0; i < run.alerts.size(); ++i) {
    const AlertSpan& a = run.alerts[i];
    const ScoredAreaAlert& s = run.evaluation.alerts[i];
    out += fmt::format("[{}] apw alert {} {} opened {} {} {} in {} max {}", name, a.id, class_name(s.cls, s.reason),
                       utc(a.opened_t, true), ended_text(a), party(a.a_source, a.a_id, a.a_callsign), alert_volume(a),
                       kew::to_string(a.max_severity));
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
    out += event_warning_text(s, run.alerts);
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
      a_json.text("id", a.id);
      json_class(a_json, s.cls, s.reason);
      a_json.text("volume", a.volume).text("volume_kind", a.volume_kind);
      json_span_times(a_json, a);
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
      JsonObject e_json(one);
      e_json.text("volume", run.truth->volumes()[e.volume].name)
          .raw("start_t", std::to_string(e.start_s))
          .text("start", utc(static_cast<double>(e.start_s), false))
          .raw("end_t", std::to_string(e.end_s))
          .raw("inside_seconds", std::to_string(e.inside_seconds))
          .text("outcome", kLossOutcomeNames.name(s.outcome))
          .raw("a", json_party(t.source, t.id, t.callsign));
      json_event_score(e_json, s, run.alerts);
      e_json.close();
      entries += (k ? "," : "") + one;
    }
    o.raw("entry_list", entries + "]");
  }
  o.close();
  return out;
}

}  // namespace kew::replay::tools
