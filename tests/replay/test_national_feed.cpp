// A national CAT062 feed 4,000 km long (design §4.9): with the default configuration
// nothing is refused for its position and no loss of separation goes unalerted. One
// plane (zones = "single", kew's only projection before zones) refuses the far ends.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "asterix_writer.hpp"
#include "kew/config/shared_config.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "kew/protocol/asterix/uap.hpp"
#include "kew/replay/evaluation.hpp"
#include "kew/replay/explanation.hpp"
#include "kew/replay/traffic_generator.hpp"
#include "kew/replay/truth.hpp"

namespace kew {
namespace {

using protocol::asterix_writer::Bytes;
using protocol::asterix_writer::put;
using protocol::asterix_writer::quantize;

constexpr double kKnotToMps = 1852.0 / 3600.0;

double day_start(double t) { return std::floor(t / 86400.0) * 86400.0; }

// One CAT062 record of SDPS 25/100: time, WGS-84 position, measured FL, track number,
// Cartesian velocity and rate of climb, as an SDPS sends a system track.
Bytes cat062_record(const TrackReport& r, std::uint16_t track_number) {
  using namespace protocol::asterix::cat062;
  protocol::asterix_writer::RecordWriter w;
  w.set(kDataSource, {25, 100});
  Bytes tod;
  put(tod, static_cast<std::uint64_t>(quantize(r.t - day_start(r.t), 1.0 / 128.0)), 3);
  w.set(kTimeOfTrack, tod);
  Bytes position;
  put(position, static_cast<std::uint32_t>(quantize(r.lat_deg, 180.0 / 33554432.0)), 4);
  put(position, static_cast<std::uint32_t>(quantize(r.lon_deg, 180.0 / 33554432.0)), 4);
  w.set(kPositionWgs84, position);
  const double speed = *r.gs_kt * kKnotToMps;
  const double track = *r.trk_deg * M_PI / 180.0;
  Bytes velocity;
  put(velocity, static_cast<std::uint16_t>(quantize(speed * std::sin(track), 0.25)), 2);
  put(velocity, static_cast<std::uint16_t>(quantize(speed * std::cos(track), 0.25)), 2);
  w.set(kVelocity, velocity);
  Bytes number;
  put(number, track_number, 2);
  w.set(kTrackNumber, number);
  Bytes level;
  put(level, static_cast<std::uint16_t>(quantize(r.alt_ft / 100.0, 0.25)), 2);
  w.set(kMeasuredFl, level);
  Bytes climb;
  put(climb, static_cast<std::uint16_t>(quantize(r.vr_fpm.value_or(0.0), 6.25)), 2);
  w.set(kRateOfClimb, climb);
  return w.bytes();
}

struct Feed {
  std::vector<TrackReport> records;  // decoded from the file, in file order
  double start = 0.0;
};

constexpr double kPeriod_s = 4.0;  // the feed's radar period

// Generated airways across a disk of 4,000 km, written to one CAT062 file and read back.
Feed national_feed(const std::filesystem::path& file) {
  replay::GeneratorConfig traffic;
  traffic.scenario = replay::Scenario::Mixed;
  traffic.aircraft = 2500;
  traffic.duration_s = 150.0;
  traffic.period_s = kPeriod_s;
  traffic.seed = 4000;
  traffic.center_lat_deg = 47.0;
  traffic.center_lon_deg = 15.0;
  traffic.radius_km = 2000.0;
  replay::TrafficGenerator generator(traffic);
  std::map<std::string, std::uint16_t> numbers;
  std::vector<Bytes> block;
  Bytes stream;
  const auto flush = [&] {
    if (block.empty()) return;
    const Bytes b = protocol::asterix_writer::data_block(62, block);
    stream.insert(stream.end(), b.begin(), b.end());
    block.clear();
  };
  for (TrackReport r; generator.next(r);) {
    const auto [it, added] = numbers.try_emplace(r.id, static_cast<std::uint16_t>(numbers.size() + 1));
    block.push_back(cat062_record(r, it->second));
    if (block.size() == 20) flush();
  }
  flush();
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(stream.data()), static_cast<std::streamsize>(stream.size()));
  }
  Feed feed;
  feed.start = traffic.start_time;
  std::ifstream in(file, std::ios::binary);
  const Bytes bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  protocol::AsterixOptions options;
  options.day_start_utc_s = day_start(traffic.start_time);
  auto decoder = protocol::make_asterix_decoder(protocol::AsterixFraming::RawBlocks, options);
  const protocol::ReportSink sink = [&](const TrackReport& r) { feed.records.push_back(r); };
  decoder->feed(std::as_bytes(std::span<const std::uint8_t>(bytes)), sink);
  decoder->finish(sink);
  EXPECT_EQ(decoder->rejections().total(), 0u);
  return feed;
}

