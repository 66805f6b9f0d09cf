// The configuration file (design §5.7): deploy/kew.toml documents the defaults the code
// uses, unknown keys are errors, and errors name the file and line; the shared tables
// (kew_config) read the same file as kewd (kew_daemon_config); one HOST:PORT parser.
#include "kew/daemon/config.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <unistd.h>

#include "kew/config/address.hpp"
#include "kew/config/document.hpp"
#include "kew/config/nats_subject.hpp"
#include "kew/config/shared_config.hpp"
#include "kew/config/utc_day.hpp"
#include "expect_config_error.hpp"

namespace kew::daemon {
namespace {

using config::ConfigError;
using config::HostPort;
using config::parse_host_port;
using config::parse_utc_day;

TEST(Config, TheShippedFileStatesExactlyTheBuiltInDefaults) {
  const Config file = load_config(std::string(KEW_DEPLOY_DIR) + "/kew.toml");
  const Config defaults = default_config();
  const PipelineConfig& p = file.pipeline;
  const PipelineConfig& d = defaults.pipeline;
  EXPECT_EQ(file.service.alert_listen, defaults.service.alert_listen);
  EXPECT_EQ(file.service.max_subscribers, defaults.service.max_subscribers);
  EXPECT_EQ(file.service.subscriber_queue, defaults.service.subscriber_queue);
  EXPECT_EQ(file.service.alive_interval_s, defaults.service.alive_interval_s);
  EXPECT_EQ(file.service.tick_interval_s, defaults.service.tick_interval_s);
  EXPECT_EQ(file.service.log_level, defaults.service.log_level);
  EXPECT_EQ(file.service.alert_log, defaults.service.alert_log);
  EXPECT_EQ(file.service.alert_log_max_bytes, defaults.service.alert_log_max_bytes);
  EXPECT_EQ(file.service.alert_log_keep, defaults.service.alert_log_keep);
  EXPECT_EQ(file.service.alert_log_sync, defaults.service.alert_log_sync);
  EXPECT_EQ(file.service.alert_log_queue_bytes, defaults.service.alert_log_queue_bytes);
  EXPECT_EQ(file.service.state_directory, defaults.service.state_directory);
  EXPECT_EQ(file.service.record_file, defaults.service.record_file);
  EXPECT_EQ(file.service.record_file_queue_bytes, defaults.service.record_file_queue_bytes);
  EXPECT_EQ(file.service.tracks_stream, defaults.service.tracks_stream);
  EXPECT_EQ(file.service.max_future_s, defaults.service.max_future_s);
  EXPECT_EQ(file.nats.servers, defaults.nats.servers);
  EXPECT_EQ(file.nats.replicas, defaults.nats.replicas);
  EXPECT_EQ(file.nats.name, defaults.nats.name);
  EXPECT_EQ(file.nats.alerts_subject, defaults.nats.alerts_subject);
  EXPECT_EQ(file.nats.acks_subject, defaults.nats.acks_subject);
  EXPECT_EQ(file.nats.status_subject, defaults.nats.status_subject);
  EXPECT_EQ(file.nats.tracks_subject, defaults.nats.tracks_subject);
  EXPECT_EQ(file.nats.tracks_interval_s, defaults.nats.tracks_interval_s);
  EXPECT_EQ(file.nats.stream, defaults.nats.stream);
  EXPECT_EQ(file.nats.stream_max_age_s, defaults.nats.stream_max_age_s);
  EXPECT_EQ(file.nats.stream_max_bytes, defaults.nats.stream_max_bytes);
  EXPECT_EQ(file.nats.outbox, defaults.nats.outbox);
  EXPECT_EQ(file.nats.hot_standby, defaults.nats.hot_standby);
  EXPECT_EQ(file.nats.lease_bucket, defaults.nats.lease_bucket);
  EXPECT_EQ(file.nats.pair_bucket, defaults.nats.pair_bucket);
  EXPECT_EQ(file.nats.checkpoint_interval_s, defaults.nats.checkpoint_interval_s);
  EXPECT_EQ(file.nats.checkpoint_stream, defaults.nats.checkpoint_stream);
  EXPECT_EQ(file.nats.lease_key, defaults.nats.lease_key);
  EXPECT_EQ(file.nats.lease_ttl_s, defaults.nats.lease_ttl_s);
  EXPECT_EQ(file.nats.instance, defaults.nats.instance);
  EXPECT_EQ(file.nats.standby_history, defaults.nats.standby_history);
  EXPECT_FALSE(p.reference.has_value());
  EXPECT_EQ(p.zone_mode, d.zone_mode);
  EXPECT_EQ(p.coverage_radius_m, d.coverage_radius_m);
  EXPECT_EQ(p.threads, d.threads);  // [pipeline] threads = 0: one per core, as the default
  EXPECT_EQ(p.batch_records, d.batch_records);
  EXPECT_EQ(p.prompt_records, d.prompt_records);
  EXPECT_EQ(p.tracks.track_timeout_s, d.tracks.track_timeout_s);
  EXPECT_EQ(p.tracks.max_ground_speed_kt, d.tracks.max_ground_speed_kt);
  EXPECT_EQ(p.tracks.max_vertical_rate_fpm, d.tracks.max_vertical_rate_fpm);
  EXPECT_EQ(p.tracks.min_altitude_ft, d.tracks.min_altitude_ft);
  EXPECT_EQ(p.tracks.max_altitude_ft, d.tracks.max_altitude_ft);
  EXPECT_EQ(p.tracks.exclude_on_ground, d.tracks.exclude_on_ground);
  EXPECT_EQ(p.tracks.max_tracks, d.tracks.max_tracks);
  EXPECT_EQ(p.tracks.max_lateness_s, d.tracks.max_lateness_s);
  EXPECT_EQ(p.tracks.max_time_jump_s, d.tracks.max_time_jump_s);
  EXPECT_EQ(p.tracks.max_derivation_gap_s, d.tracks.max_derivation_gap_s);
  EXPECT_EQ(p.kinetic.tolerance, d.kinetic.tolerance);
  EXPECT_EQ(p.kinetic.tolerance_mode, d.kinetic.tolerance_mode);
  EXPECT_EQ(p.kinetic.horizon_s, d.kinetic.horizon_s);
  EXPECT_EQ(p.kinetic.reduce_redundant_events, d.kinetic.reduce_redundant_events);
  EXPECT_EQ(p.kinetic.keep_model_s, d.kinetic.keep_model_s);
  EXPECT_EQ(p.renumber_every_s, d.renumber_every_s);
  EXPECT_EQ(p.probe_mode, d.probe_mode);
  EXPECT_DOUBLE_EQ(p.minima.horizontal_m, d.minima.horizontal_m);
  EXPECT_DOUBLE_EQ(p.minima.vertical_m, d.minima.vertical_m);
  EXPECT_EQ(p.minima.lookahead_s, d.minima.lookahead_s);
  EXPECT_EQ(p.minima.vertical_lookahead_s, d.minima.vertical_lookahead_s);
  EXPECT_DOUBLE_EQ(p.minima.altimetry_tolerance_m, d.minima.altimetry_tolerance_m);
  EXPECT_EQ(p.tracks.intent.enabled, d.tracks.intent.enabled);
  EXPECT_EQ(p.turn.enabled, d.turn.enabled);
  EXPECT_EQ(p.turn.min_rate_dps, d.turn.min_rate_dps);
  EXPECT_EQ(p.alerts.confirm, d.alerts.confirm);
  EXPECT_EQ(p.alerts.clear, d.alerts.clear);
  EXPECT_EQ(p.alerts.warning_s, d.alerts.warning_s);
  EXPECT_EQ(p.alerts.update_t_los_s, d.alerts.update_t_los_s);
  EXPECT_EQ(p.alerts.update_cpa_h_m, d.alerts.update_cpa_h_m);
  EXPECT_EQ(p.alerts.update_cpa_v_ft, d.alerts.update_cpa_v_ft);
  EXPECT_EQ(p.eligibility.min_ground_speed_kt, d.eligibility.min_ground_speed_kt);
  EXPECT_EQ(p.eligibility.min_altitude_ft, d.eligibility.min_altitude_ft);
  EXPECT_EQ(p.eligibility.max_altitude_ft, d.eligibility.max_altitude_ft);
  EXPECT_EQ(p.eligibility.lower_limit_ft, d.eligibility.lower_limit_ft);
  EXPECT_EQ(p.eligibility.aerodrome_height_ft, d.eligibility.aerodrome_height_ft);
  EXPECT_EQ(p.eligibility.aerodrome_radius_nm, d.eligibility.aerodrome_radius_nm);
  EXPECT_EQ(file.aerodromes_file, defaults.aerodromes_file);  // "": kew's table
  EXPECT_EQ(p.eligibility.aerodromes->size(), d.eligibility.aerodromes->size());
  EXPECT_EQ(p.eligibility.excluded_mode3a, d.eligibility.excluded_mode3a);
  EXPECT_EQ(p.eligibility.exclude_coasting, d.eligibility.exclude_coasting);
  EXPECT_EQ(p.eligibility.max_position_age_s, d.eligibility.max_position_age_s);
  EXPECT_EQ(p.eligibility.level_rate_fpm, d.eligibility.level_rate_fpm);
  EXPECT_EQ(p.eligibility.same_code_distance_nm, d.eligibility.same_code_distance_nm);
  EXPECT_EQ(p.eligibility.same_code_altitude_ft, d.eligibility.same_code_altitude_ft);
  EXPECT_TRUE(p.regions.empty());
  EXPECT_EQ(file.regions_geojson, "");
  EXPECT_EQ(file.cat004.enabled, defaults.cat004.enabled);
  EXPECT_EQ(file.cat004.destination, defaults.cat004.destination);
  EXPECT_EQ(file.cat004.interface, defaults.cat004.interface);
  EXPECT_EQ(file.cat004.ttl, defaults.cat004.ttl);
  EXPECT_EQ(file.cat004.sac, defaults.cat004.sac);
  EXPECT_EQ(file.cat004.sic, defaults.cat004.sic);
  EXPECT_EQ(file.cat004.alive_interval_s, defaults.cat004.alive_interval_s);
  EXPECT_EQ(file.modbus.enabled, defaults.modbus.enabled);
  EXPECT_EQ(file.modbus.listen, defaults.modbus.listen);
  EXPECT_EQ(file.modbus.unit_id, defaults.modbus.unit_id);
  EXPECT_EQ(file.modbus.table_entries, defaults.modbus.table_entries);
  EXPECT_EQ(file.modbus.read_only, defaults.modbus.read_only);
  EXPECT_EQ(file.modbus.max_connections, defaults.modbus.max_connections);
  EXPECT_EQ(file.modbus.silent_per_address, defaults.modbus.silent_per_address);
  EXPECT_EQ(file.modbus.allow_remote, defaults.modbus.allow_remote);
  EXPECT_EQ(file.modbus.acknowledge_from, defaults.modbus.acknowledge_from);
  EXPECT_EQ(file.service.allow_remote, defaults.service.allow_remote);
  EXPECT_EQ(file.http.enabled, defaults.http.enabled);
  EXPECT_EQ(file.http.listen, defaults.http.listen);
  EXPECT_EQ(file.http.allow_remote, defaults.http.allow_remote);
  EXPECT_EQ(file.http.web_root, defaults.http.web_root);
  EXPECT_EQ(file.http.leaflet_root, defaults.http.leaflet_root);
  EXPECT_EQ(file.http.host_names, defaults.http.host_names);
  EXPECT_EQ(file.http.max_connections, defaults.http.max_connections);
  EXPECT_EQ(file.http.silent_per_address, defaults.http.silent_per_address);
  EXPECT_EQ(file.service.silent_per_address, defaults.service.silent_per_address);
  EXPECT_EQ(file.service.write_timeout_s, defaults.service.write_timeout_s);
  EXPECT_EQ(file.http.max_header_bytes, defaults.http.max_header_bytes);
  EXPECT_EQ(file.http.max_body_bytes, defaults.http.max_body_bytes);
  EXPECT_EQ(file.http.request_timeout_s, defaults.http.request_timeout_s);
  EXPECT_EQ(file.http.write_timeout_s, defaults.http.write_timeout_s);
  EXPECT_EQ(file.http.client_queue_bytes, defaults.http.client_queue_bytes);
  for (const InputConfig& input : file.inputs) EXPECT_EQ(input.allow_remote, InputConfig{}.allow_remote);
  EXPECT_EQ(file.decoding.sbs_utc_offset_s, defaults.decoding.sbs_utc_offset_s);
  EXPECT_EQ(file.decoding.max_line_bytes, defaults.decoding.max_line_bytes);
  EXPECT_EQ(file.decoding.aircraft_json.max_snapshot_bytes, defaults.decoding.aircraft_json.max_snapshot_bytes);
  EXPECT_EQ(file.decoding.aircraft_json.max_position_age_s, defaults.decoding.aircraft_json.max_position_age_s);
  EXPECT_TRUE(file.decoding.asterix.radars.empty());
  ASSERT_EQ(file.inputs.size(), 2u);
  EXPECT_EQ(file.inputs[0].format, protocol::Format::AsterixDatagram);
  EXPECT_EQ(file.inputs[0].transport, Transport::Udp);
  EXPECT_EQ(file.inputs[1].transport, Transport::TcpServer);
  EXPECT_EQ(file.inputs[1].address, "127.0.0.1:4748");
}

TEST(Config, ZonesThreadsAndCoverage) {
  // Worldwide by default, every core, and no coverage limit.
  const Config defaults = parse_config("");
  EXPECT_EQ(defaults.pipeline.zone_mode, ZoneMode::Worldwide);
  EXPECT_FALSE(defaults.pipeline.coverage_radius_m.has_value());
  EXPECT_EQ(defaults.pipeline.threads, std::max(1u, std::thread::hardware_concurrency()));
  EXPECT_EQ(defaults.pipeline.batch_records, config::kDefaultBatchRecords);
  EXPECT_EQ(defaults.pipeline.prompt_records, config::kDefaultPromptRecords);
  const Config c = parse_config(R"(
[pipeline]
threads = 3
batch_records = 1
prompt_records = 0
[projection]
zones = "single"
coverage_radius_km = 2500
)");
  EXPECT_EQ(c.pipeline.threads, 3u);
  EXPECT_EQ(c.pipeline.batch_records, 1u);
  EXPECT_EQ(c.pipeline.prompt_records, 0u);
  EXPECT_EQ(c.pipeline.zone_mode, ZoneMode::Single);
  EXPECT_EQ(c.pipeline.coverage_radius_m, 2.5e6);
  // Worldwide, a limit may reach the antipode; one plane reaches 3,000 km at most.
  EXPECT_EQ(parse_config("[projection]\ncoverage_radius_km = 12000\n").pipeline.coverage_radius_m, 1.2e7);
  EXPECT_THROW(parse_config("[projection]\nzones = \"single\"\ncoverage_radius_km = 3500\n"), ConfigError);
  EXPECT_THROW(parse_config("[projection]\ncoverage_radius_km = 30000\n"), ConfigError);
  EXPECT_THROW(parse_config("[projection]\nzones = \"tiles\"\n"), ConfigError);
  EXPECT_THROW(parse_config("[pipeline]\nthreads = 300\n"), ConfigError);
  EXPECT_THROW(parse_config("[service]\nsilent_per_address = 0\n"), ConfigError);
  EXPECT_THROW(parse_config("[http]\nsilent_per_address = 0\n"), ConfigError);
  EXPECT_THROW(parse_config("[modbus]\nsilent_per_address = 0\n"), ConfigError);
  EXPECT_EQ(parse_config("[modbus]\nsilent_per_address = 2\n").modbus.silent_per_address, 2);
  EXPECT_EQ(parse_config("[service]\nsilent_per_address = 2\n[http]\nsilent_per_address = 9\n").http.silent_per_address,
            9u);
  EXPECT_THROW(parse_config("[pipeline]\nbatch_records = 0\n"), ConfigError);
  EXPECT_THROW(parse_config("[pipeline]\nprompt_records = -1\n"), ConfigError);
}

TEST(Config, ReadsEverySection) {
  const Config c = parse_config(R"(
[projection]
reference_lat = 41.3
reference_lon = 2.1
coverage_radius_km = 300
[kinetic]
tolerance = 0.001
tolerance_mode = "relative"
horizon_s = 0
renumber_every_s = 120
[probe]
mode = "edges"
horizontal_nm = 3
[[radar]]
sac = 20
sic = 129
lat = 41.300702
lon = 2.102058
height_m = 27
[[input]]
format = "asterix-raw"
transport = "file"
address = "/data/x.ast"
asterix_day = "2023-05-02"
)");
  ASSERT_TRUE(c.pipeline.reference.has_value());
  EXPECT_EQ(c.pipeline.reference->lat_deg, 41.3);
  EXPECT_EQ(c.pipeline.coverage_radius_m, 300000.0);
  EXPECT_EQ(c.pipeline.kinetic.tolerance_mode, kinetic::ToleranceMode::Relative);
  EXPECT_TRUE(std::isinf(c.pipeline.kinetic.horizon_s));
  EXPECT_EQ(c.pipeline.renumber_every_s, 120.0);
  EXPECT_EQ(c.pipeline.probe_mode, probe::ProbeMode::Edges);
  EXPECT_DOUBLE_EQ(c.pipeline.minima.horizontal_m, 5556.0);
  ASSERT_EQ(c.decoding.asterix.radars.size(), 1u);
  EXPECT_EQ(c.decoding.asterix.radars[0].sic, 129);
  ASSERT_EQ(c.inputs.size(), 1u);
  EXPECT_EQ(c.inputs[0].name, "input1");
  EXPECT_EQ(c.inputs[0].format, protocol::Format::AsterixRaw);
  EXPECT_EQ(parse_utc_day(c.inputs[0].asterix_day), 1682985600.0);  // 2023-05-02T00:00:00Z
}

TEST(Config, TheRadarsCentreTheProjectionUnlessAReferenceIsConfigured) {
  // The projection reference is never taken from a single record when the
  // configuration knows better. Two radars: their mean position.
  const Config c = parse_config(R"(
[[radar]]
sac = 20
sic = 129
lat = 41.0
lon = 2.0
[[radar]]
sac = 20
sic = 130
lat = 42.0
lon = 3.0
)");
  ASSERT_TRUE(c.pipeline.reference.has_value());
  EXPECT_DOUBLE_EQ(c.pipeline.reference->lat_deg, 41.5);
  EXPECT_DOUBLE_EQ(c.pipeline.reference->lon_deg, 2.5);
  EXPECT_FALSE(parse_config("").pipeline.reference.has_value());
}

using config_test::expect_error;

TEST(Config, RefusesMistakesWithFileAndLine) {
  expect_error("[tracks]\ntimeout = 30\n", "t.toml:2: [tracks] unknown key \"timeout\"");
  expect_error("[trakcs]\n", "unknown section or key \"trakcs\"");
  expect_error("[probe]\nmode = \"fast\"\n", "mode = \"fast\": expected one of exact, edges, brute");
  expect_error("[alerts]\nconfirm = 0\n", "confirm = 0 is outside [1, 1000]");
  expect_error("[service]\nalert_listen = \"localhost\"\n", "is not HOST:PORT");
  expect_error("[kinetic]\ntolerance = \"big\"\n", "tolerance must be a number");
  expect_error("[kinetic]\nrenumber_every_s = -1\n", "renumber_every_s");
  expect_error("[[input]]\ntransport = \"udp\"\n", "an input needs an address");
  expect_error("[[input]]\nformat = \"asterix-datagram\"\ntransport = \"file\"\naddress = \"x\"\n",
               "asterix-datagram needs transport udp");
  expect_error("[projection]\nreference_lat = 10\n", "go together");
  expect_error("[service\n", "t.toml:1:");
  expect_error("input = 3\n", "input must be written as [[input]] tables");
  expect_error("[eligibility]\nexcluded_mode3a = [\"7700\"]\n", "7700 is an emergency code and always alerts");
  expect_error("[eligibility]\nexcluded_mode3a = [\"7778\"]\n", "four octal digits");
  expect_error("[eligibility]\nexcluded_mode3a = 7777\n", "must be an array of Mode 3/A codes");
  // A record held for a time jump longer than the lateness bound would make every
  // other record too late when it moved the clock (design §4.1).
  expect_error("[tracks]\nmax_lateness_s = 5\nmax_time_jump_s = 20\n",
               "max_time_jump_s = 20 must not exceed max_lateness_s = 5");
  expect_error("[[radar]]\nsac = 20\nsic = 129\nlat = 41.3\nlon = 2.1\n"
               "[[radar]]\nsac = 20\nsic = 129\nlat = 41.5\nlon = 2.3\n",
               "t.toml:6: [radar 2] a radar with sac = 20 and sic = 129 is already configured");
  expect_error("[[input]]\ntransport = \"file\"\naddress = \"x\"\nreconnect_min_s = 2\n",
               "t.toml:4: [input 1] reconnect_min_s is for transport tcp-client and http only");
  expect_error("[[input]]\ntransport = \"udp\"\naddress = \"127.0.0.1:8600\"\npace = true\n",
               "pace is for transport file only");
  expect_error("[[input]]\ntransport = \"tcp-client\"\naddress = \"127.0.0.1:8600\"\nidle_timeout_s = 5\n",
               "idle_timeout_s is for transport tcp-server only");
}

TEST(Config, ReadsTheEligibilityRules) {
  const Config c = parse_config(R"(
[eligibility]
min_ground_speed_kt = 30
lower_limit_ft = 0
excluded_mode3a = ["7777", "0033"]
exclude_coasting = false
level_rate_fpm = 0
)");
  const eligibility::EligibilityConfig& e = c.pipeline.eligibility;
  EXPECT_EQ(e.min_ground_speed_kt, 30.0);
  EXPECT_EQ(e.lower_limit_ft, 0.0);
  EXPECT_EQ(e.excluded_mode3a, (std::vector<std::uint16_t>{07777, 033}));
  EXPECT_FALSE(e.exclude_coasting);
  EXPECT_EQ(e.level_rate_fpm, 0.0);
}

TEST(Config, ReadsTheVerticalIntentAndTurnHypothesisSwitches) {
  const Config c = parse_config(R"(
[probe]
vertical_intent = false
turn_hypothesis = true
turn_min_rate_dps = 2.5
)");
  EXPECT_FALSE(c.pipeline.tracks.intent.enabled);
  EXPECT_TRUE(c.pipeline.turn.enabled);
  EXPECT_EQ(c.pipeline.turn.min_rate_dps, 2.5);
}

TEST(Config, UtcDays) {
  EXPECT_EQ(parse_utc_day("1970-01-01"), 0.0);
  EXPECT_EQ(parse_utc_day("2024-02-29"), 1709164800.0);
  EXPECT_FALSE(parse_utc_day("2024-13-01"));
  EXPECT_FALSE(parse_utc_day("24-01-01"));
  EXPECT_FALSE(parse_utc_day(""));
}

// One rule for every address of every tool: IPv6 only in brackets, port 1-65535, and a
// message that quotes the text.
TEST(Address, OneRuleForEveryTool) {
  EXPECT_EQ(parse_host_port("127.0.0.1:4747"), (HostPort{"127.0.0.1", 4747}));
  EXPECT_EQ(parse_host_port("[::1]:1502"), (HostPort{"::1", 1502}));
  EXPECT_EQ(parse_host_port("radar.example:65535"), (HostPort{"radar.example", 65535}));
  EXPECT_EQ(parse_host_port("[ff02::1]:30003"), (HostPort{"ff02::1", 30003}));
  const std::pair<const char*, const char*> refused[] = {
      {"::1:1502", "brackets"},         {"host:70000", "above 65535"},  {"host:", "empty port"},
      {":4747", "empty host"},          {"localhost", "no ':PORT'"},    {"[::1]", "no ':PORT' after ']'"},
      {"[::1:4747", "no ']'"},          {"host:47a", "not a decimal"},  {"host:0", "port 0"},
      {"127.0.0.1:00000", "port 0"},    {"[]:4747", "empty host"},      {"host:99999999999", "above 65535"},
  };
  for (const auto& [text, why] : refused) {
    std::string error;
    EXPECT_FALSE(parse_host_port(text, &error)) << text;
    EXPECT_NE(error.find(std::string("\"") + text + "\""), std::string::npos) << error;
    EXPECT_NE(error.find(why), std::string::npos) << text << ": " << error;
  }
  EXPECT_EQ(config::to_string(HostPort{"::1", 4747}), "[::1]:4747");
  EXPECT_EQ(config::to_string(HostPort{"10.0.0.1", 8601}), "10.0.0.1:8601");
  for (const char* text : {"[::1]:4747", "10.0.0.1:8601", "radar:1"})
    EXPECT_EQ(config::to_string(config::require_host_port(text)), text);
  EXPECT_THROW(config::require_host_port("nowhere"), ConfigError);
}

TEST(Config, EveryAddressKeyUsesTheOneParser) {
  expect_error("[service]\nalert_listen = \"127.0.0.1:0\"\n", "t.toml:2: [service] alert_listen = \"127.0.0.1:0\"");
  expect_error("[modbus]\nlisten = \"::1:1502\"\n", "brackets");
  expect_error("[cat004]\ndestination = \"10.0.0.1:65536\"\n", "above 65535");
  expect_error("[[input]]\ntransport = \"tcp-client\"\naddress = \"feed\"\n", "t.toml:3: [input 1] address = \"feed\"");
  // A file input's address is a path, colons and all (resolved like every path).
  EXPECT_EQ(parse_config("[[input]]\ntransport = \"file\"\naddress = \"C:/x.ast\"\n").inputs[0].address,
            (std::filesystem::current_path() / "C:/x.ast").string());
}

// Listen addresses (item 6): loopback unless the listener's table says
// allow_remote = true or kewd runs with --listen-any; the error names the listener.
void expect_check_error(const std::string& text, const std::string& needle, bool listen_any = false) {
  try {
    check_config(parse_config(text, "t.toml"), listen_any);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(Config, NatsInputsAndPublisher) {
  const Config c = parse_config(R"(
[nats]
url = "nats://10.0.0.5:4222"
alerts_subject = "ops.alerts"
stream = ""
[[input]]
transport = "nats"
address = "feeds.radar.>"
durable = "kewd_a"
stream = "FEEDS"
[[input]]
transport = "nats"
address = "feeds.adsb"
nats_url = "nats://127.0.0.1:4223"
)");
  EXPECT_EQ(c.nats.alerts_subject, "ops.alerts");
  EXPECT_EQ(c.nats.stream, "");
  ASSERT_EQ(c.inputs.size(), 2u);
  EXPECT_EQ(c.inputs[0].transport, Transport::Nats);
  EXPECT_EQ(c.inputs[0].nats_servers, std::vector<std::string>{"nats://10.0.0.5:4222"});  // [nats] url when the input names none
  EXPECT_EQ(c.inputs[0].durable, "kewd_a");
  EXPECT_EQ(c.inputs[1].nats_servers, std::vector<std::string>{"nats://127.0.0.1:4223"});
  EXPECT_EQ(parse_config("[[input]]\ntransport = \"nats\"\naddress = \"a\"\n").inputs[0].nats_servers,
            std::vector<std::string>{std::string(kDefaultNatsUrl)});
  expect_error("[[input]]\ntransport = \"nats\"\naddress = \"a..b\"\n", "address = \"a..b\" is not a NATS subject");
  expect_error("[[input]]\ntransport = \"nats\"\naddress = \"a.>.b\"\n", "is not a NATS subject");
  expect_error("[nats]\nalerts_subject = \"kew.*\"\n", "is not a NATS subject to publish to");
  expect_error("[nats]\nstream = \"KEW.ALERTS\"\n", "a JetStream name has no '.'");
  expect_error("[nats]\nhot_standby = true\n", "hot_standby needs url");
  expect_error("[nats]\nurl = \"nats://127.0.0.1:4222\"\nhot_standby = true\nstream = \"\"\n", "hot_standby needs stream");
  expect_error("[nats]\nurl = \"nats://127.0.0.1:4222\"\nlease_key = \"a.b\"\n", "is not a key");
  EXPECT_TRUE(parse_config("[nats]\nurl = \"nats://127.0.0.1:4222\"\nhot_standby = true\n").nats.hot_standby);
  expect_error("[[input]]\ntransport = \"nats\"\naddress = \"a\"\nstream = \"S\"\n", "give durable too");
  expect_error("[[input]]\ntransport = \"udp\"\naddress = \"127.0.0.1:8600\"\ndurable = \"d\"\n",
               "durable is for transport nats only");
}

TEST(NatsSubject, TokensAndWildcards) {
  EXPECT_TRUE(config::valid_nats_subject("kew.alerts.N49_5E013_3", false));
  EXPECT_TRUE(config::valid_nats_subject("kew.*.x", true));
  EXPECT_TRUE(config::valid_nats_subject("kew.>", true));
  EXPECT_FALSE(config::valid_nats_subject("kew.>", false));
  EXPECT_FALSE(config::valid_nats_subject("kew.a*", true));
  EXPECT_FALSE(config::valid_nats_subject("kew. a", false));
  EXPECT_FALSE(config::valid_nats_subject(".kew", false));
  EXPECT_FALSE(config::valid_nats_subject("kew.", false));
  EXPECT_FALSE(config::valid_nats_subject("", true));
  EXPECT_EQ(config::nats_subject_token("N40.5E004.5"), "N40_5E004_5");
  EXPECT_EQ(config::nats_subject_token("S04.5W177.5"), "S04_5W177_5");
  EXPECT_EQ(config::nats_subject_token("a/b+c#d e"), "a_b_c_d_e");  // MQTT topic levels too
  EXPECT_EQ(config::nats_subject_token(""), "_");
}

TEST(Config, InputNamesAreDistinct) {
  // Input names label the metrics, ?STATS and the log: two inputs of one name would be
  // counted as one. A default name (inputN) taken by an explicit one counts too.
  expect_error("[[input]]\nname = \"radar\"\naddress = \"127.0.0.1:8600\"\ntransport = \"udp\"\n"
               "[[input]]\nname = \"radar\"\naddress = \"127.0.0.1:8601\"\ntransport = \"udp\"\n",
               "[input 2] name \"radar\" is the name of input 1 already");
  expect_error("[[input]]\nname = \"input2\"\naddress = \"127.0.0.1:8600\"\ntransport = \"udp\"\n"
               "[[input]]\naddress = \"127.0.0.1:8601\"\ntransport = \"udp\"\n",
               "[input 2] name \"input2\" is the name of input 1 already");
  EXPECT_NO_THROW(parse_config("[[input]]\naddress = \"127.0.0.1:8600\"\ntransport = \"udp\"\n"
                               "[[input]]\naddress = \"127.0.0.1:8601\"\ntransport = \"udp\"\n"));
}

TEST(ConfigChecks, ListenersBindLoopbackUnlessAllowed) {
  expect_check_error("[service]\nalert_listen = \"0.0.0.0:4747\"\n",
                     "t.toml: [service] alert_listen = \"0.0.0.0:4747\" listens on every interface");
  expect_check_error("[service]\nalert_listen = \"[::]:4747\"\n", "alert_listen = \"[::]:4747\" listens on every");
  expect_check_error("[http]\nlisten = \"0.0.0.0:8747\"\n",
                     "t.toml: [http] listen = \"0.0.0.0:8747\" listens on every interface");
  expect_check_error("[http]\nlisten = \"127.0.0.1:4747\"\n", "[http] listen = \"127.0.0.1:4747\" uses TCP port 4747");
  expect_check_error("[modbus]\nenabled = true\nlisten = \"192.0.2.1:1502\"\n",
                     "[modbus] listen = \"192.0.2.1:1502\" is not a loopback address");
  expect_check_error("[[input]]\ntransport = \"udp\"\naddress = \"0.0.0.0:8600\"\n",
                     "[input 1] address = \"0.0.0.0:8600\" listens on every interface");
  expect_check_error("[[input]]\ntransport = \"udp\"\naddress = \"239.1.2.3:8600\"\n",
                     "[input 1] address = \"239.1.2.3:8600\" is not a loopback address");
  expect_check_error("[[input]]\ntransport = \"tcp-server\"\naddress = \"radar.example:4748\"\n",
                     "[input 1] address = \"radar.example:4748\" is not a loopback address");
  expect_check_error("[[input]]\ntransport = \"tcp-server\"\naddress = \"0.0.0.0:4748\"\nallow_remote = false\n",
                     "allow_remote = true");
  // Allowed: by the listener's own table, or by --listen-any for every listener.
  const char* remote = R"(
[service]
alert_listen = "0.0.0.0:4747"
allow_remote = true
[modbus]
enabled = true
listen = "[::]:1502"
allow_remote = true
[[input]]
transport = "udp"
address = "239.1.2.3:8600"
allow_remote = true
)";
  EXPECT_NO_THROW(check_config(parse_config(remote), false));
  EXPECT_NO_THROW(check_config(parse_config("[service]\nalert_listen = \"0.0.0.0:4747\"\n"), true));
  // Loopback in every spelling; listeners that are not enabled, and tcp-client, are not listeners.
  EXPECT_NO_THROW(check_config(parse_config(R"(
[service]
alert_listen = "localhost:4747"
[modbus]
listen = "0.0.0.0:1502"
[[input]]
transport = "tcp-server"
address = "[::1]:4748"
[[input]]
transport = "udp"
address = "127.1.2.3:8600"
[[input]]
transport = "tcp-client"
address = "192.0.2.1:30003"
)"), false));
  expect_error("[[input]]\ntransport = \"tcp-client\"\naddress = \"192.0.2.1:1\"\nallow_remote = true\n",
               "allow_remote is for inputs that listen");
  // The built-in configuration passes.
  EXPECT_NO_THROW(check_config(Config{}, false));
  EXPECT_NO_THROW(check_config(load_config(std::string(KEW_DEPLOY_DIR) + "/kew.toml"), false));
}

// kewd --replay (design §5.6): the file's shared tables and [service] limits stay; its
// inputs are replaced by one paced file input; nothing reaches a live output or a file;
// every listener must be loopback, whatever the file allowed.
TEST(ConfigChecks, ReplayKeepsTheSharedTablesAndTurnsOutputsOff) {
  Config c = parse_config(R"(
[service]
alert_listen = "0.0.0.0:4747"
allow_remote = true
alert_log = "/var/log/kew/alerts.jsonl"
record_file = "/var/log/kew/records.ndjson"
state_directory = "/var/lib/kew"
max_subscribers = 7
[alerts]
confirm = 3
[cat004]
enabled = true
[modbus]
enabled = true
listen = "0.0.0.0:1502"
allow_remote = true
[[input]]
transport = "udp"
address = "239.1.2.3:8600"
allow_remote = true
[[input]]
transport = "tcp-client"
address = "192.0.2.1:30003"
[nats]
url = "nats://192.0.2.7:4222"
hot_standby = true
)", "site.toml");
  ReplaySettings replay;
  replay.file = "incident.ast";
  replay.format = protocol::Format::AsterixRaw;
  replay.speed = 4.0;
  apply_replay(c, replay);
  ASSERT_EQ(c.inputs.size(), 1u);
  EXPECT_EQ(c.inputs[0].name, "replay");
  EXPECT_EQ(c.inputs[0].transport, Transport::File);
  EXPECT_EQ(c.inputs[0].format, protocol::Format::AsterixRaw);
  EXPECT_EQ(c.inputs[0].address, std::filesystem::absolute("incident.ast").string());
  EXPECT_TRUE(c.inputs[0].pace);
  EXPECT_EQ(c.inputs[0].speed, 4.0);
  EXPECT_EQ(c.pipeline.alerts.confirm, 3);
  EXPECT_EQ(c.service.max_subscribers, 7u);
  EXPECT_TRUE(c.service.alert_log.empty());
  EXPECT_TRUE(c.service.record_file.empty());
  EXPECT_TRUE(state_directory(c.service).empty());
  EXPECT_FALSE(c.cat004.enabled);
  EXPECT_FALSE(c.modbus.enabled);
  EXPECT_TRUE(c.nats.servers.empty());  // a replay never reaches the production bus
  EXPECT_FALSE(c.nats.hot_standby);
  EXPECT_THROW(check_config(c, false), ConfigError);  // the file's 0.0.0.0 is no longer allowed
  replay.alert_listen = "127.0.0.1:4848";
  replay.speed = 0.0;  // --max-speed
  replay.alert_log = "replay.jsonl";
  apply_replay(c, replay);
  EXPECT_FALSE(c.inputs[0].pace);
  EXPECT_EQ(c.service.alert_listen, "127.0.0.1:4848");
  EXPECT_EQ(c.service.alert_log, std::filesystem::absolute("replay.jsonl").string());
  EXPECT_NO_THROW(check_config(c, false));
}

TEST(ConfigChecks, ListeningPortsAreDistinctPerProtocolAndFamily) {
  expect_check_error("[service]\nalert_listen = \"127.0.0.1:4748\"\n[[input]]\ntransport = \"tcp-server\"\n"
                     "address = \"127.0.0.1:4748\"\n",
                     "[input 1] address = \"127.0.0.1:4748\" uses TCP port 4748 (IPv4), as [service] alert_listen = "
                     "\"127.0.0.1:4748\" does");
  expect_check_error("[[input]]\ntransport = \"udp\"\naddress = \"127.0.0.1:8600\"\n"
                     "[[input]]\ntransport = \"udp\"\naddress = \"localhost:8600\"\n",
                     "[input 2] address = \"localhost:8600\" uses UDP port 8600 (IPv4), as [input 1]");
  expect_check_error("[modbus]\nenabled = true\nlisten = \"127.0.0.1:4747\"\n", "uses TCP port 4747");
  // TCP and UDP ports are distinct; so are IPv4 and IPv6; a disabled Modbus listens nowhere.
  EXPECT_NO_THROW(check_config(parse_config(R"(
[modbus]
listen = "127.0.0.1:4747"
[[input]]
transport = "udp"
address = "127.0.0.1:4747"
[[input]]
transport = "tcp-server"
address = "[::1]:4747"
)"), false));
}

TEST(ConfigChecks, OutputFilesMustBeWritable) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("kew-config-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "logs");
  std::ofstream(dir / "plain") << "x";
  const std::string d = dir.string();
  expect_check_error("[service]\nalert_log = \"" + d + "/logs\"\n",
                     "[service] alert_log = \"" + d + "/logs\" is a directory");
  expect_check_error("[service]\nrecord_file = \"" + d + "/missing/r.ndjson\"\n",
                     "[service] record_file = \"" + d + "/missing/r.ndjson\" cannot be created: its directory " + d +
                         "/missing does not exist");
  expect_check_error("[service]\nalert_log = \"" + d + "/plain/a.jsonl\"\n", d + "/plain is not a directory");
  expect_check_error("[service]\nalert_log = \"" + d + "/a.jsonl\"\nrecord_file = \"" + d + "/logs/../a.jsonl\"\n",
                     "is the alert log too");
  EXPECT_NO_THROW(check_config(parse_config("[service]\nalert_log = \"" + d + "/logs/a.jsonl\"\nrecord_file = \"" +
                                            d + "/plain\"\n"),
                               false));
  std::filesystem::remove_all(dir);
}

TEST(ConfigChecks, StateDirectoryDefaultsToTheAlertLogsAndMustBeCreatable) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("kew-state-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "logs");
  std::ofstream(dir / "plain") << "x";
  const std::string d = dir.string();
  const Config logged = parse_config("[service]\nalert_log = \"" + d + "/logs/a.jsonl\"\n");
  EXPECT_EQ(logged.service.alert_log_sync, AlertLogSync::Interval);
  EXPECT_EQ(state_directory(logged.service), d + "/logs");
  EXPECT_EQ(state_directory(Config{}.service), "");  // no alert log, no state: numbering from 1
  const Config chosen = parse_config("[service]\nstate_directory = \"" + d + "/state\"\nalert_log_sync = \"every\"\n");
  EXPECT_EQ(state_directory(chosen.service), d + "/state");
  EXPECT_EQ(chosen.service.alert_log_sync, AlertLogSync::Every);
  EXPECT_NO_THROW(check_config(chosen, false));  // created at start
  expect_check_error("[service]\nstate_directory = \"" + d + "/plain\"\n",
                     "[service] state_directory = \"" + d + "/plain\" is not a directory");
  expect_check_error("[service]\nstate_directory = \"" + d + "/missing/state\"\n",
                     "cannot be created: " + d + "/missing does not exist");
  EXPECT_THROW(parse_config("[service]\nalert_log_sync = \"sometimes\"\n"), config::ConfigError);
  std::filesystem::remove_all(dir);
}

// Relative paths are resolved against the working directory kewd starts in (as the
// alert log always was) and kept absolute, so "../" is resolved where it is read.
TEST(Config, RelativePathsAreResolvedAgainstTheWorkingDirectory) {
  const std::filesystem::path cwd = std::filesystem::current_path();
  const Config c = parse_config(R"(
[service]
alert_log = "logs/../alerts.jsonl"
record_file = "../records.ndjson"
[[input]]
transport = "file"
address = "./data/x.ast"
)");
  EXPECT_EQ(c.service.alert_log, (cwd / "alerts.jsonl").string());
  EXPECT_EQ(c.service.record_file, (cwd.parent_path() / "records.ndjson").string());
  EXPECT_EQ(c.inputs[0].address, (cwd / "data/x.ast").string());
  EXPECT_EQ(parse_config("[service]\nalert_log = \"/var/log/kew/a.jsonl\"\n").service.alert_log,
            "/var/log/kew/a.jsonl");
  EXPECT_EQ(parse_config("[service]\nalert_log = \"\"\n").service.alert_log, "");
}

// [modbus] acknowledge_from (item 7): addresses, kept in canonical form.
TEST(Config, AcknowledgeFromIsAListOfAddresses) {
  const Config c = parse_config("[modbus]\nacknowledge_from = [\"127.0.0.1\", \"::0001\", \"::ffff:10.0.0.7\"]\n");
  EXPECT_EQ(c.modbus.acknowledge_from, (std::vector<std::string>{"127.0.0.1", "::1", "10.0.0.7"}));
  expect_error("[modbus]\nacknowledge_from = [\"127.0.0.1:502\"]\n", "without port or brackets");
  expect_error("[modbus]\nacknowledge_from = [\"panel.example\"]\n", "t.toml:2: [modbus] acknowledge_from");
  expect_error("[modbus]\nacknowledge_from = \"127.0.0.1\"\n", "must be an array of IP addresses");
}

TEST(Address, ListenScopes) {
  using config::ListenScope;
  for (const char* host : {"127.0.0.1", "127.255.0.9", "::1", "localhost", "::ffff:127.0.0.1"})
    EXPECT_EQ(config::listen_scope(host), ListenScope::Loopback) << host;
  for (const char* host : {"0.0.0.0", "::", "0:0::0"}) EXPECT_EQ(config::listen_scope(host), ListenScope::Wildcard) << host;
  for (const char* host : {"192.0.2.1", "239.1.2.3", "ff02::1", "radar.example", "128.0.0.1"})
    EXPECT_EQ(config::listen_scope(host), ListenScope::Other) << host;
}

// Choices are checked against the enum's name table, and the error lists that table.
TEST(Config, ChoicesListTheirNameTable) {
  expect_error("[kinetic]\ntolerance_mode = \"metres\"\n", "expected one of absolute, relative");
  expect_error("[[input]]\ntransport = \"tcp\"\naddress = \"a:1\"\n",
               "expected one of udp, tcp-client, tcp-server, file");
  expect_error("[[input]]\nformat = \"json\"\naddress = \"a:1\"\n",
               "expected one of auto, ndjson, sbs, opensky-csv, opensky-json, readsb, aircraft-json, opensky-rest, "
               "readsb-trace, asterix-raw, asterix-ff, asterix-pcap, asterix-datagram");
  expect_error("[service]\nlog_level = \"warning\"\n", "expected one of trace, debug, info, warn, error, critical, off");
  EXPECT_EQ(parse_config("[service]\nlog_level = \"warn\"\n").service.log_level, LogLevel::Warn);
  EXPECT_EQ(kTransportNames.parse(to_string(Transport::TcpServer)), Transport::TcpServer);
}

// kew-replay and the other tools read the shared tables of a kewd file, identically, and
// accept kewd's own tables without reading them.
TEST(SharedConfig, ReadsAKewdFileAsKewdDoes) {
  const std::string path = std::string(KEW_DEPLOY_DIR) + "/kew.toml";
  const config::SharedConfig shared = config::load_shared_config(path);
  const Config daemon = load_config(path);
  EXPECT_EQ(shared.pipeline.coverage_radius_m, daemon.pipeline.coverage_radius_m);
  EXPECT_EQ(shared.pipeline.probe_mode, daemon.pipeline.probe_mode);
  EXPECT_EQ(shared.decoding.max_line_bytes, daemon.decoding.max_line_bytes);
  const char* text = R"(
[service]
whatever_kewd_reads = 1
[[input]]
not_checked_here = true
[probe]
mode = "brute"
[[radar]]
sac = 1
sic = 2
lat = 50
lon = 8
)";
  const config::SharedConfig c = config::read_shared_config(config::Document::parse(text, "k.toml"));
  EXPECT_EQ(c.pipeline.probe_mode, probe::ProbeMode::Brute);
  ASSERT_EQ(c.decoding.asterix.radars.size(), 1u);
  EXPECT_EQ(c.decoding.asterix.radars[0].sic, 2);
  try {
    config::read_shared_config(config::Document::parse("[probe]\nmode = \"exact\"\n[servcie]\n", "k.toml"));
    ADD_FAILURE() << "an unknown table was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("k.toml:3: unknown section or key \"servcie\""), std::string::npos) << e.what();
  }
}

// A configuration is read with a size cap: a file over kMaxConfigBytes or a
// directory is refused with a message naming it, and nothing past the cap is read
// (`/dev/zero` and pipes: tests/e2e test_kewd.InputFraming.test_config_that_never_ends_is_refused).
TEST(Config, FilesAreReadWithASizeCap) {
  const auto dir = std::filesystem::temp_directory_path() / ("kew-config-cap-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string at_cap = (dir / "at-cap.toml").string();
  const std::string over_cap = (dir / "over-cap.toml").string();
  {
    // A valid file of comments exactly at the cap, and one a byte over.
    const std::string head = "[service]\n";
    std::ofstream(at_cap) << head << '#' << std::string(config::kMaxConfigBytes - head.size() - 2, 'x') << '\n';
    std::ofstream(over_cap) << head << '#' << std::string(config::kMaxConfigBytes - head.size() - 1, 'x') << '\n';
  }
  ASSERT_EQ(std::filesystem::file_size(at_cap), config::kMaxConfigBytes);
  EXPECT_NO_THROW(load_config(at_cap));
  const auto expect_refused = [](const std::string& path, const std::string& why) {
    try {
      load_config(path);
      ADD_FAILURE() << path << " was accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(path + ": " + why), std::string::npos) << e.what();
    }
  };
  expect_refused(over_cap, "larger than 1048576 bytes, refused");
  expect_refused(dir.string(), "not a regular file (a directory), refused");
  expect_refused((dir / "absent.toml").string(), "cannot open");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kew::daemon
