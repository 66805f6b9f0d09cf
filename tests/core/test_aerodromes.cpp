// The aerodrome table and its nearest-aerodrome lookup (design §4.5), on tables of the
// tests' own (kew's table is data/aerodromes.csv, tested through kew_config in
// tests/config), and the parser of its CSV text: every error names its line.
#include "kew/eligibility/aerodrome_csv.hpp"
#include "kew/eligibility/aerodromes.hpp"
#include "kew/eligibility/eligibility.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace kew::eligibility {
namespace {

constexpr double kNm = 1852.0;

TEST(Aerodromes, NearestOfAGivenTableAndTheFirstOnATie) {
  const AerodromeTable table({{"WEST", 50.0, 7.9, 100}, {"EAST", 50.0, 8.1, 900}, {"TWIN", 50.0, 7.9, 500}});
  EXPECT_EQ(table.nearest(50.0, 7.95, 20 * kNm)->ident, "WEST");
  EXPECT_EQ(table.nearest(50.0, 8.06, 20 * kNm)->ident, "EAST");
  EXPECT_EQ(table.nearest(50.0, 8.0, 1 * kNm), nullptr);  // 3.9 NM from each
}

TEST(Aerodromes, NearestAcrossTheAntimeridianAndAtThePole) {
  const AerodromeTable table({{"NFNM", -16.6907, -179.8772, 70}, {"NZSP", -89.9805, -113.5643, 9301}});
  // Vanua Balavu (Fiji) looked up from the other side of ±180°, 7 NM away.
  EXPECT_EQ(table.nearest(-16.69, 179.99, 10 * kNm)->ident, "NFNM");
  EXPECT_EQ(table.nearest(-16.69, 179.99, 5 * kNm), nullptr);
  // At the pole every meridian is near.
  EXPECT_EQ(table.nearest(-89.99, 20.0, 5 * kNm)->ident, "NZSP");
}

TEST(Aerodromes, FoundByIdent) {
  const AerodromeTable table({{"LSZH", 47.4581, 8.5481, 1416, "Zurich Airport"}, {"LEBL", 41.2971, 2.0785, 12}});
  ASSERT_NE(table.find("LSZH"), nullptr);
  EXPECT_EQ(table.find("LSZH")->name, "Zurich Airport");
  EXPECT_DOUBLE_EQ(table.find("LEBL")->elevation_ft, 12.0);
  EXPECT_EQ(table.find("lszh"), nullptr);
  EXPECT_EQ(table.find("EDDF"), nullptr);
  EXPECT_EQ(table.size(), 2u);
}

TEST(Aerodromes, ATableRefusesRowsOutOfRangeAndAnIdentTwice) {
  EXPECT_THROW(AerodromeTable({{"A", 91.0, 0.0, 0}}), std::invalid_argument);
  EXPECT_THROW(AerodromeTable({{"A", 0.0, 180.5, 0}}), std::invalid_argument);
  EXPECT_THROW(AerodromeTable({{"A", 0.0, 0.0, 25000}}), std::invalid_argument);
  EXPECT_THROW(AerodromeTable({{"", 0.0, 0.0, 0}}), std::invalid_argument);
  EXPECT_THROW(AerodromeTable({{"A", 0.0, 0.0, 0}, {"A", 1.0, 1.0, 0}}), std::invalid_argument);
  EXPECT_EQ(problem({"A", 0.0, 0.0, std::nan("")}), "elevation_ft = nan is outside [-1500, 20000]");
}

TEST(Aerodromes, TheLowerLimitIsTheHigherOfTheSeaLevelFloorAndTheAerodromeHeight) {
  EligibilityConfig config;
  config.aerodromes = std::make_shared<const AerodromeTable>(
      std::vector<Aerodrome>{{"LEGA", 37.1332, -3.6357, 2297}, {"LEBL", 41.2971, 2.0785, 12}});
  const Rules rules(config, {});
  const Aerodrome* at = nullptr;
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(37.1332, -3.6357, &at), 2297.0 + 1000.0);
  ASSERT_NE(at, nullptr);
  EXPECT_EQ(at->ident, "LEGA");
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(41.2971, 2.0785, &at), 1500.0);  // Barcelona, 12 ft
  EXPECT_EQ(at, nullptr);
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(40.0, -40.0, &at), 1500.0);
  // Without a table the limit is lower_limit_ft everywhere.
  EXPECT_DOUBLE_EQ(Rules({}, {}).lower_limit_at(37.1332, -3.6357), 1500.0);
}

