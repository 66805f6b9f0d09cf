// kew-eval (design §2.6, §5.6): runs the pipeline over recordings as kew-replay does,
// once per configuration, or reads alert logs, and scores every alert in hindsight
// against the truth of the recording itself (kew/replay/truth.hpp, evaluation.hpp).
// Prints a table with one column per configuration or log, --json, or --list.
// The rules are in replay/README.md ("kew-eval").

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "kew/config/shared_config.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/protocol/version.hpp"
#include "kew/replay/area_evaluation.hpp"
#include "kew/replay/area_truth.hpp"
#include "kew/replay/evaluation.hpp"
#include "kew/replay/explanation.hpp"
#include "kew/replay/recording_reader.hpp"
#include "kew/replay/state_based.hpp"
#include "kew/replay/truth.hpp"
#include "kew_eval_apw.hpp"
#include "kew_eval_format.hpp"
#include "tool_config.hpp"

namespace {

using namespace kew::replay::tools;  // formatting (kew_eval_format.hpp) and the APW output
using kew::replay::AlertSpan;
using kew::replay::Evaluation;
using kew::replay::EvaluationFigures;
using kew::replay::Truth;

using kew::replay::tools::kUsageError;
constexpr int kInputError = 1;   // an alert log cannot be read

struct Options {
  std::string format = "auto";
  std::vector<std::string> config_paths;
  std::vector<std::string> alert_paths;
  std::vector<std::string> baselines;
  bool sort = false;
  bool json = false;
  bool list = false;
  bool explain = false;
  double late_s = kew::replay::explanation_rules::kLateWarning_s;
  double h_nm = 5.0;
  double v_ft = 1000.0;
  std::vector<std::string> files;
};

/// One column of the output: a pipeline run with one configuration, or an alert log.
struct Column {
  std::string name;
  bool from_log = false;
  std::string baseline;  // "statebased" or "raw"; empty: a configuration or a log
  std::string path;  // the configuration or log; empty for the default configuration
  kew::replay::ScoringParameters parameters;
  std::optional<std::uint64_t> records;            // records given to the pipeline
  std::optional<std::uint64_t> pipeline_rejected;  // of those, refused by the pipeline
  std::vector<AlertSpan> alerts;  // the pair alerts
  Evaluation evaluation;
  AreaRun area;  // the area proximity warnings: their alerts, truth and scores
  std::vector<kew::replay::LossExplanation> explanations;  // --explain, configuration runs
};

/// The records of every file, merged in time order as kew-replay merges them, then with
/// `sort` stable-sorted by time as kew-replay --sort does.
std::vector<kew::TrackReport> read_records(const Options& options, const kew::protocol::DecoderOptions& decoding,
                                           bool report, std::uint64_t& rejected) {
  const kew::protocol::Format format = *kew::protocol::kFormatNames.parse(options.format);
  kew::replay::MergedRecordings recordings;
  for (const std::string& file : options.files) {
    auto reader = std::make_unique<kew::replay::RecordingReader>(file, format, decoding);
    if (report)
      reader->rejections().set_reporter([file](std::string_view reason, std::string_view message) {
        std::fprintf(stderr, "kew-eval: %s: rejected (%.*s) %.*s\n", file.c_str(), static_cast<int>(reason.size()),
                     reason.data(), static_cast<int>(message.size()), message.data());
      });
    recordings.add(std::move(reader));
  }
  std::vector<kew::TrackReport> records;
  kew::TrackReport report_buffer;
  while (recordings.next(report_buffer)) records.push_back(report_buffer);
  if (options.sort)
    std::stable_sort(records.begin(), records.end(),
                     [](const kew::TrackReport& a, const kew::TrackReport& b) { return a.t < b.t; });
  rejected = recordings.rejections().total();
  return records;
}

/// Runs one pipeline over `records` in their order, as kew-replay does offline (no End
/// events for alerts still active at the end), and collects its alerts.
void run_pipeline(const kew::config::SharedConfig& config, const std::vector<kew::TrackReport>& records,
                  Column& column) {
  kew::Pipeline pipeline(config.pipeline);
  kew::replay::AlertCollector collector;
  pipeline.set_alert_sink([&](const kew::AlertEvent& e) { collector.add(e); });
  for (const kew::TrackReport& r : records) pipeline.process(r);
  pipeline.end_of_input();
  column.records = pipeline.statistics().records;
  column.pipeline_rejected = pipeline.rejections().total();
  column.alerts = kew::replay::alerts_of_kind(collector.alerts(), kew::AlertKind::Stca);
  column.area.alerts = kew::replay::alerts_of_kind(collector.alerts(), kew::AlertKind::Apw);
}

/// kew with every eligibility rule of design §4.5 off (--baseline raw): the one-address
/// rule stays, for it is identity, not a filter.
kew::config::SharedConfig without_eligibility(kew::config::SharedConfig config) {
  kew::eligibility::EligibilityConfig& e = config.pipeline.eligibility;
  const double infinity = std::numeric_limits<double>::infinity();
  e.min_ground_speed_kt = 0.0;
  e.min_altitude_ft = -infinity;
  e.max_altitude_ft = infinity;
  e.lower_limit_ft = 0.0;
  e.aerodrome_height_ft = 0.0;
  e.excluded_mode3a.clear();
  e.exclude_coasting = false;
  e.max_position_age_s = infinity;
  e.min_records = 1;
  e.level_rate_fpm = 0.0;
  e.adjacent_level_off = false;
  e.same_code_distance_nm = 0.0;
  return config;
}

/// Reads the ALERT lines of an alert log (kew-replay's output, kewd's alert log); other
/// objects (VERSION, ACK) are skipped. False, with `error`, when the file cannot be read
/// or a line is not a stream object.
bool read_alert_log(const std::string& path, Column& column, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot read " + path;
    return false;
  }
  kew::protocol::AlertStreamReader reader;
  kew::replay::AlertCollector collector;
  std::string line;
  for (std::uint64_t number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line == "\r") continue;
    if (!reader.read(line)) {
      error = fmt::format("{} line {}: {}", path, number, reader.error());
      return false;
    }
    if (reader.object_class() != kew::protocol::StreamObjectClass::Alert) continue;
    kew::AlertEvent event = reader.alert();
    // t_open is optional in the stream; without it a New event opened the alert.
    if (event.state == kew::AlertState::New && event.opened_t == 0.0) event.opened_t = event.t;
    collector.add(event);
  }
  column.alerts = kew::replay::alerts_of_kind(collector.alerts(), kew::AlertKind::Stca);
  column.area.alerts = kew::replay::alerts_of_kind(collector.alerts(), kew::AlertKind::Apw);
  return true;
}

