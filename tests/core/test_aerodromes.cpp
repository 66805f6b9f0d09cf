// The bundled aerodrome table and its nearest-aerodrome lookup (design §4.5): reference
// cases from the AIP elevations, the antimeridian and the poles.
#include "kew/eligibility/aerodromes.hpp"
#include "kew/eligibility/eligibility.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace kew::eligibility {
namespace {

constexpr double kNm = 1852.0;

TEST(Aerodromes, TheBundledTableHoldsEveryContinentWithPlausibleFigures) {
  const auto table = bundled_aerodromes();
  EXPECT_GT(table.size(), 8000u);
  std::set<std::string_view> idents;
  for (const Aerodrome& a : table) {
    EXPECT_GE(a.lat_deg, -90.0);
    EXPECT_LE(a.lat_deg, 90.0);
    EXPECT_GE(a.lon_deg, -180.0);
    EXPECT_LE(a.lon_deg, 180.0);
    EXPECT_GE(a.elevation_ft, -1300.0) << a.ident;  // the Dead Sea shore is the lowest
    EXPECT_LE(a.elevation_ft, 15000.0) << a.ident;  // Daocheng Yading, 14,472 ft, the highest
    EXPECT_TRUE(idents.insert(a.ident).second) << a.ident;
  }
}

TEST(Aerodromes, NearestAerodromeReferenceCases) {
  struct Case {
    const char* name;
    double lat, lon, radius_nm;
    const char* ident;  // null: none within the radius
    double elevation_ft;
  };
  const Case cases[] = {
      {"Zurich, on the field", 47.4581, 8.5481, 5.0, "LSZH", 1416},
      {"Denver, 3 NM south of the field", 39.81, -104.67, 5.0, "KDEN", 5431},
      {"Barcelona", 41.2971, 2.0785, 5.0, "LEBL", 12},
      {"Granada", 37.1332, -3.6357, 2.0, "LEGA", 2297},
      {"mid-Atlantic: none within 5 NM", 40.0, -40.0, 5.0, nullptr, 0},
      {"Vanua Balavu (Fiji), looked up from across the antimeridian", -16.69, 179.99, 10.0, "NFNM", 70},
      {"the South Pole", -89.99, 20.0, 5.0, "NZSP", 9301},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Aerodrome* a = AerodromeIndex::bundled().nearest(c.lat, c.lon, c.radius_nm * kNm);
    if (!c.ident) {
      EXPECT_EQ(a, nullptr);
      continue;
    }
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->ident, c.ident);
    EXPECT_DOUBLE_EQ(a->elevation_ft, c.elevation_ft);
  }
}

TEST(Aerodromes, NearestOfAGivenTableAndTheFirstOnATie) {
  const Aerodrome table[] = {{"WEST", 50.0, 7.9, 100}, {"EAST", 50.0, 8.1, 900}, {"TWIN", 50.0, 7.9, 500}};
  const AerodromeIndex index(table);
  EXPECT_EQ(index.nearest(50.0, 7.95, 20 * kNm)->ident, "WEST");
  EXPECT_EQ(index.nearest(50.0, 8.06, 20 * kNm)->ident, "EAST");
  EXPECT_EQ(index.nearest(50.0, 8.0, 1 * kNm), nullptr);  // 3.9 NM from each
}

TEST(Aerodromes, TheLowerLimitIsTheHigherOfTheSeaLevelFloorAndTheAerodromeHeight) {
  const Rules rules({}, {});
  const Aerodrome* at = nullptr;
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(37.1332, -3.6357, &at), 2297.0 + 1000.0);
  ASSERT_NE(at, nullptr);
  EXPECT_EQ(at->ident, "LEGA");
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(41.2971, 2.0785, &at), 1500.0);  // Barcelona, 12 ft
  EXPECT_EQ(at, nullptr);
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(40.0, -40.0, &at), 1500.0);
}

}  // namespace
}  // namespace kew::eligibility
