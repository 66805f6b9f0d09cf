// Static Delaunay triangulation (one instant): insertion, removal, degenerate inputs,
// checked against CGAL and with the exact audit.

#include <gtest/gtest.h>

#include <random>

#include "delaunay_oracle.hpp"
#include "kew/kinetic/certificate.hpp"
#include "kew/triangulation/delaunay.hpp"

namespace kew::triangulation {
namespace {

using geometry::Point2;

std::vector<std::pair<std::uint32_t, Point2>> positions(const DelaunayTriangulation& dt,
                                                        const std::vector<VertexIndex>& vs) {
  std::vector<std::pair<std::uint32_t, Point2>> out;
  for (VertexIndex v : vs) out.emplace_back(v, dt.position(v));
  return out;
}

VertexIndex add(DelaunayTriangulation& dt, Point2 p) {
  const VertexIndex v = dt.create_vertex({p, {0, 0}, 0.0});
  EXPECT_EQ(dt.attach(v), AttachResult::Attached);
  return v;
}

TEST(Delaunay, RandomInsertionsMatchCgal) {
  DelaunayTriangulation dt;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> c(0.0, 1000.0);
  std::vector<VertexIndex> vs;
  for (int k = 0; k < 2000; ++k) vs.push_back(add(dt, {c(rng), c(rng)}));
  EXPECT_TRUE(dt.tds().is_valid());
  EXPECT_EQ(dt.audit().violations(), 0u);
  EXPECT_EQ(dt.finite_edges(), testing::cgal_delaunay_edges(positions(dt, vs)));
}

TEST(Delaunay, RemovalsKeepDelaunay) {
  DelaunayTriangulation dt;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> c(0.0, 1000.0);
  std::vector<VertexIndex> vs;
  for (int k = 0; k < 600; ++k) vs.push_back(add(dt, {c(rng), c(rng)}));
  std::shuffle(vs.begin(), vs.end(), rng);
  while (vs.size() > 3) {
    EXPECT_TRUE(dt.detach(vs.back()).hole_triangulated);
    vs.pop_back();
    if (vs.size() % 50 == 0) {
      ASSERT_EQ(dt.audit().violations(), 0u);
      EXPECT_EQ(dt.finite_edges(), testing::cgal_delaunay_edges(positions(dt, vs)));
    }
  }
  EXPECT_EQ(dt.size(), 3u);
}

TEST(Delaunay, GridIsCocircularEverywhereAndStillValid) {
  DelaunayTriangulation dt;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) add(dt, {static_cast<double>(i), static_cast<double>(j)});
  EXPECT_EQ(dt.audit().violations(), 0u);
  EXPECT_EQ(dt.size(), 400u);
}

TEST(Delaunay, CollinearPointsFormAFlatChainThenBecomeTwoDimensional) {
  DelaunayTriangulation dt;
  std::vector<VertexIndex> vs;
  for (int i : {5, 1, 9, 3, 7}) vs.push_back(add(dt, {static_cast<double>(i), 2.0 * i}));
  EXPECT_TRUE(dt.is_flat());
  EXPECT_EQ(dt.audit().violations(), 0u);
  EXPECT_EQ(dt.finite_edges().size(), 4u);
  const VertexIndex off = add(dt, {0.0, 10.0});
  EXPECT_FALSE(dt.is_flat());
  EXPECT_EQ(dt.audit().violations(), 0u);
  vs.push_back(off);
  EXPECT_EQ(dt.finite_edges(), testing::cgal_delaunay_edges(positions(dt, vs)));
  EXPECT_TRUE(dt.detach(off).hole_triangulated);
  EXPECT_TRUE(dt.is_flat());
  EXPECT_EQ(dt.audit().violations(), 0u);
}

TEST(Delaunay, DuplicatePositionIsReportedNotInserted) {
  DelaunayTriangulation dt;
  const VertexIndex a = add(dt, {1.0, 1.0});
  add(dt, {2.0, 5.0});
  add(dt, {7.0, 1.0});
  const VertexIndex b = dt.create_vertex({{1.0, 1.0}, {0, 0}, 0.0});
  VertexIndex same = kNoVertex;
  EXPECT_EQ(dt.attach(b, &same), AttachResult::Duplicate);
  EXPECT_EQ(same, a);
  EXPECT_EQ(dt.size(), 3u);
}

TEST(Delaunay, AuditFindsAnInvertedFace) {
  DelaunayTriangulation dt;
  const VertexIndex a = add(dt, {0.0, 0.0});
  add(dt, {10.0, 0.0});
  add(dt, {5.0, 10.0});
  add(dt, {5.0, 3.0});
  EXPECT_EQ(dt.audit().violations(), 0u);
  // Teleport a vertex without telling the triangulation: the audit must see it.
  dt.set_trajectory(a, {{20.0, 20.0}, {0, 0}, 0.0});
  EXPECT_GT(dt.audit().violations(), 0u);
}

TEST(Certificate, IncirclePolynomialAgreesWithPositionsAtAnyTime) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> c(-1e5, 1e5), v(-250.0, 250.0);
  for (int trial = 0; trial < 200; ++trial) {
    Trajectory t[4];
    for (auto& x : t) x = {{c(rng), c(rng)}, {v(rng), v(rng)}, 0.0};
    const double now = 1000.0;
    const auto poly = kinetic::incircle_polynomial(t[0], t[1], t[2], t[3], now);
    for (double tau : {0.0, 1.5, 30.0, 200.0}) {
      const Point2 a = t[0].at(now + tau), b = t[1].at(now + tau), cc = t[2].at(now + tau), d = t[3].at(now + tau);
      const double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y, cdx = cc.x - d.x, cdy = cc.y - d.y;
      const double det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                         (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                         (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
      EXPECT_NEAR(poly(tau), det, 1e-9 * std::abs(det) + 1e6);
    }
  }
}

}  // namespace
}  // namespace kew::triangulation
