// Golden tests of the ASTERIX decoders on real recordings: the bundled fixtures of
// tests/data/asterix (expected values from tshark 4.0.17 and kew's documented rules, see
// tests/data/asterix/SOURCE.md) and, when present, the shared recordings.

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "kew/protocol/asterix/asterix_decoder.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;
using test::exists;
using test::read_file;
using test::shared_path;

std::string fixture_path(const std::string& name) {
  return std::string(KEW_TEST_DATA_DIR) + "/asterix/" + name;
}

/// A radar site (WGS84 degrees, metres above the ellipsoid).
struct Site {
  double lat_deg, lon_deg, height_m;
};

/// Nominal site given to every radar of a bundled CAT048 fixture: the real sites are not
/// published, and the positions are checked against an independent conversion from the
/// same site, so any site will do.
constexpr Site kNominalSite{45.0, 16.0, 100.0};

/// The Barcelona radar (SAC 20, SIC 129) of the UPC recording, as the MANIFEST gives it:
/// 41°18'02.5284"N 02°06'07.4095"E, antenna about 27 m up.
constexpr Site kBarcelonaSite{41.0 + 18.0 / 60 + 2.5284 / 3600, 2.0 + 6.0 / 60 + 7.4095 / 3600, 27.0};

/// Position of a target at slant range `rho_m`, azimuth `theta_deg`, height `height_m`,
/// computed independently of kew's method: the straight line of sight from the antenna
/// in the site's local east-north-up frame on the WGS84 ellipsoid, its elevation found by
/// bisection so that the end point has the target's height.
std::pair<double, double> independent_polar_to_wgs84(double site_lat, double site_lon,
                                                     double site_height, double rho_m,
                                                     double theta_deg, double height_m) {
  const GeographicLib::LocalCartesian enu(site_lat, site_lon, site_height);
  const double theta = theta_deg * std::numbers::pi / 180.0;
  double low = -std::numbers::pi / 2, high = std::numbers::pi / 2, lat = 0, lon = 0, h = 0;
  for (int i = 0; i < 100; ++i) {
    const double elevation = (low + high) / 2;
    enu.Reverse(rho_m * std::cos(elevation) * std::sin(theta),
                rho_m * std::cos(elevation) * std::cos(theta), rho_m * std::sin(elevation), lat,
                lon, h);
    (h < height_m ? low : high) = elevation;
  }
  return {lat, lon};
}

double distance_m(double lat1, double lon1, double lat2, double lon2) {
  double s12 = 0;
  GeographicLib::Geodesic::WGS84().Inverse(lat1, lon1, lat2, lon2, s12);
  return s12;
}

/// One expected/<fixture>.txt: "key value" lines, "reject reason count", "radar SAC.SIC",
/// "sample key=value ...".
struct Expected {
  std::map<std::string, std::string> values;
  std::map<std::string, std::uint64_t> rejections;
  std::vector<std::pair<int, int>> radars;
  std::vector<std::map<std::string, std::string>> samples;

  double number(const std::string& key) const { return std::stod(values.at(key)); }
};

Expected read_expected(const std::string& fixture) {
  std::string name = fixture;
  name.replace(name.find('/'), 1, "__");
  std::ifstream in(fixture_path("expected/" + name + ".txt"));
  EXPECT_TRUE(in.good()) << "missing expected file for " << fixture;
  Expected expected;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "reject") {
      std::string reason;
      std::uint64_t count = 0;
      words >> reason >> count;
      expected.rejections[reason] = count;
    } else if (key == "radar") {
      int sac = 0, sic = 0;
      char dot = 0;
      words >> sac >> dot >> sic;
      expected.radars.emplace_back(sac, sic);
    } else if (key == "sample") {
      std::map<std::string, std::string> sample;
      std::string pair;
      while (words >> pair) {
        const auto eq = pair.find('=');
        sample[pair.substr(0, eq)] = pair.substr(eq + 1);
      }
      expected.samples.push_back(sample);
    } else {
      std::string value;
      words >> value;
      expected.values[key] = value;
    }
  }
  return expected;
}

AsterixFraming framing_of(const std::string& name) {
  if (name == "ff") return AsterixFraming::FinalFormat;
  if (name == "pcap") return AsterixFraming::Pcap;
  return AsterixFraming::RawBlocks;
}

const TrackReport* find_report(const std::vector<TrackReport>& reports,
                               const std::map<std::string, std::string>& sample) {
  const double t = std::stod(sample.at("t"));
  for (const TrackReport& r : reports) {
    if (r.source == sample.at("src") && r.id == sample.at("id") && std::fabs(r.t - t) < 1e-6) return &r;
  }
  return nullptr;
}

