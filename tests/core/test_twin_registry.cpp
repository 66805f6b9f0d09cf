#include <gtest/gtest.h>

#include <initializer_list>
#include <utility>
#include <vector>

#include "kew/kinetic/twin_registry.hpp"

namespace {

using kew::kinetic::PointId;
using kew::kinetic::TwinRegistry;
using Ids = std::vector<PointId>;

/// A registry with points 1..n, then make_twin(twin, host) for each pair in turn.
TwinRegistry with_points(PointId n, std::initializer_list<std::pair<PointId, PointId>> twins = {}) {
  TwinRegistry r;
  for (PointId id = 1; id <= n; ++id) r.add(id);
  for (const auto& [twin, host] : twins) r.make_twin(twin, host);
  return r;
}

TEST(TwinRegistry, NewPointsStandForThemselves) {
  const TwinRegistry r = with_points(3);
  for (PointId id = 1; id <= 3; ++id) {
    EXPECT_FALSE(r.is_twin(id));
    EXPECT_EQ(r.host_of(id), id);
    EXPECT_TRUE(r.twins_of(id).empty());
    EXPECT_EQ(r.release_seq(id), 0u);
  }
  EXPECT_TRUE(r.twins_of(1000).empty());  // never registered
  EXPECT_TRUE(r.is_valid());
}

TEST(TwinRegistry, MakeTwinGoesToTheHostsVertexAndUnlinkKeepsTheOrder) {
  TwinRegistry r = with_points(5, {{2, 1}, {3, 2}, {4, 1}});  // 2 is a twin: 3 goes to 2's host
  EXPECT_EQ(r.host_of(3), 1u);
  EXPECT_EQ(r.twins_of(1), (Ids{2, 3, 4}));
  EXPECT_TRUE(r.twins_of(2).empty());
  r.set_release_seq(3, 17);
  EXPECT_TRUE(r.is_valid());

  r.unlink(3);
  EXPECT_FALSE(r.is_twin(3));
  EXPECT_EQ(r.release_seq(3), 0u);  // its release is forgotten
  EXPECT_EQ(r.twins_of(1), (Ids{2, 4}));
  EXPECT_TRUE(r.is_valid());
}

TEST(TwinRegistry, ReleaseAllReturnsTheTwinsInOrderAsPointsOfTheirOwn) {
  TwinRegistry r = with_points(4, {{3, 1}, {2, 1}});
  r.set_release_seq(2, 5);
  r.set_release_seq(3, 6);
  EXPECT_EQ(r.release_all(1), (Ids{3, 2}));
  EXPECT_TRUE(r.twins_of(1).empty());
  for (const PointId id : {2u, 3u}) {
    EXPECT_EQ(r.host_of(id), id);
    EXPECT_EQ(r.release_seq(id), 0u);
  }
  EXPECT_TRUE(r.is_valid());
}

TEST(TwinRegistry, MergeCarriesTheVertexsTwinsToTheNewHost) {
  TwinRegistry r = with_points(6, {{5, 1}, {3, 2}, {4, 2}, {6, 5}});  // 6 goes to host 1
  const auto moved = r.merge_into(2, 6);  // 6 is a twin of 1: 2 and its twins go to 1
  EXPECT_EQ(Ids(moved.begin(), moved.end()), (Ids{2, 3, 4}));
  EXPECT_EQ(r.twins_of(1), (Ids{5, 6, 2, 3, 4}));
  EXPECT_TRUE(r.twins_of(2).empty());
  for (const PointId id : {2u, 3u, 4u}) EXPECT_EQ(r.host_of(id), 1u);
  EXPECT_TRUE(r.is_valid());
}

TEST(TwinRegistry, IsValidFindsAReleaseQueuedForAPointOfItsOwn) {
  TwinRegistry r = with_points(2);
  r.set_release_seq(2, 4);
  EXPECT_FALSE(r.is_valid());
  r.make_twin(2, 1);
  EXPECT_TRUE(r.is_valid());
}

}  // namespace
