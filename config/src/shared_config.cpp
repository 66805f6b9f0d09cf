#include "kew/config/shared_config.hpp"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "kew/config/aerodromes.hpp"
#include "kew/config/document.hpp"
#include "kew/config/regions.hpp"
#include "kew/config/volumes.hpp"
#include "parameter_ranges.hpp"

namespace kew::config {

namespace {

using ranges::kFoot;
using ranges::kNauticalMile;

void read_pipeline(TableReader& r, PipelineConfig& p) {
  // 0: one thread per core the machine has (design §3.3).
  std::size_t threads = 0;
  r.integer("threads", threads, 0, 256);
  p.threads = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
  r.integer("batch_records", p.batch_records, 1, 1'000'000);
  r.integer("prompt_records", p.prompt_records, 0, 1'000'000);
}

void read_projection(TableReader& r, PipelineConfig& p) {
  double lat = NAN, lon = NAN;
  r.number("reference_lat", lat, -90.0, 90.0);
  r.number("reference_lon", lon, -180.0, 180.0);
  if (std::isnan(lat) != std::isnan(lon)) r.fail(nullptr, "reference_lat and reference_lon go together");
  if (!std::isnan(lat)) p.reference = geo::GeodeticPosition{lat, lon};
  r.choice("zones", p.zone_mode, kZoneModeNames);
  // One plane reaches 3,000 km at most (design §4.2); worldwide, a limit may reach the
  // antipode (half a meridian, 20,004 km).
  const double largest_km = p.zone_mode == ZoneMode::Single ? 3000.0 : 20004.0;
  double radius_km = p.coverage_radius_m ? *p.coverage_radius_m / 1000.0 : NAN;
  r.number("coverage_radius_km", radius_km, 1.0, largest_km);
  if (!std::isnan(radius_km)) p.coverage_radius_m = radius_km * 1000.0;
  // Zones across machines (design §4.9): this instance's band of pair midpoints.
  LongitudeBand band = p.served_longitudes.value_or(LongitudeBand{});
  r.number("serve_west_deg", band.west_deg, -180.0, 180.0);
  r.number("serve_east_deg", band.east_deg, -180.0, 180.0);
  if (r.node("serve_west_deg") || r.node("serve_east_deg")) {
    if (p.zone_mode != ZoneMode::Worldwide)
      r.fail(nullptr, "serve_west_deg and serve_east_deg share the worldwide zones among instances: zones = \"single\" has one");
    if (band.west_deg >= band.east_deg)
      r.fail(nullptr, fmt::format("serve_west_deg = {} must be west of serve_east_deg = {}", band.west_deg, band.east_deg));
    p.served_longitudes = band;
  }
}

void read_tracks(TableReader& r, track::TrackTableConfig& t) {
  r.number("timeout_s", t.track_timeout_s, 1.0, 3600.0);
  r.number("max_ground_speed_kt", t.max_ground_speed_kt, 1.0, 5000.0);
  r.number("max_vertical_rate_fpm", t.max_vertical_rate_fpm, 1.0, 100000.0);
  r.number("min_altitude_ft", t.min_altitude_ft, -5000.0, 200000.0);
  r.number("max_altitude_ft", t.max_altitude_ft, -5000.0, 200000.0);
  if (t.min_altitude_ft >= t.max_altitude_ft) r.fail(nullptr, "min_altitude_ft must be below max_altitude_ft");
  r.boolean("exclude_on_ground", t.exclude_on_ground);
  r.integer("max_tracks", t.max_tracks, 1, 10'000'000);
  r.number("max_lateness_s", t.max_lateness_s, 0.0, 3600.0);
  r.number("max_time_jump_s", t.max_time_jump_s, 0.0, 3600.0);
  if (t.max_time_jump_s > t.max_lateness_s)  // or the held record could make every other one too late (§4.1)
    r.fail(nullptr, fmt::format("max_time_jump_s = {} must not exceed max_lateness_s = {}", t.max_time_jump_s,
                                t.max_lateness_s));
  r.number("max_derivation_gap_s", t.max_derivation_gap_s, 0.1, 3600.0);
}

void read_kinetic(TableReader& r, PipelineConfig& p) {
  kinetic::KineticConfig& k = p.kinetic;
  r.number("tolerance", k.tolerance, 0.0, 1e6);
  r.choice("tolerance_mode", k.tolerance_mode, kinetic::kToleranceModeNames);
  double horizon = std::isinf(k.horizon_s) ? 0.0 : k.horizon_s;
  r.number("horizon_s", horizon, 0.0, 1e9);
  k.horizon_s = horizon == 0.0 ? kinetic::kNever : horizon;
  r.boolean("reduce_redundant_events", k.reduce_redundant_events);
  r.number("keep_model_s", k.keep_model_s, 0.0, 3600.0);
  r.number("renumber_every_s", p.renumber_every_s, 0.0, 86400.0);
}

void read_probe(TableReader& r, PipelineConfig& p) {
  r.choice("mode", p.probe_mode, probe::kProbeModeNames);
  double horizontal_nm = p.minima.horizontal_m / kNauticalMile;
  double vertical_ft = p.minima.vertical_m / kFoot;
  r.number("horizontal_nm", horizontal_nm, ranges::kHorizontalNm.lo, ranges::kHorizontalNm.hi);
  r.number("vertical_ft", vertical_ft, ranges::kVerticalFt.lo, ranges::kVerticalFt.hi);
  r.number("lookahead_s", p.minima.lookahead_s, ranges::kLookaheadS.lo, ranges::kLookaheadS.hi);
  r.number("vertical_lookahead_s", p.minima.vertical_lookahead_s, 0.0, 3600.0);
  double tolerance_ft = p.minima.altimetry_tolerance_m / kFoot;
  r.number("altimetry_tolerance_ft", tolerance_ft, 0.0, 1000.0);
  p.minima.altimetry_tolerance_m = tolerance_ft * kFoot;
  if (tolerance_ft >= vertical_ft) r.fail(nullptr, "altimetry_tolerance_ft must be below vertical_ft");
  p.minima.horizontal_m = horizontal_nm * kNauticalMile;
  p.minima.vertical_m = vertical_ft * kFoot;
  r.boolean("vertical_intent", p.tracks.intent.enabled);
  r.boolean("turn_hypothesis", p.turn.enabled);
  r.number("turn_min_rate_dps", p.turn.min_rate_dps, 0.1, 30.0);
}

void read_alerts(TableReader& r, alert::AlertConfig& a) {
  r.integer("confirm", a.confirm, ranges::kEvaluationsMin, ranges::kEvaluationsMax);
  r.integer("clear", a.clear, ranges::kEvaluationsMin, ranges::kEvaluationsMax);
  r.number("warning_s", a.warning_s, ranges::kWarningS.lo, ranges::kWarningS.hi);
  r.number("update_t_los_s", a.update_t_los_s, 0.0, 3600.0);
  r.number("update_cpa_h_m", a.update_cpa_h_m, 0.0, 1e6);
  r.number("update_cpa_v_ft", a.update_cpa_v_ft, 0.0, 1e5);
}

// `aerodromes_file`: the key's path, resolved beside the configuration file; "" when
// absent or "" (the default table).
void read_eligibility(TableReader& r, eligibility::EligibilityConfig& e, std::string& aerodromes_file) {
  r.number("min_ground_speed_kt", e.min_ground_speed_kt, 0.0, 1000.0);
  r.number("min_altitude_ft", e.min_altitude_ft, -5000.0, 200000.0);
  r.number("max_altitude_ft", e.max_altitude_ft, -5000.0, 200000.0);
  if (e.min_altitude_ft >= e.max_altitude_ft) r.fail(nullptr, "min_altitude_ft must be below max_altitude_ft");
  r.number("lower_limit_ft", e.lower_limit_ft, 0.0, 100000.0);
  r.number("aerodrome_height_ft", e.aerodrome_height_ft, 0.0, 10000.0);
  r.number("aerodrome_radius_nm", e.aerodrome_radius_nm, 0.1, 50.0);
  r.path_beside_file("aerodromes_file", aerodromes_file);
  r.mode3a_list("excluded_mode3a", e.excluded_mode3a);
  for (const std::uint16_t code : e.excluded_mode3a)
    if (!eligibility::may_exclude_mode3a(code))
      r.fail(nullptr, fmt::format("excluded_mode3a: {:04o} is an emergency code and always alerts", code));
  r.boolean("exclude_coasting", e.exclude_coasting);
  r.number("max_position_age_s", e.max_position_age_s, 0.1, 3600.0);
  r.integer("min_records", e.min_records, 1, 10);
  r.number("level_rate_fpm", e.level_rate_fpm, 0.0, 5000.0);
  r.boolean("adjacent_level_off", e.adjacent_level_off);
  r.number("adjacent_level_off_above_ft", e.adjacent_level_off_above_ft, -5000.0, 200000.0);
  r.number("same_code_distance_nm", e.same_code_distance_nm, 0.0, 20.0);
  r.number("same_code_altitude_ft", e.same_code_altitude_ft, 0.0, 5000.0);
}

void read_decoding(TableReader& r, protocol::DecoderOptions& d) {
  r.number("sbs_utc_offset_s", d.sbs_utc_offset_s, -86400.0, 86400.0);
  r.integer("max_line_bytes", d.max_line_bytes, 256, 1 << 20);
  r.integer("max_snapshot_bytes", d.aircraft_json.max_snapshot_bytes, 4096, std::int64_t{1} << 30);
  r.number("max_position_age_s", d.aircraft_json.max_position_age_s, 0.1, 3600.0);
}

void read_radar(TableReader& r, protocol::RadarSite& site) {
  site.lat_deg = NAN;
  site.lon_deg = NAN;
  r.integer("sac", site.sac, 0, 255);
  r.integer("sic", site.sic, 0, 255);
  r.number("lat", site.lat_deg, -90.0, 90.0);
  r.number("lon", site.lon_deg, -180.0, 180.0);
  r.number("height_m", site.height_m, -500.0, 10000.0);
  if (std::isnan(site.lat_deg) || std::isnan(site.lon_deg)) r.fail(nullptr, "a radar needs lat and lon");
}

}  // namespace

SharedConfig::SharedConfig() {
  // The tools' defaults, not the library's: every core, batches long enough for the
  // zones of one to work in parallel, and the first records after each flush judged at
  // once (design §3.3).
  pipeline.threads = std::max(1u, std::thread::hardware_concurrency());
  pipeline.batch_records = kDefaultBatchRecords;
  pipeline.prompt_records = kDefaultPromptRecords;
}

SharedConfig read_shared_config(const Document& document) {
  std::vector<std::string_view> known(kSharedSections.begin(), kSharedSections.end());
  known.insert(known.end(), kDaemonSections.begin(), kDaemonSections.end());
  document.refuse_unknown_sections(known);
  SharedConfig config;
  document.section("pipeline", [&](TableReader& r) { read_pipeline(r, config.pipeline); });
  document.section("projection", [&](TableReader& r) { read_projection(r, config.pipeline); });
  document.section("tracks", [&](TableReader& r) { read_tracks(r, config.pipeline.tracks); });
  document.section("kinetic", [&](TableReader& r) { read_kinetic(r, config.pipeline); });
  document.section("probe", [&](TableReader& r) { read_probe(r, config.pipeline); });
  document.section("alerts", [&](TableReader& r) { read_alerts(r, config.pipeline.alerts); });
  document.section("eligibility", [&](TableReader& r) {
    read_eligibility(r, config.pipeline.eligibility, config.aerodromes_file);
    if (config.aerodromes_file.empty()) return;
    try {
      config.pipeline.eligibility.aerodromes = load_aerodromes(config.aerodromes_file);
    } catch (const ConfigError& e) {
      r.fail(r.node("aerodromes_file"), e.what());
    }
  });
  if (config.aerodromes_file.empty()) {
    config.aerodromes_file = default_aerodromes_file();
    config.pipeline.eligibility.aerodromes = load_default_aerodromes();
  }
  document.section("decoding", [&](TableReader& r) { read_decoding(r, config.decoding); });
  document.each_table("radar", [&](TableReader& r, std::size_t) {
    protocol::RadarSite site{};
    read_radar(r, site);
    // Plots are placed from the site their SAC/SIC names: two sites under one name would
    // leave it to the order of the file which one places them.
    for (const protocol::RadarSite& other : config.decoding.asterix.radars)
      if (other.sac == site.sac && other.sic == site.sic)
        r.fail(r.table_node(),
               fmt::format("a radar with sac = {} and sic = {} is already configured", site.sac, site.sic));
    config.decoding.asterix.radars.push_back(site);
  });
  // After [probe]: a region's vertical_ft is checked against its altimetry tolerance.
  config.pipeline.regions = read_regions(document, config.pipeline, &config.regions_geojson);
  // After [eligibility]: a band above an aerodrome takes its elevation from the table.
  config.pipeline.volumes = read_volumes(document, config.pipeline.eligibility.aerodromes.get());
  // Without a configured reference the radars' mean position is a better centre than
  // whatever record comes first (design §4.2). Longitudes are averaged as given: radars
  // of one feed do not straddle ±180°.
  const auto& radars = config.decoding.asterix.radars;
  if (!config.pipeline.reference && !radars.empty()) {
    double lat = 0.0, lon = 0.0;
    for (const protocol::RadarSite& site : radars) {
      lat += site.lat_deg;
      lon += site.lon_deg;
    }
    const double n = static_cast<double>(radars.size());
    config.pipeline.reference = geo::GeodeticPosition{lat / n, lon / n};
  }
  return config;
}

SharedConfig load_shared_config(const std::string& path) { return read_shared_config(Document::load(path)); }

SharedConfig default_shared_config() { return read_shared_config(Document::parse("", "the built-in configuration")); }

}  // namespace kew::config