// --- the table ----------------------------------------------------------------------

std::vector<Row> figure_rows(const std::vector<Column>& columns) {
  std::vector<Row> rows;
  const auto add = [&](std::string label, auto cell) {
    Row row{std::move(label), {}};
    for (const Column& c : columns) row.cells.push_back(cell(c));
    rows.push_back(std::move(row));
  };
  const auto optional_count = [](const std::optional<std::uint64_t>& n) {
    return n ? std::to_string(*n) : std::string("-");
  };
  add("look-ahead T (s)", [](const Column& c) { return fixed(c.parameters.lookahead_s, 0); });
  add("confirm", [](const Column& c) { return std::to_string(c.parameters.confirm); });
  add("records run", [&](const Column& c) { return optional_count(c.records); });
  add("  refused by pipeline", [&](const Column& c) { return optional_count(c.pipeline_rejected); });
  std::vector<const EvaluationFigures*> figures;
  for (const Column& c : columns) figures.push_back(&c.evaluation.figures);
  const ScoreColumns scores(figures.begin(), figures.end());
  add_row(rows, "flight hours", figures, [](const EvaluationFigures& f) { return fixed(f.flight_hours, 2); });
  add_row(rows, "alerts", figures, [](const EvaluationFigures& f) { return std::to_string(f.alerts); });
  add_row(rows, "alerts / 100 flight h", figures,
          [](const EvaluationFigures& f) { return number_or_na(f.alerts_per_100_flight_hours, 1, false); });
  add_class_rows(rows, scores);
  add_row(rows, "loss events", figures, [](const EvaluationFigures& f) { return std::to_string(f.loss_events); });
  add_outcome_rows(rows, scores);
  return rows;
}