struct FeedRun {
  std::uint64_t outside_coverage = 0, accepted = 0;
  replay::EvaluationFigures figures;
  std::size_t zones_max = 0;
  /// The missed losses, explained (kew-eval --explain), and when each began (UTC s).
  std::vector<replay::LossExplanation> missed;
  std::vector<double> missed_start;
};

FeedRun replay_feed(const Feed& feed, const PipelineConfig& config) {
  Pipeline pipeline(config);
  replay::AlertCollector alerts;
  pipeline.set_alert_sink([&](const AlertEvent& e) { alerts.add(e); });
  FeedRun run;
  for (const TrackReport& r : feed.records) {
    pipeline.process(r);
    run.zones_max = std::max(run.zones_max, pipeline.zone_count());
  }
  pipeline.end_of_input();
  run.outside_coverage = pipeline.rejections().count("outside_coverage");
  run.accepted = pipeline.statistics().accepted;
  // The truth stands above the run's aerodromes, as kew-eval's above its configuration's.
  const replay::Truth truth(feed.records, *config.eligibility.aerodromes);
  replay::ScoringParameters parameters;
  parameters.lookahead_s = config.minima.lookahead_s;
  parameters.confirm = config.alerts.confirm;
  const replay::Evaluation evaluation = replay::evaluate(truth, alerts.alerts(), parameters);
  run.figures = evaluation.figures;
  std::vector<std::size_t> missed;
  for (std::size_t k = 0; k < evaluation.losses.size(); ++k)
    if (evaluation.losses[k].outcome == replay::LossOutcome::Missed) missed.push_back(k);
  run.missed = replay::explain_losses(truth, evaluation, alerts.alerts(), config, feed.records, missed);
  for (const replay::LossExplanation& e : run.missed)
    run.missed_start.push_back(static_cast<double>(truth.loss_events()[e.loss].start_s));
  return run;
}

TEST(NationalFeed, FourThousandKilometresServedWithNoRefusalAndNoLossMissedForCoverage) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("kew-national-" + std::to_string(::getpid()) + ".ast");
  const Feed feed = national_feed(file);
  std::filesystem::remove(file);
  ASSERT_GT(feed.records.size(), 80000u);

  const FeedRun zoned = replay_feed(feed, config::default_shared_config().pipeline);  // the defaults
  EXPECT_EQ(zoned.outside_coverage, 0u);
  EXPECT_EQ(zoned.accepted, feed.records.size());
  EXPECT_GE(zoned.zones_max, 8u);
  EXPECT_GT(zoned.figures.loss_events, 10u) << "the feed must hold losses of separation";
  // No loss is missed for want of coverage: a loss kew misses is one whose aircraft
  // changed their flight within a radar period of it (the conflict test saw none
  // before), which no look-ahead can warn of.
  for (std::size_t i = 0; i < zoned.missed.size(); ++i) {
    const replay::LossExplanation& e = zoned.missed[i];
    EXPECT_EQ(e.stage, PairStage::ProbeClear) << e.reason;
    ASSERT_FALSE(e.spans.empty());
    const replay::StageSpan& clear = *std::find_if(e.spans.rbegin(), e.spans.rend(), [](const replay::StageSpan& s) {
      return s.stage == PairStage::ProbeClear;
    });
    EXPECT_GE(clear.last_t, zoned.missed_start[i] - kPeriod_s) << e.reason;
  }
  EXPECT_LE(zoned.figures.missed, zoned.figures.loss_events / 50) << "at most 2 % of the losses";
  RecordProperty("loss_events", static_cast<int>(zoned.figures.loss_events));

  // One plane of 1,500 km, as kew had before zones: the far ends are refused and their
  // losses go unalerted.
  PipelineConfig single = config::default_shared_config().pipeline;
  single.zone_mode = ZoneMode::Single;
  const FeedRun one_plane = replay_feed(feed, single);
  EXPECT_GT(one_plane.outside_coverage, 1000u);
  EXPECT_GT(one_plane.figures.missed, zoned.figures.missed);
  EXPECT_TRUE(std::any_of(one_plane.missed.begin(), one_plane.missed.end(), [](const replay::LossExplanation& e) {
    return e.stage == PairStage::NoTrack || e.stage == PairStage::RecordRefused;
  })) << "the far ends' losses go unalerted because their records are refused";
}

}  // namespace
}  // namespace kew
