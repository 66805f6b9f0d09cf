// kew_kinetic_defaults_bench: evidence for kew's kinetic defaults (design §2.3, §2.4,
// PipelineConfig::default_kinetic) on real recordings: the reinsertion tolerance τ
// (KineticConfig::tolerance, m), kept models (keep_model_s) and the event threshold H
// (horizon_s), against the thesis' own setting.
//
// Each shared recording is decoded once, as kew-eval decodes it (the configuration
// tests/eval/alert_quality.py gives it: the defaults, UPC with its [[radar]] table); then
// for every kinetic setting a fresh Pipeline, configured as kew-eval would be but for
// `kinetic`, processes all records and end_of_input(), K times. Reported per setting:
// the median thread-CPU seconds of that loop and µs per record, the summed kinetic
// counters, and the alert events. τ and H must never change an alert: every setting's
// events are compared with the first setting's, field by field (bit for bit), and any
// difference is printed and makes the exit status 1.
//
// Usage: kew_kinetic_defaults_bench [--sweep tolerance|horizon|all] [--repeats K]
//                                   [--quick] [--json FILE] [--recordings DIR]
//                                   [--recording FILE]...
// --quick runs the first 20 % of each recording's records once.

#include <time.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <memory>
#include <string>
#include <vector>

#include "bench_report.hpp"
#include "kew/config/document.hpp"
#include "kew/config/shared_config.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/replay/recording_reader.hpp"

#ifndef KEW_GOLDEN_DIR
#define KEW_GOLDEN_DIR "tests/golden"
#endif
#ifndef KEW_SHARED_RECORDINGS_DIR
#define KEW_SHARED_RECORDINGS_DIR "../shared/data/recordings"
#endif

namespace {

using kew::bench::JsonText;
using kew::bench::Stopwatch;
using kew::kinetic::KineticConfig;

// UPC's radar table, the file run_golden.py reads too: without it UPC's CAT048 plots
// (polar, relative to the radar) have no position.
std::string barcelona_radar() {
  std::ifstream file(KEW_GOLDEN_DIR "/upc-bcn-radar.toml");
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Three kinds of surveillance from tests/eval/alert_quality.py's CASES: a radar's plots
// at ~4 s, system tracks (CAT062), ADS-B.
struct Case {
  const char* label;
  const char* relative_path;
  bool radar;
};
constexpr Case kCases[] = {
    {"upc-bcn-cat048 (60 min)", "upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast", true},
    {"jade-cat062-ff (30 min)", "jade-cat062-ff/final_frame_062_30min.ff", false},
    {"readsb 1hr", "adsb_actions-readsb/1hr.json", false},
};

struct Options {
  std::string sweep = "all";
  int repeats = 3;
  bool quick = false;
  std::string json_path;
  std::string recordings = KEW_SHARED_RECORDINGS_DIR;
  /// --recording: these files instead of the shared recordings, with the defaults
  /// (generated traffic, to see what a denser sky does to the choice).
  std::vector<std::string> files;
};

struct Setting {
  std::string name;
  KineticConfig kinetic;
};

[[noreturn]] void usage(const std::string& problem) {
  std::fprintf(stderr,
               "kew_kinetic_defaults_bench: %s\nusage: kew_kinetic_defaults_bench [--sweep tolerance|horizon|all] "
               "[--repeats K] [--quick] [--json FILE] [--recordings DIR] [--recording FILE]...\n",
               problem.c_str());
  std::exit(64);
}

Options parse(int argc, char** argv) {
  Options o;
  bool repeats_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--quick") {
      o.quick = true;
    } else if (flag == "--sweep" && i + 1 < argc) {
      o.sweep = argv[++i];
      if (o.sweep != "tolerance" && o.sweep != "horizon" && o.sweep != "all") usage("--sweep takes tolerance, horizon or all");
    } else if (flag == "--repeats" && i + 1 < argc) {
      o.repeats = std::atoi(argv[++i]);
      repeats_given = true;
      if (o.repeats < 1 || o.repeats > 100) usage("--repeats must be in [1, 100]");
    } else if (flag == "--json" && i + 1 < argc) {
      o.json_path = argv[++i];
    } else if (flag == "--recordings" && i + 1 < argc) {
      o.recordings = argv[++i];
    } else if (flag == "--recording" && i + 1 < argc) {
      o.files.push_back(argv[++i]);
    } else {
      usage("unknown or incomplete flag " + flag);
    }
  }
  if (o.quick && !repeats_given) o.repeats = 1;
  return o;
}

