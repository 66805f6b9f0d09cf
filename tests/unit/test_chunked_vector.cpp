#include <gtest/gtest.h>

#include <string>

#include "kew/util/chunked_vector.hpp"

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

}  // namespace
