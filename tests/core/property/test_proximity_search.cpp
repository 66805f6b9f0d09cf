// ProximitySearch::within() returns exactly the points a brute-force scan finds in the
// disk, and so does within_around() for disks around any point (inside or outside the
// hull, holding the center or not), on moving point sets that include what the face walk must not trip over: exact
// duplicates (twins, which are not triangulation vertices), all points on one line (a
// flat triangulation with no finite face), one or two points, and points leaving and
// rejoining through removal and reinsertion.

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/probe/proximity_search.hpp"

namespace {

using kew::geometry::Point2;
using kew::geometry::Vector2;
using kew::kinetic::KineticConfig;
using kew::kinetic::KineticDelaunay;
using kew::kinetic::PointId;
using kew::probe::ProximitySearch;

enum class Layout { Scattered, WithDuplicates, OneLine, Clustered };

struct Case {
  Layout layout;
  std::size_t points;
};

class ProximitySearchProperty : public testing::TestWithParam<Case> {};

Point2 place(Layout layout, std::mt19937_64& rng, const std::vector<Point2>& earlier) {
  std::uniform_real_distribution<double> coordinate(-50'000.0, 50'000.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  switch (layout) {
    case Layout::Scattered: break;
    case Layout::WithDuplicates:
      if (!earlier.empty() && unit(rng) < 0.3) return earlier[rng() % earlier.size()];  // a twin
      break;
    case Layout::OneLine: return {coordinate(rng), 0.0};
    case Layout::Clustered: {
      std::normal_distribution<double> near(0.0, 2'000.0);
      const Point2 centre = (rng() % 2 == 0) ? Point2{-20'000.0, 0.0} : Point2{20'000.0, 5'000.0};
      return {centre.x + near(rng), centre.y + near(rng)};
    }
  }
  return {coordinate(rng), coordinate(rng)};
}

/// What within() (no target) or within_around(target) must return: every other live
/// point whose position now is within the radius of the target (else of the center),
/// plus at most twins slightly farther (within twice their release distance).
void expect_same_as_brute_force(const KineticDelaunay& kdt, ProximitySearch& search, const std::vector<PointId>& live,
                                PointId center, double radius, std::optional<Point2> target = std::nullopt) {
  std::vector<PointId> found;
  if (target) {
    search.within_around(kdt, center, *target, radius, found);
  } else {
    search.within(kdt, center, radius, found);
  }
  std::vector<PointId> sorted = found;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "a point was returned twice";
  ASSERT_EQ(std::count(sorted.begin(), sorted.end(), center), 0) << "the center was returned";
  const Point2 c = target ? *target : kdt.position_now(center);
  const double slack = radius + 2.0 * kdt.config().twin_release_distance_m;
  for (const PointId p : live) {
    if (p == center) continue;
    const double d = kew::geometry::norm(kdt.position_now(p) - c);
    const bool returned = std::binary_search(sorted.begin(), sorted.end(), p);
    if (d <= radius) {
      EXPECT_TRUE(returned) << "point " << p << " at " << d << " m of a " << radius << " m disk missed";
    }
    if (returned) {
      EXPECT_LE(d, slack) << "point " << p << " returned from " << d << " m";
    }
  }
}

TEST_P(ProximitySearchProperty, WithinEqualsBruteForce) {
  const Case param = GetParam();
  std::mt19937_64 rng(0x5eed + static_cast<std::uint64_t>(param.layout) * 131 + param.points);
  KineticConfig config;
  config.tolerance = 50.0;
  KineticDelaunay kdt(config, 0.0);
  ProximitySearch search;
  std::uniform_real_distribution<double> speed(-250.0, 250.0);
  std::uniform_real_distribution<double> radius(500.0, 40'000.0);
  std::vector<Point2> placed;
  std::vector<PointId> live;
  const bool on_line = param.layout == Layout::OneLine;
  std::vector<Vector2> velocities;
  for (std::size_t i = 0; i < param.points; ++i) {
    placed.push_back(place(param.layout, rng, placed));
    Vector2 v{speed(rng), on_line ? 0.0 : speed(rng)};
    // A duplicate flying with its original stays its twin until one of them changes.
    for (std::size_t k = 0; k + 1 < placed.size(); ++k)
      if (placed[k].x == placed.back().x && placed[k].y == placed.back().y) v = velocities[k];
    velocities.push_back(v);
    live.push_back(kdt.insert(0.0, placed.back(), v));
  }
  if (param.layout == Layout::WithDuplicates) {
    EXPECT_GT(kdt.statistics().twins_created, 10u);
  }
  std::size_t searches = 0;
  for (int period = 1; period <= 6; ++period) {
    const double t = 4.0 * period;
    kdt.advance(t);
    // Some points leave and come back elsewhere: ids and faces are recycled.
    if (live.size() > 3 && period % 2 == 0) {
      const std::size_t k = rng() % live.size();
      kdt.remove(live[k], t);
      placed.push_back(place(param.layout, rng, placed));
      live[k] = kdt.insert(t, placed.back(), {speed(rng), on_line ? 0.0 : speed(rng)});
    }
    std::uniform_real_distribution<double> offset(-60'000.0, 60'000.0);
    for (const PointId center : live) {
      expect_same_as_brute_force(kdt, search, live, center, radius(rng));
      // A disk ahead of the center (the probe's predicted position, design §2.1), up to
      // 60 km off: often beyond the hull, sometimes holding no point at all.
      const Point2 here = kdt.position_now(center);
      const Point2 ahead{here.x + offset(rng), on_line ? here.y : here.y + offset(rng)};
      expect_same_as_brute_force(kdt, search, live, center, radius(rng), ahead);
      ++searches;
    }
  }
  EXPECT_EQ(searches, 6 * live.size());
}

std::string case_name(const testing::TestParamInfo<Case>& param) {
  static const char* const kNames[] = {"Scattered", "WithDuplicates", "OneLine", "Clustered"};
  return std::string(kNames[static_cast<int>(param.param.layout)]) + std::to_string(param.param.points);
}

INSTANTIATE_TEST_SUITE_P(Layouts, ProximitySearchProperty,
                         testing::Values(Case{Layout::Scattered, 1}, Case{Layout::Scattered, 2},
                                         Case{Layout::Scattered, 400}, Case{Layout::WithDuplicates, 300},
                                         Case{Layout::OneLine, 2}, Case{Layout::OneLine, 60},
                                         Case{Layout::Clustered, 400}),
                         case_name);

}  // namespace
