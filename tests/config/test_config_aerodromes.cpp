// The aerodrome table in the configuration (design §4.5, data/README.md): [eligibility]
// aerodromes_file names a CSV file beside the configuration, kew's table by default; the
// table it names is the one the lower limit stands on, and a file that cannot be read or
// a malformed row is an error naming the file and line.
#include "kew/config/aerodromes.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "kew/config/document.hpp"
#include "kew/config/shared_config.hpp"
#include "kew/eligibility/eligibility.hpp"

namespace kew::config {
namespace {

constexpr double kNm = 1852.0;

/// A fresh directory for one test's files, removed with it.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / ("kew-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_ / "etc");
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::string path(const std::string& relative) const { return (path_ / relative).string(); }
  std::string write(const std::string& relative, const std::string& text) const {
    std::ofstream(path(relative)) << text;
    return path(relative);
  }

 private:
  std::filesystem::path path_;
};

TEST(ConfigAerodromes, KewsTableHoldsEveryContinentWithPlausibleFigures) {
  const SharedConfig c = default_shared_config();
  EXPECT_EQ(c.aerodromes_file, default_aerodromes_file());
  ASSERT_NE(c.pipeline.eligibility.aerodromes, nullptr);
  const eligibility::AerodromeTable& table = *c.pipeline.eligibility.aerodromes;
  // OurAirports' 8,588 with runway data and the supplement's 5 (data/README.md).
  EXPECT_EQ(table.size(), 8593u);
  std::set<std::string> idents;
  for (const eligibility::Aerodrome& a : table.aerodromes()) {
    EXPECT_GE(a.elevation_ft, -1300.0) << a.ident;  // the Dead Sea shore is the lowest
    EXPECT_LE(a.elevation_ft, 15000.0) << a.ident;  // Daocheng Yading, 14,472 ft, the highest
    EXPECT_TRUE(idents.insert(a.ident).second) << a.ident;
  }
}

TEST(ConfigAerodromes, KewsTableGivesTheNearestAerodromeOfReferenceCases) {
  const std::shared_ptr<const eligibility::AerodromeTable> table = load_default_aerodromes();
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
      {"Bangkok Suvarnabhumi, a row of the supplement", 13.69, 100.75, 5.0, "VTBS", 5},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const eligibility::Aerodrome* a = table->nearest(c.lat, c.lon, c.radius_nm * kNm);
    if (!c.ident) {
      EXPECT_EQ(a, nullptr);
      continue;
    }
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->ident, c.ident);
    EXPECT_DOUBLE_EQ(a->elevation_ft, c.elevation_ft);
  }
}

TEST(ConfigAerodromes, ATwoRowFileIsTheTableTheLowerLimitStandsOn) {
  const ScratchDir dir("aerodromes-two");
  dir.write("etc/two.csv",
            "ident,lat_deg,lon_deg,elevation_ft,name\n"
            "HILL,46.0,7.0,4000,A field in the hills\n"
            "LSZH,47.4635,8.5500,1416,Zurich\n");
  // Relative to the configuration file's directory, whatever the working directory.
  const std::string path = dir.write("etc/kew.toml", "[eligibility]\naerodromes_file = \"two.csv\"\n");
  const SharedConfig two = load_shared_config(path);
  EXPECT_EQ(two.aerodromes_file, std::filesystem::path(path).parent_path() / "two.csv");
  ASSERT_EQ(two.pipeline.eligibility.aerodromes->size(), 2u);
  const eligibility::Rules rules(two.pipeline.eligibility, two.pipeline.minima);
  const eligibility::Aerodrome* at = nullptr;
  // 2 NM from a row's aerodrome: its elevation plus aerodrome_height_ft.
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(46.0333, 7.0, &at), 4000.0 + 1000.0);
  ASSERT_NE(at, nullptr);
  EXPECT_EQ(at->ident, "HILL");
  EXPECT_EQ(at->name, "A field in the hills");
  // Over Granada (2,297 ft), an aerodrome of kew's table but not of this file: the sea
  // level floor alone, where kew's table puts the limit 1,000 ft above the field.
  EXPECT_DOUBLE_EQ(rules.lower_limit_at(37.1332, -3.6357, &at), 1500.0);
  EXPECT_EQ(at, nullptr);
  const SharedConfig kews = default_shared_config();
  EXPECT_DOUBLE_EQ(eligibility::Rules(kews.pipeline.eligibility, kews.pipeline.minima).lower_limit_at(37.1332, -3.6357),
                   2297.0 + 1000.0);
  // "" is kew's table.
  const SharedConfig empty = load_shared_config(dir.write("etc/empty.toml", "[eligibility]\naerodromes_file = \"\"\n"));
  EXPECT_EQ(empty.aerodromes_file, default_aerodromes_file());
  EXPECT_EQ(empty.pipeline.eligibility.aerodromes->size(), kews.pipeline.eligibility.aerodromes->size());
}

