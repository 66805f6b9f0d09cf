// The field rules every text decoder shares (protocol/docs/text-formats.md, design §4.3
// and §5.1): a bad required field refuses the record; a bad optional one costs only that
// field, dropped and counted by the track table (fields_dropped), the record kept; a
// track angle within one turn of [0, 360) is brought into it, any other is dropped,
// never wrapped. One table of reference cases, each decoded by its format's decoder and
// then offered to a pipeline.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/formats.hpp"
#include "test_formats_support.hpp"

namespace kew::protocol {
namespace {

using test::decode_all;

std::string ndjson(const std::string& extra) {
  return R"({"t":1714400000,"id":"4CA123","lat":50,"lon":8,"alt_ft":35000)" + extra + "}\n";
}

// SBS: a MSG,4 velocity (ground speed, track, vertical rate), then a MSG,3 position.
std::string sbs(const std::string& gs, const std::string& track, const std::string& rate) {
  const std::string head = "1,1,4CA123,1,2024/04/29,14:13:20.000,2024/04/29,14:13:20.000,";
  return "MSG,4," + head + ",," + gs + "," + track + ",,," + rate + ",,,,,0\n" +
         "MSG,3," + head + ",35000,,,50,8,,,0,0,0,0\n";
}

std::string opensky_csv(const std::string& velocity_mps, const std::string& heading) {
  return "time,icao24,lat,lon,velocity,heading,vertrate,callsign,onground,alert,spi,squawk,"
         "baroaltitude,geoaltitude,lastposupdate,lastcontact\n"
         "1714400000,4ca123,50,8," + velocity_mps + "," + heading + ",0,CS,False,False,False,1000,10000,10100,,\n";
}

std::string opensky_json(const std::string& extra) {
  return R"([{"timestamp":1714400000,"icao24":"4ca123","latitude":50,"longitude":8,"altitude":35000)" + extra +
         "}]";
}

std::string readsb(const std::string& extra) {
  return R"({"now":1714400000,"hex":"4ca123","lat":50,"lon":8,"alt_baro":35000)" + extra + "}\n";
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Case {
  const char* name;
  Format format;
  std::string input;
  /// The decoder's refusal, or "" when the record is decoded.
  const char* refused;
  /// What the decoded record says (only for decoded records).
  std::optional<double> gs_kt, trk_deg;
  /// The field the track table drops, or "" when the record is accepted whole.
  const char* dropped;
};

const Case kCases[] = {
    // The operator's two findings: a negative speed refused the whole record, an angle of
    // 1e10 degrees was wrapped to 280.
    {"ndjson negative speed", Format::Ndjson, ndjson(R"(,"gs_kt":-5,"trk_deg":90)"), "", -5.0, 90.0,
     "speed_negative"},
    {"ndjson absurd track angle", Format::Ndjson, ndjson(R"(,"gs_kt":450,"trk_deg":1e10)"), "", 450.0, 1e10,
     "track_angle_out_of_range"},
    {"ndjson angle a turn below", Format::Ndjson, ndjson(R"(,"trk_deg":-361)"), "", std::nullopt, -361.0,
     "track_angle_out_of_range"},
    {"ndjson angle two turns up", Format::Ndjson, ndjson(R"(,"trk_deg":720)"), "", std::nullopt, 720.0,
     "track_angle_out_of_range"},
    {"ndjson angle -180..180 convention", Format::Ndjson, ndjson(R"(,"trk_deg":-90)"), "", std::nullopt, 270.0, ""},
    {"ndjson angle 360 for north", Format::Ndjson, ndjson(R"(,"trk_deg":360)"), "", std::nullopt, 0.0, ""},
    {"ndjson angle -360", Format::Ndjson, ndjson(R"(,"trk_deg":-360)"), "", std::nullopt, 0.0, ""},
    {"ndjson angle just under two turns", Format::Ndjson, ndjson(R"(,"trk_deg":719.5)"), "", std::nullopt, 359.5, ""},
    {"ndjson speed too high", Format::Ndjson, ndjson(R"(,"gs_kt":5000)"), "", 5000.0, std::nullopt, "speed_too_high"},
    {"ndjson vertical rate too high", Format::Ndjson, ndjson(R"(,"vr_fpm":-165100)"), "", std::nullopt, std::nullopt,
     "vertical_rate_too_high"},
    // A bad required field still refuses the record.
    {"ndjson latitude out of range", Format::Ndjson,
     R"({"t":1714400000,"id":"4CA123","lat":91,"lon":8,"alt_ft":35000,"gs_kt":-5})" "\n", "lat_out_of_range", 0, 0,
     ""},
    {"sbs negative speed", Format::Sbs, sbs("-5", "90", "0"), "", -5.0, 90.0, "speed_negative"},
    {"sbs absurd track angle", Format::Sbs, sbs("450", "1e10", "0"), "", 450.0, 1e10, "track_angle_out_of_range"},
    {"sbs speed not finite", Format::Sbs, sbs("nan", "90", "0"), "", kNaN, 90.0, "speed_not_finite"},
    {"sbs angle -180..180 convention", Format::Sbs, sbs("450", "-90", "0"), "", 450.0, 270.0, ""},
    {"opensky-csv negative speed", Format::OpenskyCsv, opensky_csv("-1", "90"), "", -1.0 * 3600.0 / 1852.0, 90.0,
     "speed_negative"},
    {"opensky-csv absurd heading", Format::OpenskyCsv, opensky_csv("200", "1e10"), "", 200.0 * 3600.0 / 1852.0,
     1e10, "track_angle_out_of_range"},
    {"opensky-json negative speed", Format::OpenskyJson, opensky_json(R"(,"groundspeed":-5,"track":90)"), "", -5.0,
     90.0, "speed_negative"},
    {"opensky-json absurd track", Format::OpenskyJson, opensky_json(R"(,"groundspeed":450,"track":1e10)"), "",
     450.0, 1e10, "track_angle_out_of_range"},
    {"readsb negative speed", Format::ReadsbJson, readsb(R"(,"gs":-5,"track":90)"), "", -5.0, 90.0,
     "speed_negative"},
    {"readsb absurd track", Format::ReadsbJson, readsb(R"(,"gs":450,"track":1e10)"), "", 450.0, 1e10,
     "track_angle_out_of_range"},
};

void expect_field(const std::optional<double>& field, const std::optional<double>& expected, const char* what) {
  if (!expected) {
    EXPECT_FALSE(field) << what;
  } else if (!field) {
    ADD_FAILURE() << "no " << what;
  } else if (std::isnan(*expected)) {
    EXPECT_TRUE(std::isnan(*field)) << what;
  } else {
    EXPECT_DOUBLE_EQ(*field, *expected) << what;
  }
}

TEST(TextFieldRules, ABadOptionalFieldCostsOnlyThatFieldAndNoAngleIsWrappedFromFarAway) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.name);
    auto decoder = make_decoder(c.format);
    const std::vector<TrackReport> reports = decode_all(*decoder, c.input);
    if (*c.refused != '\0') {
      EXPECT_TRUE(reports.empty());
      EXPECT_EQ(decoder->rejections().count(c.refused), 1u) << decoder->rejections().total();
      continue;
    }
    if (reports.size() != 1u) {
      ADD_FAILURE() << reports.size() << " records decoded, " << decoder->rejections().total() << " refused";
      continue;
    }
    EXPECT_EQ(decoder->rejections().total(), 0u);
    expect_field(reports[0].gs_kt, c.gs_kt, "gs_kt");
    expect_field(reports[0].trk_deg, c.trk_deg, "trk_deg");

    Pipeline pipeline;
    pipeline.process(reports[0]);
    EXPECT_EQ(pipeline.statistics().accepted, 1u);
    EXPECT_EQ(pipeline.rejections().total(), 0u);
    const bool drops = *c.dropped != '\0';
    EXPECT_EQ(pipeline.dropped_fields().total(), drops ? 1u : 0u);
    if (drops) {
      EXPECT_EQ(pipeline.dropped_fields().count(c.dropped), 1u);
    }
  }
}

}  // namespace
}  // namespace kew::protocol
