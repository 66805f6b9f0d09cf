// Positions as an AIP writes them (aip_coordinates.hpp): a table of reference cases,
// worked out by hand from degrees, minutes and seconds.
#include "kew/config/aip_coordinates.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kew::config {
namespace {

struct Case {
  const char* text;
  std::vector<geo::GeodeticPosition> expected;
};

TEST(AipCoordinates, ReadsPositionsAsAnAipWritesThem) {
  const Case cases[] = {
      {"471234N 0083456E - 471500N 0084000E - 470830.5N 0084512E",
       {{47.0 + 12.0 / 60 + 34.0 / 3600, 8.0 + 34.0 / 60 + 56.0 / 3600},
        {47.25, 8.0 + 40.0 / 60},
        {47.0 + 8.0 / 60 + 30.5 / 3600, 8.0 + 45.0 / 60 + 12.0 / 3600}}},
      {"4712N 00834E, 4713N 00835E", {{47.2, 8.0 + 34.0 / 60}, {47.0 + 13.0 / 60, 8.0 + 35.0 / 60}}},
      {"335959S 1510000W", {{-(33.0 + 59.0 / 60 + 59.0 / 3600), -151.0}}},
      {"000000n 1800000e", {{0.0, 180.0}}},
      // Written closed, as AIPs often do: the repeated first position is dropped.
      {"471234N 0083456E - 471500N 0084000E - 470830N 0084512E - 471234N 0083456E",
       {{47.0 + 12.0 / 60 + 34.0 / 3600, 8.0 + 34.0 / 60 + 56.0 / 3600},
        {47.25, 8.0 + 40.0 / 60},
        {47.0 + 8.0 / 60 + 30.0 / 3600, 8.0 + 45.0 / 60 + 12.0 / 3600}}},
      {"  ", {}},
  };
  for (const Case& c : cases) {
    std::string error;
    const auto got = parse_aip_coordinates(c.text, error);
    ASSERT_TRUE(got) << c.text << ": " << error;
    ASSERT_EQ(got->size(), c.expected.size()) << c.text;
    for (std::size_t i = 0; i < got->size(); ++i) {
      EXPECT_NEAR((*got)[i].lat_deg, c.expected[i].lat_deg, 1e-12) << c.text << " position " << i + 1;
      EXPECT_NEAR((*got)[i].lon_deg, c.expected[i].lon_deg, 1e-12) << c.text << " position " << i + 1;
    }
  }
}

TEST(AipCoordinates, RefusesWhatIsNotAPositionNamingIt) {
  const std::pair<const char*, const char*> cases[] = {
      {"471234X 0083456E", "position 1: latitude \"471234X\" does not end in N or S"},
      {"471234N 0083456E - 476034N 0083456E", "position 2: latitude \"476034N\": minutes and seconds are below 60"},
      {"911234N 0083456E", "position 1: latitude \"911234N\" is beyond 90°"},
      {"471234N 1813456E", "position 1: longitude \"1813456E\" is beyond 180°"},
      {"471234N", "position 1: longitude missing"},
      {"471234N 083456E", "position 1: longitude \"083456E\" is not DDDMMSS[.s] (or DDDMM) with E/W"},
      {"471234N 0083456E - clockwise arc", "position 2: latitude \"clockwise\" does not end in N or S"},
      {"4712.5N 00834E", "position 1: latitude \"4712.5N\": a fraction belongs to the seconds"},
  };
  for (const auto& [text, message] : cases) {
    std::string error;
    EXPECT_FALSE(parse_aip_coordinates(text, error)) << text;
    EXPECT_EQ(error, message) << text;
  }
}

}  // namespace
}  // namespace kew::config
