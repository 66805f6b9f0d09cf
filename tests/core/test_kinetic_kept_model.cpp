// Kept models (design §2.3): an update within τ for keep_model_s leaves the model as it
// is, and a Drift deadline reinserts the point on its report before the model can lag
// the report by more than τ.

#include <gtest/gtest.h>

#include "kew/kinetic/kinetic_delaunay.hpp"

namespace kew::kinetic {
namespace {

using geometry::Point2;
using geometry::Vector2;

KineticConfig kept(double tolerance_m, double keep_s) {
  KineticConfig c;
  c.horizon_s = 300.0;
  c.tolerance = tolerance_m;
  c.keep_model_s = keep_s;
  return c;
}

/// Four points at the corners of a 20 km square, the first moving east at 200 m/s.
struct Square {
  explicit Square(const KineticConfig& config) : engine(config, 0.0) {
    mover = engine.insert(0.0, {0.0, 0.0}, {200.0, 0.0});
    engine.insert(0.0, {20'000.0, 0.0}, {0.0, 0.0});
    engine.insert(0.0, {0.0, 20'000.0}, {0.0, 0.0});
    engine.insert(0.0, {20'000.0, 20'000.0}, {0.0, 0.0});
  }
  KineticDelaunay engine;
  PointId mover = kNoPoint;
};

TEST(KeptModel, UpdateWithinToleranceLongEnoughChangesNothing) {
  Square s(kept(300.0, 4.0));
  // 100 m off the model, 10 m/s faster: within 300 m for 20 s.
  EXPECT_EQ(s.engine.update(s.mover, 4.0, {900.0, 0.0}, {210.0, 0.0}), UpdateKind::Kept);
  EXPECT_EQ(s.engine.velocity(s.mover), (Vector2{200.0, 0.0}));
  EXPECT_EQ(s.engine.position_now(s.mover), (Point2{800.0, 0.0}));
  EXPECT_EQ(s.engine.statistics().kept_updates, 1u);
}

TEST(KeptModel, ShortBoundChangesTheVelocityAsBefore) {
  Square s(kept(300.0, 4.0));
  // 100 m off, 60 m/s apart: within 300 m for 3.3 s only, less than keep_model_s.
  EXPECT_EQ(s.engine.update(s.mover, 4.0, {900.0, 0.0}, {260.0, 0.0}), UpdateKind::VelocityOnly);
  EXPECT_EQ(s.engine.velocity(s.mover), (Vector2{260.0, 0.0}));
}

TEST(KeptModel, OffWhenKeepIsZeroOrToleranceRelative) {
  Square off(kept(300.0, 0.0));
  EXPECT_EQ(off.engine.update(off.mover, 4.0, {900.0, 0.0}, {210.0, 0.0}), UpdateKind::VelocityOnly);
  KineticConfig relative = kept(0.01, 4.0);
  relative.tolerance_mode = ToleranceMode::Relative;
  Square rel(relative);
  EXPECT_NE(rel.engine.update(rel.mover, 4.0, {810.0, 0.0}, {201.0, 0.0}), UpdateKind::Kept);
}

TEST(KeptModel, DeadlineReinsertsOnTheReportWhenTheBoundRunsOut) {
  Square s(kept(300.0, 4.0));
  ASSERT_EQ(s.engine.update(s.mover, 4.0, {900.0, 0.0}, {210.0, 0.0}), UpdateKind::Kept);
  // The bound runs out 20 s after the report: the model still lags by less than τ.
  s.engine.advance(23.9);
  EXPECT_EQ(s.engine.statistics().drift_reinsertions, 0u);
  EXPECT_LE(geometry::norm(s.engine.position_now(s.mover) - Point2{900.0 + 210.0 * 19.9, 0.0}), 300.0);
  s.engine.advance(24.1);
  EXPECT_EQ(s.engine.statistics().drift_reinsertions, 1u);
  EXPECT_NEAR(s.engine.position_now(s.mover).x, 900.0 + 210.0 * 20.1, 1e-6);
  EXPECT_EQ(s.engine.velocity(s.mover), (Vector2{210.0, 0.0}));
  EXPECT_TRUE(s.engine.is_valid());
}

TEST(KeptModel, LaterUpdateCancelsTheDeadline) {
  Square s(kept(300.0, 4.0));
  ASSERT_EQ(s.engine.update(s.mover, 4.0, {900.0, 0.0}, {210.0, 0.0}), UpdateKind::Kept);
  // A report beyond τ: reinserted now, and the old deadline must not fire later.
  ASSERT_EQ(s.engine.update(s.mover, 8.0, {2'500.0, 0.0}, {200.0, 0.0}), UpdateKind::Reinserted);
  s.engine.advance(60.0);
  EXPECT_EQ(s.engine.statistics().drift_reinsertions, 0u);
  EXPECT_NEAR(s.engine.position_now(s.mover).x, 2'500.0 + 200.0 * 52.0, 1e-6);
}

TEST(KeptModel, RemovedPointHasNoDeadline) {
  Square s(kept(300.0, 4.0));
  ASSERT_EQ(s.engine.update(s.mover, 4.0, {900.0, 0.0}, {210.0, 0.0}), UpdateKind::Kept);
  s.engine.remove(s.mover, 5.0);
  s.engine.advance(60.0);
  EXPECT_EQ(s.engine.statistics().drift_reinsertions, 0u);
  EXPECT_EQ(s.engine.statistics().drifts_queued, 0u);
  EXPECT_TRUE(s.engine.is_valid());
}

}  // namespace
}  // namespace kew::kinetic
