#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "kew/util/chunked_vector.hpp"
#include "kew/util/gentle_growth.hpp"

namespace {

using kew::util::ChunkedVector;

TEST(ChunkedVector, GrowsByOneChunkAndNeverMovesAnElement) {
  ChunkedVector<std::string, 4> v;
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.capacity(), 0u);
  std::string& first = v.emplace_back();
  first = "first";
  const std::string* address = &first;
  for (int i = 1; i < 10; ++i) v.emplace_back() = std::to_string(i);
  EXPECT_EQ(v.size(), 10u);
  EXPECT_EQ(v.capacity(), 12u);  // three chunks of four: never more than one chunk spare
  EXPECT_EQ(&v[0], address);     // growth moved nothing
  EXPECT_EQ(v[0], "first");
  for (int i = 1; i < 10; ++i) EXPECT_EQ(v[static_cast<std::size_t>(i)], std::to_string(i));
}

TEST(ChunkedVector, NewElementsAreValueInitialised) {
  ChunkedVector<double, 2> v;
  for (int i = 0; i < 5; ++i) EXPECT_EQ(v.emplace_back(), 0.0);
  const ChunkedVector<double, 2>& read_only = v;
  EXPECT_EQ(read_only[4], 0.0);
}

TEST(GentleGrowth, CapacityStaysWithinAQuarterOfTheSize) {
  std::vector<int> v;
  for (int i = 0; i < 100000; ++i) {
    kew::util::push_back_gently(v, i);
    // std::vector's own growth would reach twice the size right after a doubling.
    ASSERT_LE(v.capacity(), v.size() + v.size() / 4 + 17) << "at size " << v.size();
  }
  EXPECT_EQ(v[99999], 99999);
}

TEST(GentleGrowth, GrowToFillsOnlyTheNewEntriesAndNeverShrinks) {
  std::vector<unsigned> v{7, 8};
  kew::util::grow_to(v, 5, 3u);
  EXPECT_EQ(v, (std::vector<unsigned>{7, 8, 3, 3, 3}));
  kew::util::grow_to(v, 2, 9u);  // smaller: unchanged
  EXPECT_EQ(v.size(), 5u);
  for (std::size_t n = 6; n < 50000; n += 7) {
    kew::util::grow_to(v, n, 0u);
    ASSERT_LE(v.capacity(), n + n / 4 + 17);
  }
}

}  // namespace