// ------------------------------------------------------------------ the CSV text

std::string parse_error(const std::string& text) {
  try {
    parse_aerodrome_csv(text, "t.csv");
  } catch (const AerodromeCsvError& e) {
    return e.what();
  }
  return "no error";
}

TEST(AerodromeCsv, ReadsTheRowsInOrderWithQuotedNamesAndColumnsInAnyOrder) {
  const std::vector<Aerodrome> rows = parse_aerodrome_csv(
      "\xEF\xBB\xBF"
      "name,elevation_ft,ident,lon_deg,lat_deg,remark\r\n"
      "\"Zurich, \"\"Kloten\"\"\",1416,LSZH,8.5481,47.4581,x\r\n"
      "\r\n"
      " Barcelona , -12 ,LEBL,2.0785,41.2971,\n",
      "t.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].ident, "LSZH");
  EXPECT_EQ(rows[0].name, "Zurich, \"Kloten\"");
  EXPECT_DOUBLE_EQ(rows[0].lat_deg, 47.4581);
  EXPECT_DOUBLE_EQ(rows[0].lon_deg, 8.5481);
  EXPECT_DOUBLE_EQ(rows[0].elevation_ft, 1416.0);
  EXPECT_EQ(rows[1].name, "Barcelona");
  EXPECT_DOUBLE_EQ(rows[1].elevation_ft, -12.0);
  // The name is optional.
  EXPECT_EQ(parse_aerodrome_csv("ident,lat_deg,lon_deg,elevation_ft\nLSZH,47.4581,8.5481,1416\n", "t.csv")[0].name,
            "");
}

TEST(AerodromeCsv, EveryErrorNamesItsLine) {
  const std::string header = "ident,lat_deg,lon_deg,elevation_ft,name\n";
  const std::string good = "LSZH,47.4581,8.5481,1416,Zurich\n";
  EXPECT_EQ(parse_error(header + good + "LEBL,41.2971,2.0785,12 ft,Barcelona\n"),
            "t.csv:3: elevation_ft = \"12 ft\" is not a number");
  EXPECT_EQ(parse_error(header + good + "LEBL,41.2971,,12,Barcelona\n"), "t.csv:3: lon_deg = \"\" is not a number");
  EXPECT_EQ(parse_error(header + "LEBL,nan,2.0785,12,Barcelona\n"), "t.csv:2: lat_deg = \"nan\" is not a number");
  EXPECT_EQ(parse_error("ident,lat_deg,elevation_ft\nLSZH,47.4581,1416\n"),
            "t.csv:1: the header has no column lon_deg (it needs ident, lat_deg, lon_deg and elevation_ft)");
  EXPECT_EQ(parse_error(header + good + "LEGA,37.1332,-3.6357,2297,Granada\n" + "LEBL,91.2971,2.0785,12,Barcelona\n"),
            "t.csv:4: LEBL: lat_deg = 91.2971 is outside [-90, 90]");
  EXPECT_EQ(parse_error(header + good + "LEBL,41.2971,2.0785,12\n"), "t.csv:3: 4 fields where the header has 5");
  EXPECT_EQ(parse_error(header + good + "\n" + good), "t.csv:4: LSZH is already on line 2");
  EXPECT_EQ(parse_error(header + good + ",41.2971,2.0785,12,\n"), "t.csv:3: the ident is empty");
  EXPECT_EQ(parse_error(header + "LEBL,41.2971,2.0785,12,\"Barcelona\n"),
            "t.csv:2: a quoted field is not closed on its line");
  EXPECT_EQ(parse_error(header + "LEBL,41.2971,2.0785,12,\"Barcelona\" El Prat\n"),
            "t.csv:2: text after a quoted field");
  EXPECT_EQ(parse_error("ident,ident,lat_deg,lon_deg,elevation_ft\n"), "t.csv:1: the header names the column ident twice");
  EXPECT_EQ(parse_error(""), "t.csv:1: no header row");
  EXPECT_EQ(parse_error(header).substr(0, 22), "t.csv:1: no aerodrome:");
}

TEST(AerodromeCsv, TheErrorCarriesItsLineNumber) {
  try {
    parse_aerodrome_csv("ident,lat_deg,lon_deg,elevation_ft\n\n\nX,1,2,three\n", "t.csv");
    FAIL() << "no error";
  } catch (const AerodromeCsvError& e) {
    EXPECT_EQ(e.line(), 4u);
  }
}

}  // namespace
}  // namespace kew::eligibility