TEST(ConfigAerodromes, AFileReadAgainIsTheSameTableUntilItIsReplacedOrEdited) {
  const ScratchDir dir("aerodromes-again");
  const std::string path = dir.write("a.csv", "ident,lat_deg,lon_deg,elevation_ft\nHILL,46.0,7.0,4000\n");
  const auto first = load_aerodromes(path);
  EXPECT_EQ(load_aerodromes(path), first);  // parsed once
  // Edited in place to the same size: the modification time tells.
  dir.write("a.csv", "ident,lat_deg,lon_deg,elevation_ft\nHILL,46.0,7.0,4100\n");
  std::filesystem::last_write_time(path, std::filesystem::last_write_time(path) + std::chrono::seconds(5));
  const auto edited = load_aerodromes(path);
  ASSERT_NE(edited, first);
  EXPECT_DOUBLE_EQ(edited->aerodromes().front().elevation_ft, 4100.0);
  // Replaced by rename, with another size.
  const std::string other = dir.write("b.csv", "ident,lat_deg,lon_deg,elevation_ft\nHILL,46.0,7.0,4000\nLOW,45.0,7.0,300\n");
  std::filesystem::rename(other, path);
  EXPECT_EQ(load_aerodromes(path)->size(), 2u);
  // Another file between two reads of the first does not hide the first's changes.
  const std::string kews = default_aerodromes_file();
  EXPECT_EQ(load_aerodromes(kews), load_aerodromes(kews));
  EXPECT_EQ(load_aerodromes(path)->size(), 2u);
}

TEST(ConfigAerodromes, AFileThatCannotBeReadOrAMalformedRowNamesTheFileAndLine) {
  const ScratchDir dir("aerodromes-bad");
  const std::string config_path = dir.path("etc/kew.toml");
  const std::string etc = dir.path("etc");
  const auto refusal = [&](const std::string& toml) {
    dir.write("etc/kew.toml", toml);
    try {
      load_shared_config(config_path);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string key = "[eligibility]\n# kew's table is not enough here\naerodromes_file = \"a.csv\"\n";
  EXPECT_EQ(refusal(key), config_path + ":3: [eligibility] " + etc + "/a.csv: cannot open (No such file or directory)");
  dir.write("etc/a.csv", "ident,lat_deg,lon_deg,elevation_ft\nHILL,46.0,7.0,4000\nLOW,45.0,7.0,ten\n");
  EXPECT_EQ(refusal(key), config_path + ":3: [eligibility] " + etc + "/a.csv:3: elevation_ft = \"ten\" is not a number");
  dir.write("etc/a.csv", "ident,lat_deg,elevation_ft\nHILL,46.0,4000\n");
  EXPECT_EQ(refusal(key), config_path + ":3: [eligibility] " + etc +
                              "/a.csv:1: the header has no column lon_deg (it needs ident, lat_deg, lon_deg and "
                              "elevation_ft)");
  dir.write("etc/a.csv", "ident,lat_deg,lon_deg,elevation_ft\nHILL,46.0,7.0,4000\nSOUTH,-91,7.0,10\n");
  EXPECT_EQ(refusal(key), config_path + ":3: [eligibility] " + etc + "/a.csv:3: SOUTH: lat_deg = -91 is outside [-90, 90]");
  EXPECT_EQ(refusal("[eligibility]\naerodromes_file = 5\n"), config_path + ":2: [eligibility] aerodromes_file must be a string");
}

}  // namespace
}  // namespace kew::config
