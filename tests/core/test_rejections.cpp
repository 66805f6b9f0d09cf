#include "kew/util/rejections.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kew {
namespace {

TEST(Rejections, CountsByReasonInReasonOrder) {
  Rejections r;
  r.reject("nan_position");
  r.reject("bad_json");
  r.reject("nan_position");
  EXPECT_EQ(r.total(), 3u);
  EXPECT_EQ(r.count("nan_position"), 2u);
  EXPECT_EQ(r.count("bad_json"), 1u);
  EXPECT_EQ(r.count("never_seen"), 0u);
  ASSERT_EQ(r.by_reason().size(), 2u);
  EXPECT_EQ(r.by_reason().begin()->first, "bad_json");
}

TEST(Rejections, ReportsABurstThenPowersOfTwoMultiples) {
  Rejections r(3);
  std::vector<std::string> seen;
  r.set_reporter([&](std::string_view, std::string_view message) { seen.emplace_back(message); });
  for (int i = 1; i <= 30; ++i) r.reject("flood", std::to_string(i));
  // 1..3 in the burst, then 6, 12, 24.
  EXPECT_EQ(seen, (std::vector<std::string>{"1", "2", "3", "6", "12", "24"}));
  EXPECT_EQ(r.count("flood"), 30u);
}

TEST(Rejections, MergeAddsCounts) {
  Rejections a, b;
  a.reject("x");
  b.reject("x");
  b.reject("y");
  a.merge(b);
  EXPECT_EQ(a.count("x"), 2u);
  EXPECT_EQ(a.count("y"), 1u);
  EXPECT_EQ(a.total(), 3u);
}

}  // namespace
}  // namespace kew