void expect_optional_near(const std::optional<double>& actual,
                          const std::map<std::string, std::string>& sample, const std::string& key,
                          double tolerance) {
  const auto it = sample.find(key);
  if (it == sample.end()) {
    EXPECT_FALSE(actual.has_value()) << key;
    return;
  }
  ASSERT_TRUE(actual.has_value()) << key;
  EXPECT_NEAR(*actual, std::stod(it->second), tolerance) << key;
}

void expect_sample(const TrackReport& r, const std::map<std::string, std::string>& sample,
                   const Site& site) {
  SCOPED_TRACE(sample.at("src") + " " + sample.at("id") + " t=" + sample.at("t"));
  if (sample.count("lat")) {
    EXPECT_NEAR(r.lat_deg, std::stod(sample.at("lat")), 1e-9);
    EXPECT_NEAR(r.lon_deg, std::stod(sample.at("lon")), 1e-9);
  } else {
    // CAT048: compare with the independent conversion of tshark's RHO/THETA.
    const auto [lat, lon] = independent_polar_to_wgs84(
        site.lat_deg, site.lon_deg, site.height_m, std::stod(sample.at("rho_nm")) * 1852.0,
        std::stod(sample.at("theta_deg")), std::stod(sample.at("alt_ft")) * 0.3048);
    // The decoder's spherical (Gaussian radius) slant-to-ground conversion and this
    // ellipsoidal line of sight differ by well under a metre to 250 NM; 2 m is still far
    // below the resolution of RHO itself (1/256 NM = 7.2 m).
    EXPECT_LT(distance_m(r.lat_deg, r.lon_deg, lat, lon), 2.0);
  }
  EXPECT_NEAR(r.alt_ft, std::stod(sample.at("alt_ft")), 1e-9);
  expect_optional_near(r.gs_kt, sample, "gs_kt", 1e-6);
  expect_optional_near(r.trk_deg, sample, "trk_deg", 1e-6);
  expect_optional_near(r.vr_fpm, sample, "vr_fpm", 1e-9);
  if (sample.count("mode3a")) {
    EXPECT_EQ(r.mode3a, std::stoi(sample.at("mode3a")));
  } else {
    EXPECT_FALSE(r.mode3a.has_value());
  }
  EXPECT_EQ(r.callsign, sample.at("cs") == "-" ? "" : sample.at("cs"));
  EXPECT_EQ(r.on_ground, sample.at("gnd") == "1");
  if (sample.count("addr")) {
    EXPECT_EQ(r.address, std::optional<std::uint32_t>(std::stoul(sample.at("addr"), nullptr, 16)));
  } else {
    EXPECT_FALSE(r.address.has_value());
  }
  EXPECT_EQ(r.coasting, sample.at("coast") == "1");
  EXPECT_EQ(r.track_end, sample.at("end") == "1");
}

/// Decodes `data` with the framing and radars of expected/<name>.txt (every radar at
/// `site`) and checks counts, time span, rejections and samples; returns the reports.
std::vector<TrackReport> expect_golden(const std::string& name, const std::string& data,
                                       const Site& site) {
  const Expected expected = read_expected(name);
  AsterixOptions options;
  for (const auto& [sac, sic] : expected.radars) {
    options.radars.push_back({static_cast<std::uint8_t>(sac), static_cast<std::uint8_t>(sic),
                              site.lat_deg, site.lon_deg, site.height_m});
  }
  auto decoder = make_asterix_decoder(framing_of(expected.values.at("framing")), options);
  auto reports = decode_all(*decoder, data);

  EXPECT_EQ(reports.size(), expected.number("reports"));
  const test::Summary summary = test::summarize(reports);
  std::set<std::string> keys;
  std::set<std::uint32_t> addresses;
  std::size_t coasting = 0, track_ends = 0;
  for (const TrackReport& r : reports) {
    keys.insert(r.source + "/" + r.id);
    if (r.address) addresses.insert(*r.address);
    coasting += r.coasting ? 1 : 0;
    track_ends += r.track_end ? 1 : 0;
  }
  EXPECT_EQ(keys.size(), expected.number("distinct_ids"));
  if (expected.values.count("distinct_addresses")) {
    EXPECT_EQ(addresses.size(), expected.number("distinct_addresses"));
  }
  // tshark's I062/080 CST, TSE and I048/170 TRE: an independent check of kew's bit positions.
  if (expected.values.count("coasting")) {
    EXPECT_EQ(coasting, expected.number("coasting"));
    EXPECT_EQ(track_ends, expected.number("track_ends"));
  }
  if (!reports.empty()) {
    EXPECT_DOUBLE_EQ(summary.t_min, expected.number("t_first"));
    EXPECT_DOUBLE_EQ(summary.t_max, expected.number("t_last"));
  }
  EXPECT_EQ(decoder->rejections().by_reason(),
            (std::map<std::string, std::uint64_t, std::less<>>(expected.rejections.begin(),
                                                                 expected.rejections.end())));
  // Every record tshark decodes is either reported or rejected for a counted reason.
  std::uint64_t record_rejections = 0;
  for (const auto& [reason, count] : expected.rejections) {
    if (reason != "asterix_category_ignored") record_rejections += count;
  }
  EXPECT_EQ(reports.size() + record_rejections, expected.number("tshark_records"));

  EXPECT_FALSE(expected.samples.empty() && !reports.empty());
  for (const auto& sample : expected.samples) {
    const TrackReport* report = find_report(reports, sample);
    EXPECT_NE(report, nullptr) << "no report " << sample.at("src") << " " << sample.at("id");
    if (report != nullptr) expect_sample(*report, sample, site);
  }
  return reports;
}