std::string number_text(double x) {
  if (x == kew::kinetic::kNever) return "inf";
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

/// The grid, each setting a change of PipelineConfig::default_kinetic(); kew's defaults
/// appear once even when both sweeps hold them.
std::vector<Setting> settings_of(const std::string& sweep) {
  std::vector<Setting> out;
  const KineticConfig defaults = kew::PipelineConfig::default_kinetic();
  const auto add = [&](const std::string& name, const KineticConfig& k) {
    for (const Setting& s : out)
      if (s.kinetic.tolerance == k.tolerance && s.kinetic.keep_model_s == k.keep_model_s &&
          s.kinetic.horizon_s == k.horizon_s && s.kinetic.lazy_window_s == k.lazy_window_s)
        return;
    // kew's defaults under one name, whichever sweep reaches them first.
    const bool is_default = k.tolerance == defaults.tolerance && k.keep_model_s == defaults.keep_model_s &&
                            k.horizon_s == defaults.horizon_s && k.lazy_window_s == defaults.lazy_window_s;
    out.push_back({is_default ? "defaults" : name, k});
  };
  if (sweep != "horizon") {
    // τ = 0 keeps only reports exactly on the model (repeated reports).
    for (const double tau : {0.0, 25.0, 50.0, 100.0, 150.0, 300.0, 600.0, 1000.0, 2000.0}) {
      KineticConfig k = defaults;
      k.tolerance = tau;
      add("tau " + number_text(tau) + " keep 4", k);
    }
    for (const double tau : {50.0, 150.0, 300.0}) {
      KineticConfig k = defaults;
      k.tolerance = tau;
      k.keep_model_s = 0.0;
      add("tau " + number_text(tau) + " keep 0", k);
    }
  }
  if (sweep != "tolerance") {
    for (const double h : {4.0, 12.0, 30.0, 60.0, 120.0, 300.0, kew::kinetic::kNever}) {
      KineticConfig k = defaults;
      k.horizon_s = h;
      add("H " + number_text(h), k);
    }
  }
  KineticConfig thesis = defaults;
  thesis.lazy_window_s = 0.0;
  thesis.keep_model_s = 0.0;
  thesis.tolerance = 50.0;
  thesis.horizon_s = 4.0;
  add("thesis", thesis);
  return out;
}

// Every field of an event, doubles to the last bit (%.17g): "identical" means identical.
std::string event_line(const kew::AlertEvent& e) {
  std::string line;
  char text[160];
  const auto party = [&](const kew::AlertParty& p) {
    std::snprintf(text, sizeof text, " %u %.17g %.17g %.17g %.17g %.17g %.17g", p.track_number, p.lat_deg, p.lon_deg,
                  p.alt_ft, p.gs_kt, p.trk_deg, p.vr_fpm);
    line += " " + p.source + "/" + p.id + "/" + p.callsign + text;
  };
  std::snprintf(text, sizeof text, "%" PRIu64 " %s %u %d %d %d %d %d %.17g %.17g", e.seq, e.id.c_str(), e.number,
                static_cast<int>(e.kind), static_cast<int>(e.state), static_cast<int>(e.end_reason),
                static_cast<int>(e.severity), static_cast<int>(e.hypothesis), e.t, e.opened_t);
  line += text;
  party(e.a);
  party(e.b);
  std::snprintf(text, sizeof text, " %.17g %.17g %.17g %.17g %.17g %.17g", e.t_los_s, e.t_cpa_s, e.cpa_h_m, e.cpa_v_ft,
                e.sep_h_m, e.sep_v_ft);
  line += text;
  line += " " + e.region + " " + e.volume + " " + e.volume_kind + (e.acknowledged ? " ack" : "");
  return line;
}

std::uint64_t fnv1a(const std::vector<std::string>& lines) {
  std::uint64_t h = 14695981039346656037ull;
  for (const std::string& line : lines)
    for (const char c : line + '\n') h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

struct Result {
  Setting setting;
  std::vector<double> cpu_s;  // one per repeat
  double median_s = 0.0;
  kew::kinetic::KineticStatistics kinetic;
  std::uint64_t records = 0, accepted = 0, events = 0, alerts = 0;
  std::uint64_t digest = 0;
  bool repeats_agree = true;  // every repeat gave the same events (determinism)
  bool identical = true;      // the same events as the first setting
};

struct RecordingRun {
  std::string label, path;
  std::uint64_t decoded = 0, decode_rejected = 0, run = 0;
  std::vector<Result> results;
  bool identical = true;
};

/// kew-eval's read_records for one file (Format::Auto, no --sort): the recording's
/// records in file order.
std::vector<kew::TrackReport> read_records(const std::string& path, const kew::protocol::DecoderOptions& decoding,
                                           std::uint64_t& rejected) {
  kew::replay::MergedRecordings recordings;
  recordings.add(std::make_unique<kew::replay::RecordingReader>(path, kew::protocol::Format::Auto, decoding));
  std::vector<kew::TrackReport> records;
  kew::TrackReport report;
  while (recordings.next(report)) records.push_back(report);
  rejected = recordings.rejections().total();
  return records;
}

Result run_setting(const kew::PipelineConfig& base, const Setting& setting, const std::vector<kew::TrackReport>& records,
                   int repeats, std::vector<std::string>& lines) {
  Result r;
  r.setting = setting;
  kew::PipelineConfig config = base;
  config.kinetic = setting.kinetic;
  std::vector<kew::AlertEvent> events;
  for (int k = 0; k < repeats; ++k) {
    events.clear();
    kew::Pipeline pipeline(config);
    pipeline.set_alert_sink([&](const kew::AlertEvent& e) { events.push_back(e); });
    Stopwatch watch;
    for (const kew::TrackReport& report : records) pipeline.process(report);
    pipeline.end_of_input();
    r.cpu_s.push_back(watch.seconds());
    std::vector<std::string> run_lines;
    run_lines.reserve(events.size());
    for (const kew::AlertEvent& e : events) run_lines.push_back(event_line(e));
    if (k == 0) {
      lines = std::move(run_lines);
      r.kinetic = pipeline.kinetic_statistics();
      r.records = pipeline.statistics().records;
      r.accepted = pipeline.statistics().accepted;
      r.events = events.size();
      for (const kew::AlertEvent& e : events) r.alerts += e.state == kew::AlertState::New;
      r.digest = fnv1a(lines);
    } else {
      r.repeats_agree = r.repeats_agree && fnv1a(run_lines) == r.digest;
    }
  }
  std::vector<double> times = r.cpu_s;
  r.median_s = kew::bench::percentile(times, 0.5);
  return r;
}

void print_table(const RecordingRun& run) {
  std::printf("\n### %s\n\n%s: %" PRIu64 " records decoded (%" PRIu64 " rejected by the decoders), %" PRIu64
              " run; alerts identical across settings: %s\n\n",
              run.label.c_str(), run.path.c_str(), run.decoded, run.decode_rejected, run.run,
              run.identical ? "yes" : "NO");
  std::printf(
      "| setting | lazy s | τ m | keep s | H s | CPU s | µs/rec | updates | velocity | kept | reinsert | drift | "
      "renewals | solved | deferred | computed | discarded | queue mean | renewals queued | events (alerts) | same |\n"
      "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|:-:|\n");
  for (const Result& r : run.results) {
    const KineticConfig& k = r.setting.kinetic;
    const kew::kinetic::KineticStatistics& s = r.kinetic;
    const double us = r.records ? 1e6 * r.median_s / static_cast<double>(r.records) : 0.0;
    std::printf("| %s | %s | %s | %s | %s | %.3f | %.2f | %" PRIu64 " | %" PRIu64 " | %" PRIu64 " | %" PRIu64 " | %" PRIu64
                " | %" PRIu64 " | %" PRIu64 " | %" PRIu64 " | %" PRIu64 " | %" PRIu64 " | %.1f | %zu | %" PRIu64
                " (%" PRIu64 ") | %s |\n",
                r.setting.name.c_str(), number_text(k.lazy_window_s).c_str(), number_text(k.tolerance).c_str(),
                number_text(k.keep_model_s).c_str(), number_text(k.horizon_s).c_str(), r.median_s, us, s.updates,
                s.velocity_updates, s.kept_updates, s.reinsertions, s.drift_reinsertions, s.renewals,
                s.certificates_solved, s.certificates_deferred, s.events_computed, s.events_discarded, s.queue_mean(),
                s.renewals_queued, r.events, r.alerts, r.identical ? (r.repeats_agree ? "yes" : "yes*") : "NO");
  }
  std::fflush(stdout);
}

void put_result(JsonText& json, const Result& r) {
  const KineticConfig& k = r.setting.kinetic;
  const kew::kinetic::KineticStatistics& s = r.kinetic;
  json.begin_object();
  json.key("name").value(r.setting.name);
  json.key("parameters").begin_object();
  json.key("lazy_window_s").value(k.lazy_window_s);
  json.key("tolerance_m").value(k.tolerance);
  json.key("tolerance_mode").value(kew::kinetic::kToleranceModeNames.name(k.tolerance_mode));
  json.key("keep_model_s").value(k.keep_model_s);
  json.key("horizon_s").value(k.horizon_s);  // null: never (kinetic::kNever)
  json.key("reduce_redundant_events").value(k.reduce_redundant_events);
  json.end_object();
  json.key("cpu_s_median").value(r.median_s);
  json.key("cpu_s_runs").begin_array();
  for (const double t : r.cpu_s) json.value(t);
  json.end_array();
  json.key("us_per_record").value(r.records ? 1e6 * r.median_s / static_cast<double>(r.records) : 0.0);
  json.key("records").value(r.records);
  json.key("accepted").value(r.accepted);
  json.key("counters").begin_object();
  const std::pair<const char*, std::uint64_t> counts[] = {
      {"updates", s.updates},
      {"velocity_updates", s.velocity_updates},
      {"kept_updates", s.kept_updates},
      {"reinsertions", s.reinsertions},
      {"drift_reinsertions", s.drift_reinsertions},
      {"renewals", s.renewals},
      {"certificates_solved", s.certificates_solved},
      {"certificates_deferred", s.certificates_deferred},
      {"certificates_kept", s.certificates_kept},
      {"events_computed", s.events_computed},
      {"events_executed", s.events_executed},
      {"events_discarded", s.events_discarded},
      {"insertions", s.insertions},
      {"removals", s.removals},
      {"renewals_queued", s.renewals_queued},
      {"queue_max", s.queue_max},
  };
  for (const auto& [name, n] : counts) json.key(name).value(n);
  json.key("queue_mean").value(s.queue_mean());
  json.end_object();
  json.key("alert_events").value(r.events);
  json.key("alerts").value(r.alerts);
  char digest[24];
  std::snprintf(digest, sizeof digest, "%016" PRIx64, r.digest);
  json.key("alert_digest").value(digest);
  json.key("alerts_identical").value(r.identical);
  json.key("repeats_agree").value(r.repeats_agree);
  json.end_object();
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);
  const std::vector<Setting> settings = settings_of(options.sweep);
  std::printf("# kew kinetic defaults: %zu settings, %d repeat(s)%s, build %s, %s\n", settings.size(), options.repeats,
              options.quick ? ", --quick (first 20 % of records)" : "", KEW_BUILD_TYPE,
              kew::bench::cpu_model_name().c_str());

  std::vector<RecordingRun> runs;
  std::vector<std::string> skipped;
  bool all_identical = true;
  Stopwatch total;
  std::vector<Case> cases(std::begin(kCases), std::end(kCases));
  if (!options.files.empty()) {
    cases.clear();
    for (const std::string& file : options.files) cases.push_back({file.c_str(), file.c_str(), false});
  }
  for (const Case& c : cases) {
    const bool shared = options.files.empty();
    const std::string path = shared ? (std::filesystem::path(options.recordings) / c.relative_path).string() : c.relative_path;
    if (!std::filesystem::exists(path)) {
      std::fprintf(stderr, "kew_kinetic_defaults_bench: %s is absent: skipped\n", path.c_str());
      skipped.push_back(path);
      continue;
    }
    // The configuration alert_quality.py hands kew-eval: a file holding nothing (the
    // defaults) or UPC's radar table.
    kew::config::SharedConfig config;
    try {
      config = kew::config::read_shared_config(kew::config::Document::parse(c.radar ? barcelona_radar() : "", c.label));
    } catch (const kew::config::ConfigError& e) {
      std::fprintf(stderr, "kew_kinetic_defaults_bench: %s\n", e.what());
      return 2;
    }
    // One thread, so that the thread-CPU stopwatch sees all the work; events do not
    // depend on the number of threads (Pipeline's determinism).
    config.pipeline.threads = 1;

    RecordingRun run;
    run.label = c.label;
    run.path = path;
    std::vector<kew::TrackReport> records = read_records(path, config.decoding, run.decode_rejected);
    run.decoded = records.size();
    if (options.quick) records.resize(records.size() / 5);
    run.run = records.size();
    std::fprintf(stderr, "%s: %zu records to run\n", c.label, records.size());

    std::vector<std::string> reference;  // the first setting's events, one line each
    for (const Setting& setting : settings) {
      std::vector<std::string> lines;
      Result r = run_setting(config.pipeline, setting, records, options.repeats, lines);
      if (run.results.empty()) {
        reference = std::move(lines);
      } else if (r.digest != run.results.front().digest || lines.size() != reference.size()) {
        r.identical = false;
        std::size_t i = 0;
        while (i < lines.size() && i < reference.size() && lines[i] == reference[i]) ++i;
        std::fprintf(stderr,
                     "kew_kinetic_defaults_bench: %s: '%s' differs from '%s' (%zu vs %zu events) at event %zu:\n"
                     "  %s: %s\n  %s: %s\n",
                     c.label, setting.name.c_str(), settings.front().name.c_str(), lines.size(), reference.size(), i,
                     settings.front().name.c_str(), i < reference.size() ? reference[i].c_str() : "(none)",
                     setting.name.c_str(), i < lines.size() ? lines[i].c_str() : "(none)");
      }
      if (!r.repeats_agree)
        std::fprintf(stderr, "kew_kinetic_defaults_bench: %s: '%s' gave different events on repeats\n", c.label,
                     setting.name.c_str());
      run.identical = run.identical && r.identical && r.repeats_agree;
      std::fprintf(stderr, "  %-18s %8.3f s CPU (median of %d)\n", setting.name.c_str(), r.median_s, options.repeats);
      run.results.push_back(std::move(r));
    }
    all_identical = all_identical && run.identical;
    print_table(run);
    runs.push_back(std::move(run));
  }
  std::printf("\nalerts identical across settings: %s; %.1f CPU s in all\n", all_identical ? "yes" : "NO",
              total.seconds());

  if (!options.json_path.empty()) {
    JsonText json;
    json.begin_object();
    json.key("benchmark").value("kew_kinetic_defaults_bench");
    json.key("command_line").value(command_line);
    json.key("date_utc").value(utc_now());
    kew::bench::put_machine(json, KEW_BUILD_TYPE);
    json.key("sweep").value(options.sweep);
    json.key("repeats").value(static_cast<std::uint64_t>(options.repeats));
    json.key("quick").value(options.quick);
    json.key("threads").value(std::uint64_t{1});
    json.key("alerts_identical").value(all_identical);
    json.key("skipped").begin_array();
    for (const std::string& path : skipped) json.value(path);
    json.end_array();
    json.key("recordings").begin_array();
    for (const RecordingRun& run : runs) {
      json.begin_object();
      json.key("label").value(run.label);
      json.key("path").value(run.path);
      json.key("records_decoded").value(run.decoded);
      json.key("decode_rejected").value(run.decode_rejected);
      json.key("records_run").value(run.run);
      json.key("alerts_identical").value(run.identical);
      json.key("settings").begin_array();
      for (const Result& r : run.results) put_result(json, r);
      json.end_array();
      json.end_object();
    }
    json.end_array();
    json.end_object();
    if (!json.save(options.json_path)) {
      std::fprintf(stderr, "kew_kinetic_defaults_bench: cannot write %s\n", options.json_path.c_str());
      return 2;
    }
  }
  return all_identical ? 0 : 1;
}