void print_table(const Options& options, const Truth& truth, const std::vector<Column>& columns) {
  const kew::replay::TruthFigures& t = truth.figures();
  const kew::replay::SeparationStandard& standard = truth.standard();
  std::string out = "truth\n";
  for (const std::string& file : options.files) out += fmt::format("  {:<14}{}\n", "recording", file);
  out += fmt::format("  {:<14}{} ({} refused)\n", "records", t.records, t.records_refused);
  out += fmt::format("  {:<14}{} tracks, {} aircraft ({} merged by address, {} by proximity)\n", "tracks", t.tracks,
                     t.aircraft, t.merged_by_address, t.merged_by_proximity);
  out += fmt::format("  {:<14}{}\n", "flight hours", fixed(t.flight_hours(), 2));
  out += fmt::format("  {:<14}below {} NM and {} ft (S_v {} ft less the altimetry tolerance)\n", "loss",
                     fixed(standard.horizontal_m / kew::replay::truth_rules::kNauticalMile_m, 2),
                     fixed(standard.vertical_loss_ft(), 0), fixed(standard.vertical_ft, 0));
  out += fmt::format("  {:<14}{}\n\n", "loss events", truth.loss_events().size());

  std::vector<std::string> names;
  for (const Column& c : columns) names.push_back(c.name);
  out += table_text(names, figure_rows(columns));
  std::fwrite(out.data(), 1, out.size(), stdout);
}

// --- the list -----------------------------------------------------------------------