class AsterixGolden : public testing::TestWithParam<const char*> {};

TEST_P(AsterixGolden, MatchesTsharkAndTheDocumentedRules) {
  const std::string fixture = GetParam();
  expect_golden(fixture, read_file(fixture_path(fixture)), kNominalSite);
}

INSTANTIATE_TEST_SUITE_P(
    BundledFixtures, AsterixGolden,
    testing::Values("jade/final_frame_062_first3min.ff", "jade/JADE_final_frame_062_one_packet_sample2.ff",
                    "jade/JADE_NATS_CAT048_119bytes_TCAS.ff", "croatiacontrol/cat_034_048.pcap",
                    "croatiacontrol/cat_062_065.pcap", "croatiacontrol/cat062cat065.raw",
                    "croatiacontrol/cat21_re.ast", "croatiacontrol/cat048.raw",
                    "croatiacontrol/cat034.raw", "jasterix/cat021ed2.1.bin",
                    "jasterix/cat048ed1.15.bin", "jasterix/cat048ed1.23.bin",
                    "jasterix/cat062ed1.12.bin", "jasterix/cat062ed1.16.bin",
                    "asterix4py/cat062.ast"),
    [](const testing::TestParamInfo<const char*>& param_info) {
      std::string name = param_info.param;
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

// ---- Bundled fixtures tshark cannot serve as reference for ---------------------------

TEST(AsterixMalformedFixtures, OldCat062EditionIsRejectedRecordByRecord) {
  // croatiacontrol/asterix.pcap carries CAT062 of a pre-1.0 edition (2008) whose UAP differs
  // from every edition kew walks; tshark itself flags 64 of its 100 frames malformed. Each
  // record that cannot be walked ends its block with a counted reason; nothing crashes and
  // no wrong report comes out. The counts are kew's own (regression values).
  auto decoder = make_asterix_decoder(AsterixFraming::Pcap);
  const auto reports = decode_all(*decoder, read_file(fixture_path("croatiacontrol/asterix.pcap")));
  EXPECT_TRUE(reports.empty());
  const test::Counts expected{{"asterix_item_overflow", 43},
                              {"asterix_missing_altitude", 29},
                              {"asterix_tentative_track", 19},
                              {"asterix_unknown_item", 29}};
  EXPECT_EQ(decoder->rejections().by_reason(), expected);
  // tshark sees 100 blocks: 72 of them end at a record kew cannot walk (overflow or unknown
  // item, one count each); the 48 records that do walk lack an altitude or are tentative.
  EXPECT_EQ(read_expected("croatiacontrol/asterix.pcap").number("tshark_blocks"), 100.0);
}

TEST(AsterixMalformedFixtures, WrappedSubFramesAreNotDataBlocks) {
  // cat_001_002.pcap: one UDP payload of 6 sub-frames, each a 6-byte wrapper header then a
  // data block (MANIFEST). The payload does not start with a data block header whose
  // length fits, so the datagram is counted once and dropped.
  auto decoder = make_asterix_decoder(AsterixFraming::Pcap);
  const auto reports = decode_all(*decoder, read_file(fixture_path("croatiacontrol/cat_001_002.pcap")));
  EXPECT_TRUE(reports.empty());
  EXPECT_EQ(decoder->rejections().by_reason(), (test::Counts{{"asterix_bad_block_length", 1}}));
}

TEST(AsterixCat021, Edition026DecodedByHand) {
  // jasterix/cat021ed0.26.bin (36 bytes), decoded by hand since tshark 4.0.17 has no 0.26:
  //   15 0024 | FSPEC fb 81 13 80: FRN 1-5, 7, 8, 18, 21, 22
  //   010 00 05 | 040 40 30 (GBS: on the ground) | 030 1c293e = 1845566/128 s
  //   130 006e4cc9 ffe606d6 (180/2^25 deg) | 080 496c2e | 090 0008 | 210 08
  //   170 18dc31ca0820 = "FM012   " | 200 00 | 020 15.
  // No I021/145 or 140: a ground target without altitude is kept at 0 ft.
  auto decoder = make_asterix_decoder(AsterixFraming::RawBlocks);
  const auto reports = decode_all(*decoder, read_file(fixture_path("jasterix/cat021ed0.26.bin")));
  ASSERT_EQ(reports.size(), 1U);
  const TrackReport& r = reports[0];
  EXPECT_EQ(r.source, "cat021/0.5");
  EXPECT_EQ(r.id, "496C2E");
  EXPECT_EQ(r.address, std::optional<std::uint32_t>(0x496C2E));
  EXPECT_DOUBLE_EQ(r.t, 1845566 / 128.0);
  EXPECT_DOUBLE_EQ(r.lat_deg, 0x006e4cc9 * 180.0 / 33554432.0);
  EXPECT_DOUBLE_EQ(r.lon_deg, -1702186 * 180.0 / 33554432.0);
  EXPECT_EQ(r.alt_ft, 0.0);
  EXPECT_TRUE(r.on_ground);
  EXPECT_EQ(r.callsign, "FM012");
  EXPECT_FALSE(r.gs_kt.has_value());
  EXPECT_FALSE(r.mode3a.has_value());
  EXPECT_EQ(decoder->rejections().total(), 0U);
}

// ---- Shared recordings (read in place; skipped when ../shared is absent) ----------------

TEST(AsterixSharedRecordings, UpcBarcelonaCat048Hour) {
  // No licence: read from the shared directory only, never bundled (MANIFEST).
  const std::string path = shared_path("upc-bcn-cat048/230502-est-080001_BCN_60MN_08_09.ast");
  if (!exists(path)) GTEST_SKIP() << "shared recording absent (never bundled, no licence): " << path;
  const auto reports = expect_golden("shared/upc-bcn-cat048", read_file(path), kBarcelonaSite);
  // The MANIFEST's figures: 44,085 records (expect_golden: every one reported or rejected
  // for a counted reason), 177 Mode S addresses, 60 minutes.
  std::set<std::uint32_t> addresses;
  double t_min = 1e300, t_max = -1e300, farthest_m = 0;
  for (const TrackReport& r : reports) {
    if (r.address) addresses.insert(*r.address);
    t_min = std::min(t_min, r.t);
    t_max = std::max(t_max, r.t);
    farthest_m = std::max(farthest_m, distance_m(kBarcelonaSite.lat_deg, kBarcelonaSite.lon_deg,
                                                 r.lat_deg, r.lon_deg));
    EXPECT_EQ(r.source, "cat048/20.129");
  }
  EXPECT_EQ(addresses.size(), 177U);
  EXPECT_NEAR((t_max - t_min) / 60.0, 60.0, 0.05);
  // Plausible around Barcelona: the recording's polar plots reach about 60 NM, and the
  // ground range never exceeds the slant range.
  EXPECT_LT(farthest_m, 61.0 * 1852.0);
  EXPECT_GT(farthest_m, 40.0 * 1852.0);
}

TEST(AsterixSharedRecordings, JadeCat062FinalFormatHalfHour) {
  const std::string path = shared_path("jade-cat062-ff/final_frame_062_30min.ff");
  if (!exists(path)) GTEST_SKIP() << "shared recording absent: " << path;
  const auto reports = expect_golden("shared/jade-cat062-30min", read_file(path), kNominalSite);
  // MANIFEST: 34,957 records over 30.0 min (ToD 14:44:41-15:14:40). 168 of its 191 tracks
  // carry an altitude at least once; the others are all counted "asterix_missing_altitude".
  const test::Summary summary = test::summarize(reports);
  EXPECT_NEAR((summary.t_max - summary.t_min) / 60.0, 30.0, 0.05);
  EXPECT_EQ(static_cast<int>(summary.t_min) / 60, 14 * 60 + 44);
  EXPECT_EQ(static_cast<int>(summary.t_max) / 60, 15 * 60 + 14);
}

}  // namespace
}  // namespace kew::protocol
