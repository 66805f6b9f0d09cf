// The probe's fast paths must decide exactly what the slow ones decide:
// the allocation-free neighbour walk, the level-pair shortcut of the CPA test, and the
// conflict tap the peers benchmark compares against.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "kew/pipeline/instrumentation.hpp"
#include "kew/pipeline/pipeline.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/triangulation/delaunay.hpp"

namespace kew {
namespace {

TEST(TdsWalk, ForEachAdjacentVertexGivesAdjacentVerticesInOrder) {
  triangulation::DelaunayTriangulation dt;
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> coordinate(-1000.0, 1000.0);
  for (int i = 0; i < 200; ++i) dt.attach(dt.create_vertex({{coordinate(random), coordinate(random)}, {0, 0}, 0.0}));
  const triangulation::Tds& tds = dt.tds();
  std::size_t infinite_seen = 0, compared = 0;
  std::vector<triangulation::VertexIndex> expected, walked;
  for (triangulation::VertexIndex v = 1; v < tds.vertex_capacity(); ++v) {
    if (!tds.is_attached(v)) continue;
    tds.adjacent_vertices(v, expected);
    walked.clear();
    tds.for_each_adjacent_vertex(v, [&](triangulation::VertexIndex w) { walked.push_back(w); });
    ASSERT_EQ(walked, expected) << "vertex " << v;
    ASSERT_GE(walked.size(), 2u);
    for (const auto w : walked) infinite_seen += w == triangulation::kInfiniteVertex;
    ++compared;
  }
  EXPECT_EQ(compared, 200u);
  EXPECT_GE(infinite_seen, 3u);  // hull vertices see the infinite vertex
}

TEST(TdsWalk, DetachedVertexHasNoNeighbours) {
  triangulation::DelaunayTriangulation dt;
  const auto v = dt.create_vertex({{0.0, 0.0}, {0, 0}, 0.0});
  int calls = 0;
  dt.tds().for_each_adjacent_vertex(v, [&](triangulation::VertexIndex) { ++calls; });
  EXPECT_EQ(calls, 0);
}

probe::Kinematics aircraft(double x, double y, double vx, double vy, double alt_m, double vr) {
  return {{x, y}, {vx, vy}, alt_m, vr};
}

TEST(LevelShortcut, LevelPairsAtLeastSvApartAreNeverInConflict) {
  const probe::SeparationMinima minima;  // 9260 m, 304.8 m, 120 s
  // Head-on on one line, exactly S_v apart (altitudes chosen so that the difference is
  // exactly 304.8 in floating point), both level: horizontally a sure conflict.
  const auto a = aircraft(0, 0, 200, 0, 0.0, 0.0);
  const auto b = aircraft(10000, 0, -200, 0, 304.8, 0.0);
  EXPECT_TRUE(probe::vertically_apart_for_ever(a, b, minima));
  EXPECT_TRUE(probe::vertically_apart_for_ever(b, a, minima));
  EXPECT_FALSE(probe::in_conflict(a, b, minima));
  // 1 cm less than S_v apart: the shortcut must not claim it, and it is a conflict.
  const auto c = aircraft(10000, 0, -200, 0, 304.79, 0.0);
  EXPECT_FALSE(probe::vertically_apart_for_ever(a, c, minima));
  EXPECT_TRUE(probe::in_conflict(a, c, minima));
  // Far apart vertically but one climbing: only the full test may decide.
  const auto d = aircraft(10000, 0, -200, 0, 2000.0, -20.0);
  EXPECT_FALSE(probe::vertically_apart_for_ever(a, d, minima));
}

TEST(LevelShortcut, NeverContradictsTheFullTest) {
  const probe::SeparationMinima minima;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> xy(-40000.0, 40000.0), v(-250.0, 250.0), alt(9000.0, 11000.0);
  const double rates[] = {0.0, 0.0, 5.0, -5.0};
  std::uniform_int_distribution<int> rate(0, 3);
  int shortcut = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto a = aircraft(xy(random), xy(random), v(random), v(random), alt(random), rates[rate(random)]);
    const auto b = aircraft(xy(random), xy(random), v(random), v(random), alt(random), rates[rate(random)]);
    if (!probe::vertically_apart_for_ever(a, b, minima)) continue;
    ++shortcut;
    ASSERT_FALSE(probe::in_conflict(a, b, minima)) << i;
  }
  EXPECT_GT(shortcut, 1000);
}

TrackReport report(const std::string& id, double t, double lon, double trk_deg) {
  TrackReport r;
  r.t = t;
  r.id = id;
  r.source = "tap";
  r.lat_deg = 50.0;
  r.lon_deg = lon;
  r.alt_ft = 35000.0;
  r.gs_kt = 400.0;
  r.trk_deg = trk_deg;
  r.vr_fpm = 0.0;
  return r;
}

// A Pipeline whose conflict tap and alert sink keep what they are told.
struct TappedPipeline {
  Pipeline pipeline;
  std::vector<std::pair<track::TrackSlot, track::TrackSlot>> taps;
  std::vector<AlertEvent> events;
  TappedPipeline() {
    PipelineInstrumentation instruments;
    instruments.conflict_tap = [this](track::TrackSlot p, track::TrackSlot q) { taps.emplace_back(p, q); };
    pipeline.instrument(instruments);
    pipeline.set_alert_sink([this](const AlertEvent& e) { events.push_back(e); });
  }
  TappedPipeline(const TappedPipeline&) = delete;
  TappedPipeline& operator=(const TappedPipeline&) = delete;
};

// Two aircraft head-on at one level, ~14 km apart at k = 0 and closing at ~411 m/s: their
// reports (west, east) of the k-th 4 s period. In conflict from the first evaluation on.
std::pair<TrackReport, TrackReport> head_on(int k) {
  const double t = 1714400000.0 + 4.0 * k;
  const double flown_deg = 4.0 * k * 205.8 / 71700.0;
  return {report("W", t, 7.9 + flown_deg, 90.0), report("E", t, 8.1 - flown_deg, 270.0)};
}

TEST(ConflictTap, SeesEveryConflictingEvaluationOnceWithOrderedSlots) {
  TappedPipeline tapped;
  // A third aircraft 1° of longitude away (~72 km) is never in conflict.
  for (int k = 0; k < 3; ++k) {
    const auto [west, east] = head_on(k);
    tapped.pipeline.process(west);
    tapped.pipeline.process(east);
    tapped.pipeline.process(report("F", west.t, 9.0, 0.0));
  }
  // W's first update has no partner yet; then every update of W or E evaluates the pair.
  ASSERT_EQ(tapped.taps.size(), 5u);
  for (const auto& [p, q] : tapped.taps) {
    EXPECT_LT(p, q);
    EXPECT_EQ(p, tapped.pipeline.tracks().find("tap", "W"));
    EXPECT_EQ(q, tapped.pipeline.tracks().find("tap", "E"));
  }
  ASSERT_FALSE(tapped.events.empty());  // confirm = 2: the second conflicting evaluation opens it
  EXPECT_EQ(tapped.events.front().state, AlertState::New);
}

TEST(ConflictTap, SeesConflictsTheRulesThenSuppress) {
  // The tap reports what the probe found, so that the peers benchmark can compare
  // candidate searches; the eligibility rules decide afterwards what becomes an alert.
  // Two tracks of one aircraft (one address, two sources) head-on: every evaluation of
  // the pair is a conflict, and same_aircraft suppresses every alert.
  TappedPipeline tapped;
  for (int k = 0; k < 3; ++k) {
    auto [west, east] = head_on(k);
    west.address = east.address = 0x4B1234;
    east.source = "tap-2";
    tapped.pipeline.process(west);
    tapped.pipeline.process(east);
  }
  EXPECT_EQ(tapped.taps.size(), 5u);
  EXPECT_TRUE(tapped.events.empty());
  EXPECT_GE(tapped.pipeline.suppressed().count("same_aircraft"), 5u);
}

}  // namespace
}  // namespace kew