void print_list(const Truth& truth, const std::vector<Column>& columns) {
  std::string out;
  for (const Column& c : columns) {
    for (std::size_t i = 0; i < c.alerts.size(); ++i) {
      const AlertSpan& a = c.alerts[i];
      const kew::replay::ScoredAlert& s = c.evaluation.alerts[i];
      out += fmt::format("[{}] alert {} {} opened {} {} {} x {} max {}", c.name, a.id, class_name(s.cls, s.reason),
                         utc(a.opened_t, true), ended_text(a), party(a.a_source, a.a_id, a.a_callsign),
                         party(a.b_source, a.b_id, a.b_callsign), kew::to_string(a.max_severity));
      if (s.loss_s) out += " loss " + utc(static_cast<double>(*s.loss_s), false);
      out += '\n';
    }
    const auto& losses = truth.loss_events();
    for (std::size_t k = 0; k < losses.size(); ++k) {
      const kew::replay::LossEvent& l = losses[k];
      const kew::replay::ScoredLoss& s = c.evaluation.losses[k];
      out += fmt::format("[{}] loss {} to {} {} {} x {} min {} NM {} ft eligible for {} s", c.name,
                         utc(static_cast<double>(l.start_s), false), utc(static_cast<double>(l.end_s), false),
                         kew::replay::kLossOutcomeNames.name(s.outcome), track_party(truth, l.track_a),
                         track_party(truth, l.track_b),
                         fixed(l.min_horizontal_m / kew::replay::truth_rules::kNauticalMile_m, 2),
                         fixed(l.vertical_at_min_ft, 0), s.eligible_for_s);
      out += event_warning_text(s, c.alerts);
      out += '\n';
    }
    out += area_list(truth, c.name, c.area);
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
}

// --- explanations -------------------------------------------------------------------

std::string loss_heading(const Truth& truth, const Column& c, const kew::replay::LossExplanation& e) {
  const kew::replay::LossEvent& l = truth.loss_events()[e.loss];
  const kew::replay::ScoredLoss& s = c.evaluation.losses[e.loss];
  std::string out = fmt::format("loss {} {} x {} {}", utc(static_cast<double>(l.start_s), false),
                                track_party(truth, l.track_a), track_party(truth, l.track_b),
                                kew::replay::kExplainedOutcomeNames.name(e.outcome));
  if (s.warning_s) out += fmt::format(" (warning {} s)", fixed(*s.warning_s, 0));
  return out;
}

/// Stage → (missed, late, unwarnable) counts.
using Census = std::map<kew::PairStage, std::array<std::size_t, 3>>;

Census census_of(const Column& c) {
  Census census;
  for (const kew::replay::LossExplanation& e : c.explanations) ++census[e.stage][static_cast<std::size_t>(e.outcome)];
  return census;
}

void print_explanations(const Truth& truth, const std::vector<Column>& columns, double late_s) {
  std::string out;
  for (const Column& c : columns) {
    if (c.from_log) continue;
    for (const kew::replay::LossExplanation& e : c.explanations) {
      out += fmt::format("[{}] {}: {}: {}\n", c.name, loss_heading(truth, c, e), kew::replay::kPairStageNames.name(e.stage),
                         e.reason);
      const double start = static_cast<double>(truth.loss_events()[e.loss].start_s);
      for (const kew::replay::StageSpan& span : e.spans) {
        out += fmt::format("    {:+6.0f} .. {:+6.0f} s  {} x{}: {}\n", span.first_t - start, span.last_t - start,
                           kew::replay::kPairStageNames.name(span.stage), span.notes, span.first.detail);
        if (span.notes > 1) out += fmt::format("{:>27}last: {}\n", "", span.last.detail);
      }
    }
    out += fmt::format("[{}] census of {} missed, late (< {} s) and unwarnable losses by stage\n", c.name,
                       c.explanations.size(), fixed(late_s, 0));
    out += fmt::format("    {:<22}{:>8}{:>8}{:>12}\n", "stage", "missed", "late", "unwarnable");
    for (const auto& [stage, counts] : census_of(c))
      out += fmt::format("    {:<22}{:>8}{:>8}{:>12}\n", kew::replay::kPairStageNames.name(stage), counts[0], counts[1],
                         counts[2]);
  }
  std::fwrite(out.data(), 1, out.size(), stdout);
}

// --- JSON ---------------------------------------------------------------------------

std::string json_alert(const AlertSpan& a, const kew::replay::ScoredAlert& s) {
  std::string out;
  JsonObject o(out);
  o.text("id", a.id);
  json_class(o, s.cls, s.reason);
  json_span_times(o, a);
  o.raw("a", json_party(a.a_source, a.a_id, a.a_callsign)).raw("b", json_party(a.b_source, a.b_id, a.b_callsign));
  o.text("max_severity", kew::to_string(a.max_severity));
  o.raw("loss_t", s.loss_s ? std::to_string(*s.loss_s) : "null");
  o.close();
  return out;
}

std::string json_loss(const Truth& truth, const Column& c, const kew::replay::LossEvent& l,
                      const kew::replay::ScoredLoss& s) {
  const kew::replay::TruthTrack& ta = truth.track(l.track_a);
  const kew::replay::TruthTrack& tb = truth.track(l.track_b);
  std::string out;
  JsonObject o(out);
  o.raw("start_t", std::to_string(l.start_s)).text("start", utc(static_cast<double>(l.start_s), false));
  o.raw("end_t", std::to_string(l.end_s)).raw("loss_seconds", std::to_string(l.loss_seconds));
  o.text("outcome", kew::replay::kLossOutcomeNames.name(s.outcome));
  o.raw("a", json_party(ta.source, ta.id, ta.callsign)).raw("b", json_party(tb.source, tb.id, tb.callsign));
  o.number("min_h_m", l.min_horizontal_m, 1).number("v_at_min_ft", l.vertical_at_min_ft, 0);
  json_event_score(o, s, c.alerts);
  o.close();
  return out;
}

std::string json_column(const Truth& truth, const Column& c, bool list, bool explain) {
  const EvaluationFigures& f = c.evaluation.figures;
  std::string out;
  JsonObject o(out);
  o.text("name", c.name).text("kind", !c.baseline.empty() ? "baseline" : c.from_log ? "alerts" : "config");
  if (c.path.empty())
    o.raw("path", "null");
  else
    o.text("path", c.path);
  o.number("lookahead_s", c.parameters.lookahead_s, 3);
  o.count("confirm", static_cast<std::uint64_t>(c.parameters.confirm));
  o.count_or_null("records", c.records).count_or_null("pipeline_rejected", c.pipeline_rejected);
  o.number("flight_hours", f.flight_hours, 3).count("alerts", f.alerts);
  o.number_or_na("alerts_per_100_flight_hours", f.alerts_per_100_flight_hours, 3);
  json_classes(o, f);
  o.count("loss_events", f.loss_events);
  json_outcomes(o, f);
  if (!c.explanations.empty() || (explain && !c.from_log)) {
    std::string list_json = "[";
    for (std::size_t i = 0; i < c.explanations.size(); ++i) {
      const kew::replay::LossExplanation& e = c.explanations[i];
      const kew::replay::LossEvent& l = truth.loss_events()[e.loss];
      std::string spans = "[";
      for (std::size_t k = 0; k < e.spans.size(); ++k) {
        const kew::replay::StageSpan& span = e.spans[k];
        std::string one;
        JsonObject(one)
            .text("stage", kew::replay::kPairStageNames.name(span.stage))
            .number("from_t", span.first_t, 3)
            .number("to_t", span.last_t, 3)
            .count("notes", span.notes)
            .text("first", span.first.detail)
            .text("last", span.last.detail)
            .close();
        spans += (k ? "," : "") + one;
      }
      std::string one;
      JsonObject(one)
          .raw("start_t", std::to_string(l.start_s))
          .text("start", utc(static_cast<double>(l.start_s), false))
          .raw("a", json_party(truth.track(l.track_a).source, truth.track(l.track_a).id, truth.track(l.track_a).callsign))
          .raw("b", json_party(truth.track(l.track_b).source, truth.track(l.track_b).id, truth.track(l.track_b).callsign))
          .text("outcome", kew::replay::kExplainedOutcomeNames.name(e.outcome))
          .raw("warning_s", c.evaluation.losses[e.loss].warning_s ? fixed(*c.evaluation.losses[e.loss].warning_s, 3) : "null")
          .text("stage", kew::replay::kPairStageNames.name(e.stage))
          .text("reason", e.reason)
          .raw("spans", spans + "]")
          .close();
      list_json += (i ? "," : "") + one;
    }
    o.raw("explain", list_json + "]");
    std::string census = "{";
    bool first = true;
    for (const auto& [stage, counts] : census_of(c)) {
      std::string one;
      JsonObject(one).count("missed", counts[0]).count("late", counts[1]).count("unwarnable", counts[2]).close();
      census += (first ? "\"" : ",\"") + std::string(kew::replay::kPairStageNames.name(stage)) + "\":" + one;
      first = false;
    }
    o.raw("census", census + "}");
  }
  if (list) {
    std::string alerts = "[";
    for (std::size_t i = 0; i < c.alerts.size(); ++i)
      alerts += (i ? "," : "") + json_alert(c.alerts[i], c.evaluation.alerts[i]);
    o.raw("alert_list", alerts + "]");
    std::string losses = "[";
    const auto& events = truth.loss_events();
    for (std::size_t k = 0; k < events.size(); ++k)
      losses += (k ? "," : "") + json_loss(truth, c, events[k], c.evaluation.losses[k]);
    o.raw("loss_list", losses + "]");
  }
  if (c.area.truth) o.raw("apw", area_json(truth, c.area, list));
  o.close();
  return out;
}

void print_json(const Options& options, const Truth& truth, const std::vector<Column>& columns) {
  const kew::replay::TruthFigures& t = truth.figures();
  std::string files = "[";
  for (std::size_t i = 0; i < options.files.size(); ++i) files += (i ? "," : "") + json_string(options.files[i]);
  std::string truth_json;
  JsonObject(truth_json)
      .raw("files", files + "]")
      .number("h_nm", options.h_nm, 3)
      .number("v_ft", options.v_ft, 1)
      .count("records", t.records)
      .count("records_refused", t.records_refused)
      .count("tracks", t.tracks)
      .count("aircraft", t.aircraft)
      .count("merged_by_address", t.merged_by_address)
      .count("merged_by_proximity", t.merged_by_proximity)
      .number("flight_hours", t.flight_hours(), 3)
      .count("loss_events", truth.loss_events().size())
      .close();
  std::string runs = "[";
  for (std::size_t c = 0; c < columns.size(); ++c)
    runs += (c ? "," : "") + json_column(truth, columns[c], options.list, options.explain);
  std::string out;
  JsonObject(out).raw("truth", truth_json).raw("runs", runs + "]").close();
  out += '\n';
  std::fwrite(out.data(), 1, out.size(), stdout);
}

/// Column names: the configuration's file stem or the log's file name ("default" for
/// the built-in configuration); a name taken twice becomes the path as given.
void name_columns(std::vector<Column>& columns) {
  for (Column& c : columns) {
    if (!c.baseline.empty())
      c.name = c.baseline;
    else if (c.path.empty())
      c.name = "default";
    else
      c.name = c.from_log ? std::filesystem::path(c.path).filename().string()
                          : std::filesystem::path(c.path).stem().string();
  }
  for (std::size_t i = 0; i < columns.size(); ++i) {
    bool taken = false;
    for (std::size_t j = 0; j < columns.size(); ++j) taken |= j != i && columns[j].name == columns[i].name;
    if (taken && !columns[i].path.empty()) columns[i].name = columns[i].path;
  }
  std::set<std::string> seen;
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (!seen.insert(columns[i].name).second) columns[i].name += fmt::format("#{}", i + 1);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{
      "kew-eval: score kew's alerts on recordings in hindsight (hits, close calls, nuisances, ineligible; "
      "detected, missed and unwarnable losses; warning times)"};
  app.set_version_flag("--version", kew::protocol::version_line("kew-eval"));
  const auto file_formats = {kew::protocol::Format::AsterixDatagram};
  app.add_option("--format", options.format, "input format: " + kew::protocol::kFormatNames.list(file_formats))
      ->default_val("auto")
      ->check(CLI::IsMember(kew::protocol::kFormatNames.names(file_formats)));
  app.add_option("-c,--config", options.config_paths,
                 "kew TOML configuration to run (repeatable: one column each; none: the default configuration)")
      ->allow_extra_args(false);  // one file per --config: the rest are recordings
  app.add_option("--alerts", options.alert_paths,
                 "score this alert log (JSON lines of kew-replay or kewd) as a column of its own (repeatable); "
                 "scored with the first configuration's look-ahead and confirm")
      ->allow_extra_args(false)
      ->check(CLI::ExistingFile);
  app.add_option("--baseline", options.baselines,
                 "add a peer column scored by the same truth (repeatable): statebased (all pairs, linear, 5 NM, "
                 "1000 ft, 300 s, no filters, as BlueSky's StateBasedCD), raw (kew with every eligibility rule off)")
      ->allow_extra_args(false)
      ->check(CLI::IsMember({"statebased", "raw"}));
  app.add_flag("--sort", options.sort, "replay in time order (stable), as kew-replay --sort");
  app.add_flag("--json", options.json, "print one JSON object instead of the table");
  app.add_flag("--list", options.list, "list every alert and every loss with its class (in the JSON with --json)");
  app.add_flag("--explain", options.explain,
               "explain every missed, late (warned < --late-s ahead) and unwarnable loss: the stage that kept kew "
               "from alerting earlier, with its evidence, and a census by stage (in the JSON with --json)");
  app.add_option("--late-s", options.late_s, "with --explain: a loss warned less than this ahead is late, s")
      ->default_val(kew::replay::explanation_rules::kLateWarning_s)
      ->check(CLI::Range(0.0, 3600.0));
  app.add_option("--h-nm", options.h_nm, "horizontal separation minimum of the truth, NM")
      ->default_val(5.0)
      ->check(CLI::Range(0.001, 100.0));
  app.add_option("--v-ft", options.v_ft,
                 "vertical separation minimum of the truth, ft (a loss is below it less 200 ft)")
      ->default_val(1000.0)
      ->check(CLI::Range(201.0, 10000.0));
  app.add_option("files", options.files, "recordings (merged in time order)")
      ->required()
      ->check(CLI::Validator([](std::string& path) { return kew::replay::recording_path_problem(path); }, "RECORDING"));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }

  // Configurations to run: those given, else the default one unless only logs are scored.
  std::vector<kew::config::SharedConfig> configs;
  std::vector<Column> columns;
  for (const std::string& path : options.config_paths) {
    std::optional<kew::config::SharedConfig> loaded = kew::replay::tools::load_tool_config("kew-eval", path);
    if (!loaded) return kUsageError;
    configs.push_back(std::move(*loaded));
    columns.push_back(Column{});
    columns.back().path = path;
  }
  const bool run_default = configs.empty() && options.alert_paths.empty();
  if (configs.empty()) {
    // The default configuration: run, or only the source of the truth's aerodromes.
    std::optional<kew::config::SharedConfig> defaults = kew::replay::tools::load_tool_config("kew-eval", "");
    if (!defaults) return kUsageError;
    configs.push_back(std::move(*defaults));
  }
  if (run_default) columns.push_back(Column{});
  for (std::size_t i = 0; i < columns.size(); ++i) {
    columns[i].parameters = {configs[i].pipeline.minima.lookahead_s, configs[i].pipeline.alerts.confirm};
  }
  for (const std::string& path : options.alert_paths) {
    Column c;
    c.from_log = true;
    c.path = path;
    c.parameters = {configs.front().pipeline.minima.lookahead_s, configs.front().pipeline.alerts.confirm};
    columns.push_back(std::move(c));
  }
  for (const std::string& baseline : options.baselines) {
    Column c;
    c.baseline = baseline;
    if (baseline == "statebased") {
      const kew::replay::StateBasedConfig peer;
      c.parameters = {peer.lookahead_s, 1};
    } else {
      c.parameters = {configs.front().pipeline.minima.lookahead_s, configs.front().pipeline.alerts.confirm};
    }
    columns.push_back(std::move(c));
  }
  name_columns(columns);

  // The truth comes from the first configuration's decoding; each run decodes with its
  // own configuration, as kew-replay with that file would.
  std::uint64_t decode_rejected = 0;
  const std::vector<kew::TrackReport> records = read_records(options, configs.front().decoding, true, decode_rejected);
  kew::replay::SeparationStandard standard;
  standard.horizontal_m = options.h_nm * kew::replay::truth_rules::kNauticalMile_m;
  standard.vertical_ft = options.v_ft;
  const auto start = std::chrono::steady_clock::now();
  // The truth's lower limit stands above the first configuration's aerodromes.
  const Truth truth(records, *configs.front().pipeline.eligibility.aerodromes, standard);
  const double truth_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (std::size_t i = 0; i < columns.size(); ++i) {
    Column& c = columns[i];
    // A pipeline run, scored, and explained when asked.
    const auto run_scored = [&](const kew::config::SharedConfig& config, const std::vector<kew::TrackReport>& run) {
      run_pipeline(config, run, c);
      c.evaluation = kew::replay::evaluate(truth, c.alerts, c.parameters);
      if (options.explain)
        c.explanations = kew::replay::explain_losses(truth, c.evaluation, c.alerts, config.pipeline, run,
                                                     kew::replay::losses_to_explain(c.evaluation, options.late_s),
                                                     options.late_s);
    };
    if (c.baseline == "statebased") {
      c.alerts = kew::replay::state_based_alerts(records);
      c.records = records.size();
    } else if (c.baseline == "raw") {
      run_scored(without_eligibility(configs.front()), records);
      continue;
    } else if (c.from_log) {
      std::string error;
      if (!read_alert_log(c.path, c, error)) {
        std::fprintf(stderr, "kew-eval: %s\n", error.c_str());
        return kInputError;
      }
    } else if (i == 0) {
      run_scored(configs[i], records);
      continue;
    } else {
      std::uint64_t ignored = 0;
      run_scored(configs[i], read_records(options, configs[i].decoding, false, ignored));
      continue;
    }
    c.evaluation = kew::replay::evaluate(truth, c.alerts, c.parameters);
  }
  // Area proximity warnings, scored against the truth of the volumes of the column's
  // configuration (a log's and the raw baseline's: the first), on the first's records.
  std::vector<std::shared_ptr<const kew::replay::AreaTruth>> area_truths(configs.size());
  for (std::size_t i = 0; i < columns.size(); ++i) {
    Column& c = columns[i];
    if (c.baseline == "statebased") continue;
    const std::size_t k = !c.from_log && c.baseline.empty() ? i : 0;
    const std::vector<kew::volume::WatchedVolume>& volumes = configs[k].pipeline.volumes;
    if (volumes.empty() && c.area.alerts.empty()) continue;
    if (!area_truths[k]) area_truths[k] = std::make_shared<const kew::replay::AreaTruth>(truth, records, volumes);
    c.area.truth = area_truths[k];
    c.area.evaluation = kew::replay::evaluate_areas(truth, *c.area.truth, c.area.alerts, c.parameters.confirm);
  }
  std::fprintf(stderr,
               "kew-eval: %zu records decoded (%llu rejected by the decoders), %zu tracks, %.2f flight hours, "
               "%zu loss events; truth in %.2f s\n",
               records.size(), static_cast<unsigned long long>(decode_rejected), truth.figures().tracks,
               truth.figures().flight_hours(), truth.loss_events().size(), truth_s);

  if (options.json) {
    print_json(options, truth, columns);
  } else {
    if (options.list) print_list(truth, columns);
    if (options.explain) print_explanations(truth, columns, options.late_s);
    print_table(options, truth, columns);
    std::vector<std::pair<std::string, const AreaRun*>> area_columns;
    for (const Column& c : columns) area_columns.emplace_back(c.name, &c.area);
    const std::string areas = area_table(area_columns);
    std::fwrite(areas.data(), 1, areas.size(), stdout);
  }
  std::fflush(stdout);
  return 0;
}
