// What an update costs the engine, in certificates (design §2.3): a reinsertion solves
// the certificates of the point's new star once, and a velocity-only update keeps the
// renewals its new motion cannot reach before they are due.

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "kew/kinetic/kinetic_delaunay.hpp"

namespace kew::kinetic {
namespace {

using geometry::Point2;
using geometry::Vector2;

/// 200 points in a 100 km square, each moving at 150–250 m/s on its own heading.
struct Cloud {
  explicit Cloud(const KineticConfig& config) : engine(config, 0.0) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> coordinate(0.0, 100'000.0), speed(150.0, 250.0), heading(0.0, 6.283185307);
    for (int k = 0; k < 200; ++k) {
      const double h = heading(rng), s = speed(rng);
      ids.push_back(engine.insert(0.0, {coordinate(rng), coordinate(rng)}, {s * std::cos(h), s * std::sin(h)}));
    }
    engine.advance(1.0);
  }
  /// A vertex of degree ≥ 5 well inside the hull.
  PointId interior_vertex() const {
    for (const PointId id : ids) {
      std::size_t degree = 0;
      bool on_hull = false;
      engine.for_each_neighbor(id, [&](PointId) { ++degree; });
      engine.triangulation().tds().for_each_adjacent_vertex(
          id, [&](PointId w) { on_hull = on_hull || w == triangulation::kInfiniteVertex; });
      if (degree >= 5 && !on_hull) return id;
    }
    return kNoPoint;
  }
  KineticDelaunay engine;
  std::vector<PointId> ids;
};

std::uint64_t certificates(const KineticStatistics& s) { return s.certificates_solved + s.certificates_deferred; }

TEST(KineticUpdateCost, AReinsertionSolvesItsNewStarOnce) {
  KineticConfig config;
  config.horizon_s = 4.0;
  Cloud cloud(config);
  const PointId id = cloud.interior_vertex();
  ASSERT_NE(id, kNoPoint);
  std::size_t degree = 0;
  cloud.engine.for_each_neighbor(id, [&](PointId) { ++degree; });
  const Point2 at = cloud.engine.position_now(id);
  const std::uint64_t before = certificates(cloud.engine.statistics());
  // τ = 0: a report 1 mm off the model reinserts the point where it was, with the star
  // it had. Its d spokes and d link edges are the certificates to solve, no more: the
  // hole its removal leaves is filled again at the same instant and is never solved.
  ASSERT_EQ(cloud.engine.update(id, 1.0, {at.x + 1e-3, at.y}, cloud.engine.velocity(id)), UpdateKind::Reinserted);
  EXPECT_LE(certificates(cloud.engine.statistics()) - before, 2 * degree);
  EXPECT_TRUE(cloud.engine.is_valid());
}

/// H = 4 s, τ = 100 m: every update below is within τ, velocity-only.
KineticConfig velocity_only() {
  KineticConfig config;
  config.horizon_s = 4.0;
  config.tolerance = 100.0;
  return config;
}

/// Advancing through every renewal and failure leaves a valid triangulation with
/// nothing to repair.
void expect_exact_after(Cloud& cloud, double t) {
  cloud.engine.advance(t);
  EXPECT_TRUE(cloud.engine.is_valid());
  EXPECT_EQ(cloud.engine.audit_and_repair().violations_found, 0u);
}

TEST(KineticUpdateCost, AVelocityOnlyUpdateKeepsTheRenewalsItCannotReach) {
  Cloud cloud(velocity_only());
  const PointId id = cloud.interior_vertex();
  ASSERT_NE(id, kNoPoint);
  const Vector2 v = cloud.engine.velocity(id);
  const double faster = 1.0 + 1.0 / geometry::norm(v);
  // 1 m/s faster: over the ≤ 4 s left to each renewal the point moves 4 m more, which
  // no certificate of a 100 km cloud's star notices.
  ASSERT_EQ(cloud.engine.update(id, 1.0, cloud.engine.position_now(id), {faster * v.x, faster * v.y}),
            UpdateKind::VelocityOnly);
  EXPECT_GT(cloud.engine.statistics().certificates_kept, 0u);
  expect_exact_after(cloud, 30.0);
}

TEST(KineticUpdateCost, AVelocityOnlyUpdateThatTurnsHardSolvesAgain) {
  Cloud cloud(velocity_only());
  const PointId id = cloud.interior_vertex();
  ASSERT_NE(id, kNoPoint);
  const KineticStatistics before = cloud.engine.statistics();
  // Reversed at 2 km/s: within 4 s it crosses its neighbours' circles, so renewals
  // cannot be kept where its certificates may fail.
  const Vector2 v = cloud.engine.velocity(id);
  ASSERT_EQ(cloud.engine.update(id, 1.0, cloud.engine.position_now(id), {-10.0 * v.x, -10.0 * v.y}),
            UpdateKind::VelocityOnly);
  EXPECT_GT(cloud.engine.statistics().certificates_solved, before.certificates_solved);
  expect_exact_after(cloud, 30.0);
}

}  // namespace
}  // namespace kew::kinetic
