// Hilbert-curve order (core/include/kew/geometry/hilbert.hpp): the curve of order 2
// against its published cell sequence, the curve's defining properties at order 6, and
// the order of points.
#include "kew/geometry/hilbert.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <utility>
#include <vector>

namespace kew::geometry {
namespace {

TEST(Hilbert, OrderOneVisitsTheFourCellsUpAcrossAndDown) {
  EXPECT_EQ(hilbert_index(0, 0, 1), 0u);
  EXPECT_EQ(hilbert_index(0, 1, 1), 1u);
  EXPECT_EQ(hilbert_index(1, 1, 1), 2u);
  EXPECT_EQ(hilbert_index(1, 0, 1), 3u);
}

TEST(Hilbert, OrderTwoFollowsTheCurveOfTheFourByFourGrid) {
  // The 4 × 4 curve from (0, 0) to (3, 0), cell by cell.
  const std::array<std::pair<std::uint32_t, std::uint32_t>, 16> cells{{{0, 0}, {1, 0}, {1, 1}, {0, 1},
                                                                       {0, 2}, {0, 3}, {1, 3}, {1, 2},
                                                                       {2, 2}, {2, 3}, {3, 3}, {3, 2},
                                                                       {3, 1}, {2, 1}, {2, 0}, {3, 0}}};
  for (std::uint64_t d = 0; d < cells.size(); ++d)
    EXPECT_EQ(hilbert_index(cells[d].first, cells[d].second, 2), d) << cells[d].first << "," << cells[d].second;
}

TEST(Hilbert, EveryCellOnceAndEachStepToANeighbour) {
  constexpr int kOrder = 6;
  constexpr std::uint32_t kSide = 1u << kOrder;
  std::vector<std::pair<int, int>> at(kSide * kSide, {-1, -1});
  for (std::uint32_t x = 0; x < kSide; ++x)
    for (std::uint32_t y = 0; y < kSide; ++y) {
      const std::uint64_t d = hilbert_index(x, y, kOrder);
      ASSERT_LT(d, at.size());
      ASSERT_EQ(at[d].first, -1) << "two cells at " << d;
      at[d] = {static_cast<int>(x), static_cast<int>(y)};
    }
  EXPECT_EQ(at.front(), std::make_pair(0, 0));
  EXPECT_EQ(at.back(), std::make_pair(static_cast<int>(kSide) - 1, 0));
  for (std::size_t d = 1; d < at.size(); ++d)
    EXPECT_EQ(std::abs(at[d].first - at[d - 1].first) + std::abs(at[d].second - at[d - 1].second), 1) << d;
}

TEST(Hilbert, PointsFollowTheCurveOverTheirBoundingBox) {
  // Corners of a 100 km square, offset from the origin, in the order the curve visits
  // their quadrants: lower left, upper left, upper right, lower right.
  const std::vector<Point2> points{{250e3, 50e3}, {150e3, 150e3}, {250e3, 150e3}, {150e3, 50e3}};
  EXPECT_EQ(hilbert_order(points), (std::vector<std::uint32_t>{3, 1, 2, 0}));
}

TEST(Hilbert, TiesKeepIndexOrderAndNonFinitePointsGoLast) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Point2> points{{nan, 0.0}, {5.0, 5.0}, {0.0, 0.0}, {5.0, 5.0}};
  EXPECT_EQ(hilbert_order(points), (std::vector<std::uint32_t>{2, 1, 3, 0}));
  EXPECT_TRUE(hilbert_order({}).empty());
  EXPECT_EQ(hilbert_order({{1.0, 2.0}}), (std::vector<std::uint32_t>{0}));
}

}  // namespace
}  // namespace kew::geometry
