// A checkpoint of the whole pipeline (design §5.9): taken between records of generated
// traffic (worldwide zones and one plane, with missed updates, late and noisy records,
// acknowledgements and timeouts) and restored into a fresh pipeline, the run goes on with
// the same alert events, every field, and ends with the same tracks, counts and refusals;
// the restored pipeline's own checkpoint is the same bytes; every truncation is refused.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/replay/traffic_generator.hpp"
#include "kew/util/checkpoint_io.hpp"

namespace kew {
namespace {

struct Case {
  const char* name;
  ZoneMode mode;
  replay::Scenario scenario;
  double lat_deg, lon_deg;
  std::size_t threads, batch;
};

std::vector<TrackReport> feed_of(const Case& c, std::uint32_t seed) {
  replay::GeneratorConfig traffic;
  traffic.scenario = c.scenario;
  traffic.aircraft = 300;
  traffic.duration_s = 150.0;
  traffic.seed = seed;
  traffic.missed_update_probability = 0.1;
  traffic.center_lat_deg = c.lat_deg;
  traffic.center_lon_deg = c.lon_deg;
  traffic.radius_km = 150.0;
  replay::TrafficGenerator generator(traffic);
  std::vector<TrackReport> feed;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (TrackReport r; generator.next(r);) {
    // Late records, and a record an hour ahead now and then (held by the time guard).
    if (unit(rng) < 0.01) r.t -= 10.0;
    if (unit(rng) < 0.001) r.t += 3600.0;
    feed.push_back(r);
  }
  return feed;
}

PipelineConfig config_of(const Case& c) {
  PipelineConfig config;
  config.zone_mode = c.mode;
  config.threads = c.threads;
  config.batch_records = c.batch;
  config.tracks.track_timeout_s = 20.0;  // tracks of missed updates time out, slots are reused
  return config;
}

// The events a pipeline delivers, as the stream writes them, with the figures exactly.
struct Recorder {
  std::vector<std::string> lines;
  void operator()(const AlertEvent& e) {
    std::string line;
    protocol::append_alert_json(line, e, e.seq);
    char exact[160];
    std::snprintf(exact, sizeof exact, " %a %a %a %a %a %d", e.t, e.t_los_s, e.t_cpa_s, e.cpa_h_m, e.sep_h_m,
                  e.acknowledged ? 1 : 0);
    lines.push_back(line + exact);
  }
};

// A daemon's read of 50 records ends after record i: the batch runs, an operator may act.
// (A checkpoint flushes too, between reads: events do not depend on where batches end.)
bool read_ends(std::size_t i) { return (i + 1) % 50 == 0; }

// Acknowledges every third alert at its opening, as an operator might, in any pipeline.
void acknowledge_some(Pipeline& p, const std::vector<std::string>& lines, std::size_t& seen) {
  for (; seen < lines.size(); ++seen)
    if (seen % 3 == 0 && lines[seen].find("\"state\":\"new\"") != std::string::npos) {
      const std::size_t at = lines[seen].find("\"id\":\"") + 6;
      p.alerts().acknowledge(lines[seen].substr(at, lines[seen].find('"', at) - at));
    }
}

std::string tracks_of(const Pipeline& p) {
  std::string out;
  const track::TrackTable& table = p.tracks();
  for (track::TrackSlot slot = 0; slot < table.slot_end(); ++slot) {
    const track::Track& t = table[slot];
    if (!t.in_use) continue;
    char line[200];
    std::snprintf(line, sizeof line, "%u %s %s %u %a %a %a %d\n", slot, t.source.c_str(), t.id.c_str(), t.number,
                  t.t, t.lat_deg, t.lon_deg, t.in_engine ? 1 : 0);
    out += line;
  }
  return out;
}

std::string statistics_of(const Pipeline& p) {
  const PipelineStatistics s = p.statistics();
  return std::to_string(s.records) + " " + std::to_string(s.accepted) + " " + std::to_string(s.tracks_dropped) +
         " " + std::to_string(s.runs_restarted) + " " + std::to_string(s.probes) + " " +
         std::to_string(p.rejections().total()) + " " + std::to_string(p.suppressed().total()) + " " +
         std::to_string(p.live_tracks()) + " " + std::to_string(p.alerts().active_count());
}

class PipelineCheckpoint : public ::testing::TestWithParam<Case> {};

TEST_P(PipelineCheckpoint, ARestoredPipelineContinuesEventForEvent) {
  const Case c = GetParam();
  for (const std::uint32_t seed : {20261206u, 7u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::vector<TrackReport> feed = feed_of(c, seed);
    const PipelineConfig config = config_of(c);

    // The run without a checkpoint.
    Recorder whole;
    std::size_t acknowledged = 0;
    {
      Pipeline p(config);
      p.set_alert_sink(std::ref(whole));
      for (std::size_t i = 0; i < feed.size(); ++i) {
        p.process(feed[i]);
        if (read_ends(i)) {
          p.flush();
          acknowledge_some(p, whole.lines, acknowledged);
        }
      }
      p.end_of_input();
    }
    ASSERT_GT(whole.lines.size(), 20u) << "the traffic must raise alerts";

    // Checkpoints at random records, each restored into a fresh pipeline that goes on.
    std::mt19937 rng(seed);
    std::size_t restored_runs = 0, held_refusals = 0;
    for (int trial = 0; trial < 4; ++trial) {
      std::size_t k = std::uniform_int_distribution<std::size_t>(feed.size() / 10, feed.size() - 1)(rng);
      Recorder before;
      std::size_t seen = 0;
      Pipeline first(config);
      first.set_alert_sink(std::ref(before));
      std::optional<std::string> bytes;
      for (std::size_t i = 0; i < feed.size(); ++i) {
        first.process(feed[i]);
        if (read_ends(i)) {
          first.flush();
          acknowledge_some(first, before.lines, seen);
        }
        if (i + 1 < k) continue;
        bytes = first.checkpoint();
        if (bytes) {
          k = i + 1;
          break;
        }
        ++held_refusals;
      }
      ASSERT_TRUE(bytes) << "no record after " << k << " could be checkpointed";
      Recorder after = before;
      Pipeline second(config);
      second.set_alert_sink(std::ref(after));
      second.restore(*bytes);
      EXPECT_TRUE(second.is_valid());
      // (Compared as a truth value: a failure would print megabytes.)
      ASSERT_TRUE(second.checkpoint() == bytes) << "a restored pipeline's checkpoint is the bytes it came from";
      EXPECT_EQ(tracks_of(second), tracks_of(first));
      EXPECT_EQ(statistics_of(second), statistics_of(first));
      for (std::size_t i = k; i < feed.size(); ++i) {
        second.process(feed[i]);
        if (read_ends(i)) {
          second.flush();
          acknowledge_some(second, after.lines, seen);
        }
      }
      second.end_of_input();
      ASSERT_EQ(after.lines.size(), whole.lines.size()) << "checkpoint after record " << k;
      for (std::size_t i = 0; i < whole.lines.size(); ++i) ASSERT_EQ(after.lines[i], whole.lines[i]) << "event " << i;
      EXPECT_TRUE(second.is_valid());
      ++restored_runs;

      if (trial == 0) {
        // Every truncation is refused, and so is a checkpoint of another zone mode.
        for (std::size_t cut = 0; cut < bytes->size(); cut += 1 + bytes->size() / 97) {
          Pipeline fresh(config);
          EXPECT_THROW(fresh.restore(std::string_view(*bytes).substr(0, cut)), util::CheckpointError) << cut;
        }
        PipelineConfig other = config;
        other.zone_mode = config.zone_mode == ZoneMode::Single ? ZoneMode::Worldwide : ZoneMode::Single;
        Pipeline elsewhere(other);
        EXPECT_THROW(elsewhere.restore(*bytes), util::CheckpointError);
        // Only a fresh pipeline takes a checkpoint.
        EXPECT_THROW(first.restore(*bytes), std::logic_error);
      }
    }
    EXPECT_EQ(restored_runs, 4u);
    RecordProperty("held_refusals", static_cast<int>(held_refusals));
  }
}

INSTANTIATE_TEST_SUITE_P(
    Traffic, PipelineCheckpoint,
    ::testing::Values(Case{"WorldwideMixed", ZoneMode::Worldwide, replay::Scenario::Mixed, 49.0, 11.0, 1, 1},
                      Case{"WorldwideAcrossZones", ZoneMode::Worldwide, replay::Scenario::Airways, 0.0, 0.0, 2, 64},
                      Case{"SinglePlaneTma", ZoneMode::Single, replay::Scenario::Tma, 52.0, 4.5, 1, 16}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace kew
