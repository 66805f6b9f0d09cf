// A checkpoint of the track table (design §5.9): saved at any record of a random feed and
// restored into a fresh table, the feed goes on with the same verdicts, the same slots
// and numbers, the same tracks bit for bit and the same expiries in the same order; the
// restored table's own checkpoint is the same bytes; every truncation is refused.
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kew/track/track_table.hpp"

namespace kew::track {
namespace {

// Records of 40 aircraft from two sources over a few minutes: some late, some out of
// range, some with optional fields missing or implausible, some ending their tracks, and
// gaps long enough for tracks to time out and their slots to be reused.
std::vector<TrackReport> random_feed(std::uint32_t seed, std::size_t count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<TrackReport> feed;
  double t = 1.7e9;
  for (std::size_t i = 0; i < count; ++i) {
    TrackReport r;
    t += unit(rng) < 0.02 ? 40.0 : std::floor(unit(rng) * 3.0) * 0.5;
    const int aircraft = static_cast<int>(unit(rng) * 40);
    r.t = t - (unit(rng) < 0.05 ? 20.0 * unit(rng) : 0.0);
    r.source = aircraft % 3 == 0 ? "adsb" : "radar";
    r.id = "A" + std::to_string(aircraft);
    r.lat_deg = 50.0 + aircraft * 0.01 + (t - 1.7e9) * 1e-4;
    r.lon_deg = 8.0 + aircraft * 0.02 + (unit(rng) < 0.01 ? 200.0 : 0.0);
    r.alt_ft = 3000.0 + aircraft * 500.0 + (t - 1.7e9) * (aircraft % 2 ? 10.0 : -5.0);
    if (unit(rng) < 0.8) r.gs_kt = 250.0 + aircraft + (unit(rng) < 0.02 ? -5.0 : 0.0);
    if (unit(rng) < 0.8) r.trk_deg = std::fmod(aircraft * 37.0 + (t - 1.7e9) * 0.5, 360.0);
    if (unit(rng) < 0.6) r.vr_fpm = aircraft % 2 ? 600.0 : -300.0;
    if (unit(rng) < 0.4) {
      r.sel_ft = 3000.0 + aircraft * 1000.0;
      r.sel_src = unit(rng) < 0.5 ? SelectedAltitudeSource::Mcp : SelectedAltitudeSource::Fms;
    }
    if (unit(rng) < 0.2) r.tar_dps = unit(rng) * 4.0 - 2.0;
    if (unit(rng) < 0.7) r.callsign = "CS" + std::to_string(aircraft);
    if (unit(rng) < 0.5) r.mode3a = static_cast<std::uint16_t>(01000 + aircraft);
    if (aircraft % 3 == 0) r.address = 0x400000u + static_cast<std::uint32_t>(aircraft);
    r.coasting = unit(rng) < 0.05;
    r.track_end = unit(rng) < 0.01;
    feed.push_back(r);
  }
  return feed;
}

struct Outcome {
  std::vector<std::string> lines;
  void admitted(const AdmitResult& a) {
    lines.push_back("admit " + std::to_string(static_cast<int>(a.admission)) + " " + std::to_string(a.slot) + " " +
                    std::to_string(a.new_track) + std::to_string(a.velocity_reset) + " " +
                    std::to_string(static_cast<int>(a.refusal)));
  }
};

// Feeds `from` .. `to` of the feed into `table` as a pipeline does: the clock is the
// newest record's time, expired tracks are dropped before each record.
void feed_into(TrackTable& table, const geo::Projection& projection, const std::vector<TrackReport>& feed,
               std::size_t from, std::size_t to, double& now, Outcome& outcome) {
  for (std::size_t i = from; i < to; ++i) {
    const TrackReport& r = feed[i];
    now = std::max(now, r.t);
    table.expire(now, [&](TrackSlot slot, const Track& track) {
      outcome.lines.push_back("expire " + std::to_string(slot) + " " + track.id);
    });
    const AdmitResult a = table.admit(r, now, projection);
    outcome.admitted(a);
    if (a.admission != Admission::Rejected && r.track_end) {
      table.drop(a.slot);
      outcome.lines.push_back("end " + std::to_string(a.slot));
    }
  }
}

// Every field of every slot, read without the checkpoint's code (hexfloat: bit for bit).
std::string contents(const TrackTable& table) {
  std::ostringstream o;
  o << std::hexfloat;
  const auto opt = [&](const auto& v) -> std::ostream& {
    if (v) return o << '[' << +*v << ']';
    return o << "[-]";
  };
  for (TrackSlot slot = 0; slot < table.slot_end(); ++slot) {
    const Track& k = table[slot];
    o << slot << ':' << k.in_use << ' ' << k.source << '/' << k.id << ' ' << k.callsign << ' ';
    opt(k.mode3a) << ' ';
    opt(k.address) << ' ' << k.coasting << k.has_velocity << k.vertical_rate_known << k.vertical_rate_derived
                   << k.altitude_moving_one_way << k.has_turn_reference << k.in_engine << ' ' << k.number << ' '
                   << k.records << ' ' << k.altitude_step_ft << ' ' << k.altitude_change_ft << ' ' << k.t << ' '
                   << k.lat_deg << ' ' << k.lon_deg << ' ' << k.alt_ft << ' ' << k.gs_kt << ' ' << k.trk_deg << ' '
                   << k.vr_fpm << ' ' << k.plane_scale << ' ';
    opt(k.intent.sel_ft) << static_cast<int>(k.intent.sel_src) << ' ' << k.intent.sel_t << ' '
                         << k.intent.approach_sign << k.intent.busted << ' ';
    opt(k.intent.band_entry_rate_fpm) << ' ';
    opt(k.level_off_ft) << ' ';
    opt(k.turn_rate_dps) << ' ' << k.turn_reference_t << ' ' << k.turn_reference_trk_deg << ' '
                         << k.kinematics.position.x << ' ' << k.kinematics.position.y << ' '
                         << k.kinematics.velocity.x << ' ' << k.kinematics.velocity.y << ' '
                         << k.kinematics.altitude_m << ' ' << k.kinematics.vertical_rate_mps << ' '
                         << k.kinematics.level_off_m << ' ' << k.kinematics.turn_rate_rps << ' ' << k.plane << '\n';
  }
  o << "in use " << table.size() << " max " << table.max_size() << " resets " << table.velocity_resets()
    << " derived " << table.velocities_derived() << '\n';
  return o.str();
}

std::string saved(const TrackTable& table) {
  util::CheckpointWriter out;
  table.save(out);
  return out.take();
}

TEST(TrackCheckpoint, ARestoredTableContinuesRecordForRecordAtAnyStep) {
  const geo::Projection projection(geo::GeodeticPosition{50.2, 8.4}, 1000e3);
  TrackTableConfig config;
  config.track_timeout_s = 30.0;
  std::size_t tracks_at_checkpoints = 0, free_slots_seen = 0;
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    const std::vector<TrackReport> feed = random_feed(seed, 1500);
    TrackTable whole(config);
    Outcome expected;
    double now = 0.0;
    feed_into(whole, projection, feed, 0, feed.size(), now, expected);

    const std::size_t cut = (seed * 131) % feed.size();
    TrackTable before(config);
    Outcome outcome;
    double now_cut = 0.0;
    feed_into(before, projection, feed, 0, cut, now_cut, outcome);
    tracks_at_checkpoints += before.size();
    free_slots_seen += before.slot_end() - before.size();
    const std::string bytes = saved(before);

    TrackTable after(config);
    util::CheckpointReader in(bytes);
    after.restore(in);
    ASSERT_TRUE(in.at_end()) << "seed " << seed;
    ASSERT_EQ(saved(after), bytes) << "seed " << seed << ": restored, the same state";
    ASSERT_EQ(contents(after), contents(before)) << "seed " << seed << ": every field of every track";
    feed_into(after, projection, feed, cut, feed.size(), now_cut, outcome);
    ASSERT_EQ(outcome.lines, expected.lines) << "seed " << seed << ", checkpoint at record " << cut;
    ASSERT_EQ(contents(after), contents(whole)) << "seed " << seed << ": the same tracks at the end";
    EXPECT_EQ(after.rejections().by_reason(), whole.rejections().by_reason());
    EXPECT_EQ(after.dropped_fields().by_reason(), whole.dropped_fields().by_reason());
  }
  EXPECT_GT(tracks_at_checkpoints, 400u) << "the checkpoints must catch tracks";
  EXPECT_GT(free_slots_seen, 20u) << "and free slots to reuse";
}

TEST(TrackCheckpoint, EveryTruncationIsRefusedAndLeavesTheTableEmpty) {
  const geo::Projection projection(geo::GeodeticPosition{50.2, 8.4}, 1000e3);
  TrackTable table;
  Outcome outcome;
  double now = 0.0;
  const std::vector<TrackReport> feed = random_feed(3, 300);
  feed_into(table, projection, feed, 0, feed.size(), now, outcome);
  const std::string bytes = saved(table);
  for (std::size_t size = 0; size < bytes.size(); size += 7) {
    TrackTable restored;
    util::CheckpointReader in(std::string_view(bytes).substr(0, size));
    EXPECT_THROW(restored.restore(in), util::CheckpointError) << "cut at " << size;
    EXPECT_EQ(restored.size(), 0u);
    EXPECT_EQ(restored.slot_end(), 0u);
  }
}

}  // namespace
}  // namespace kew::track
