// Alert stream JSON (design §5.3): byte-exact objects (a formatting change must be
// deliberate and show up here), string escaping for any bytes, the ?WATCH request, and
// encode → read round trips within the documented precision.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/protocol/version.hpp"

namespace kew::protocol {
namespace {

AlertEvent update_event() {
  AlertEvent e;
  e.id = "9f3c2a51d0e4b7c8";
  e.number = 42;
  e.seq = 17;
  e.state = AlertState::Update;
  e.severity = Severity::Warning;
  e.t = 1714400000.25;
  e.opened_t = 1714399990.0;
  e.a = {"4CA123", "sbs", "BAW123", 12, 51.47, -0.45, 35000.0, 450.0, 270.0, -0.2};
  e.b = {"3C6586", "sbs", "DLH4AB", 13, 51.5123456789, -0.3, 35500.4, 430.26, 90.04, -1500.0};
  e.t_los_s = 41.04;
  e.t_cpa_s = 63.46;
  e.cpa_h_m = 1234.56;
  e.cpa_v_ft = 300.4;
  e.sep_h_m = 15000.0;
  e.sep_v_ft = 500.0;
  return e;
}

constexpr const char* kUpdateLine =
    R"({"class":"ALERT","kind":"stca","id":"9f3c2a51d0e4b7c8","number":42,"seq":17,"state":"update",)"
    R"("severity":"warning","t":1714400000.250,"t_open":1714399990.000,)"
    R"("a":{"id":"4CA123","src":"sbs","cs":"BAW123","lat":51.470000,"lon":-0.450000,)"
    R"("alt_ft":35000,"gs_kt":450.0,"trk_deg":270.0,"vr_fpm":0,"tn":12},)"
    R"("b":{"id":"3C6586","src":"sbs","cs":"DLH4AB","lat":51.512346,"lon":-0.300000,)"
    R"("alt_ft":35500,"gs_kt":430.3,"trk_deg":90.0,"vr_fpm":-1500,"tn":13},)"
    R"("t_los_s":41.0,"t_cpa_s":63.5,"cpa_h_m":1234.6,"cpa_v_ft":300,"sep_h_m":15000.0,)"
    R"("sep_v_ft":500,"hypothesis":"linear","region":"","ack":false})"
    "\n";

TEST(AlertJson, AlertObjectIsByteExact) {
  std::string out;
  append_alert_json(out, update_event(), 17);
  EXPECT_EQ(out, kUpdateLine);
}

TEST(AlertJson, EndObjectCarriesItsReason) {
  AlertEvent e = update_event();
  e.state = AlertState::End;
  e.end_reason = AlertEndReason::TrackDropped;
  e.acknowledged = true;
  e.b.callsign.clear();
  e.t_los_s = std::nan("");
  std::string out = "previous line\n";  // appends, never overwrites
  append_alert_json(out, e, 18);
  EXPECT_EQ(out,
            "previous line\n"
            R"({"class":"ALERT","kind":"stca","id":"9f3c2a51d0e4b7c8","number":42,"seq":18,"state":"end",)"
            R"("reason":"track_dropped","severity":"warning","t":1714400000.250,)"
            R"("t_open":1714399990.000,)"
            R"("a":{"id":"4CA123","src":"sbs","cs":"BAW123","lat":51.470000,"lon":-0.450000,)"
            R"("alt_ft":35000,"gs_kt":450.0,"trk_deg":270.0,"vr_fpm":0,"tn":12},)"
            R"("b":{"id":"3C6586","src":"sbs","cs":"","lat":51.512346,"lon":-0.300000,)"
            R"("alt_ft":35500,"gs_kt":430.3,"trk_deg":90.0,"vr_fpm":-1500,"tn":13},)"
            R"("t_los_s":null,"t_cpa_s":63.5,"cpa_h_m":1234.6,"cpa_v_ft":300,)"
            R"("sep_h_m":15000.0,"sep_v_ft":500,"hypothesis":"linear","region":"","ack":true})"
            "\n");
}

TEST(AlertJson, AlertSaysWhichHypothesisFoundItAndWhichRegionJudgedIt) {
  const std::vector<std::pair<Hypothesis, std::string>> hypotheses{
      {Hypothesis::Linear, "linear"},
      {Hypothesis::LevelOff, "level_off"},
      {Hypothesis::Turn, "turn"},
      {Hypothesis::Proximity, "proximity"},
  };
  AlertStreamReader reader;
  for (const auto& [hypothesis, name] : hypotheses) {
    AlertEvent e = update_event();
    e.hypothesis = hypothesis;
    e.region = name == "turn" ? "" : "EGLL \"TMA\"";  // the defaults, or a named region
    std::string line;
    append_alert_json(line, e, 17);
    const std::string region = e.region.empty() ? R"("")" : R"("EGLL \"TMA\"")";
    EXPECT_NE(line.find(R"(,"sep_v_ft":500,"hypothesis":")" + name + R"(","region":)" + region +
                        R"(,"ack":false})"),
              std::string::npos)
        << line;
    ASSERT_TRUE(reader.read(line)) << reader.error();
    EXPECT_EQ(reader.alert().hypothesis, hypothesis) << name;
    EXPECT_EQ(reader.alert().region, e.region) << name;
  }
}

TEST(AlertStreamReader, AlertOfAnOlderServerWasFoundByTheLinearPredictionWithTheDefaults) {
  std::string line = kUpdateLine;
  line.replace(line.find(R"("hypothesis":"linear","region":"",)"), 34, "");
  ASSERT_EQ(line.find("hypothesis"), std::string::npos);
  AlertStreamReader reader;
  AlertEvent turning = update_event();  // the reader's previous alert does not leak
  turning.hypothesis = Hypothesis::Turn;
  turning.region = "north";
  std::string previous;
  append_alert_json(previous, turning, 16);
  ASSERT_TRUE(reader.read(previous)) << reader.error();
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.alert().hypothesis, Hypothesis::Linear);
  EXPECT_EQ(reader.alert().region, "");
}

TEST(AlertJson, AnAreaWarningNamesItsVolumeAndHasNoSecondAircraft) {
  AlertEvent e = update_event();
  e.kind = AlertKind::Apw;
  e.b = AlertParty{};
  e.volume = "ED-R 138";
  e.volume_kind = "restricted";
  e.region.clear();
  std::string out;
  append_alert_json(out, e, 17);
  EXPECT_EQ(out,
            R"({"class":"ALERT","kind":"apw","id":"9f3c2a51d0e4b7c8","number":42,"seq":17,"state":"update",)"
            R"("severity":"warning","t":1714400000.250,"t_open":1714399990.000,)"
            R"("a":{"id":"4CA123","src":"sbs","cs":"BAW123","lat":51.470000,"lon":-0.450000,)"
            R"("alt_ft":35000,"gs_kt":450.0,"trk_deg":270.0,"vr_fpm":0,"tn":12},)"
            R"("volume":"ED-R 138","volume_kind":"restricted","t_los_s":41.0,"hypothesis":"linear","ack":false})"
            "\n");
  AlertStreamReader reader;
  ASSERT_TRUE(reader.read(out)) << reader.error();
  EXPECT_EQ(reader.alert().kind, AlertKind::Apw);
  EXPECT_EQ(reader.alert().volume, "ED-R 138");
  EXPECT_TRUE(reader.alert().b.id.empty());
  // An area warning without its volume is refused; a pair alert without a kind is read
  // as a pair's (servers before "kind").
  std::string broken = out;
  broken.replace(broken.find(R"("volume":"ED-R 138",)"), 20, "");
  EXPECT_FALSE(reader.read(broken));
  std::string older = kUpdateLine;
  older.replace(older.find(R"("kind":"stca",)"), 14, "");
  ASSERT_TRUE(reader.read(older)) << reader.error();
  EXPECT_EQ(reader.alert().kind, AlertKind::Stca);
}

TEST(AlertJson, AbsurdMagnitudesArePrintedShortAndReadBack) {
  AlertEvent e = update_event();
  e.a.vr_fpm = 5.555555555555556e41;  // 0 decimals: would be a 42-digit integer
  e.sep_h_m = -1e300;                 // 1 decimal: would be 300 digits
  e.cpa_h_m = 999999999999999.9;      // just below the limit: fixed notation
  std::string line;
  append_alert_json(line, e, 1);
  EXPECT_NE(line.find(R"("vr_fpm":5.555555555555556e+41,)"), std::string::npos) << line;
  EXPECT_NE(line.find(R"("sep_h_m":-1e+300,)"), std::string::npos) << line;
  EXPECT_NE(line.find(R"("cpa_h_m":999999999999999.9,)"), std::string::npos) << line;
  AlertStreamReader reader;
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.alert().a.vr_fpm, e.a.vr_fpm);
  EXPECT_EQ(reader.alert().sep_h_m, e.sep_h_m);
}

TEST(AlertJson, SnapshotHoldsCompleteAlertObjectsWithTheirOwnSeq) {
  AlertEvent first = update_event();
  AlertEvent second = update_event();
  second.id = "77";
  second.number = 43;
  second.seq = 20;
  second.state = AlertState::New;
  second.severity = Severity::Caution;
  std::string out;
  append_alerts_snapshot_json(out, std::vector<AlertEvent>{first, second}, 99);
  std::string first_object = kUpdateLine;
  first_object.pop_back();
  std::string second_line;
  append_alert_json(second_line, second, 20);
  second_line.pop_back();
  EXPECT_EQ(out, R"({"class":"ALERTS","seq":99,"alerts":[)" + first_object + "," + second_line + "]}\n");
  EXPECT_NE(second_line.find(R"("id":"77","number":43,"seq":20,"state":"new")"), std::string::npos);

  std::string by_pointer;
  const std::vector<const AlertEvent*> pointers{&first, &second};
  append_alerts_snapshot_json(by_pointer, pointers, 99);
  EXPECT_EQ(by_pointer, out);

  std::string empty;
  append_alerts_snapshot_json(empty, std::span<const AlertEvent>{}, 1);
  EXPECT_EQ(empty, R"({"class":"ALERTS","seq":1,"alerts":[]})" "\n");
}

TEST(AlertJson, VersionAliveErrorAndTrackObjectsAreByteExact) {
  std::string out;
  append_version_json(out, 0);
  EXPECT_EQ(out, R"({"class":"VERSION","seq":0,"release":")" + std::string(release()) + R"(","revision":")" +
                     std::string(revision()) + R"(","proto":2})" "\n");

  const std::string provenance = R"("release":")" + std::string(release()) + R"(","revision":")" +
                                 std::string(revision()) + R"("})" "\n";
  AliveStatus alive;
  alive.last_data_t = 1714400000.25;
  alive.tracks = 123;
  alive.alerts = 2;
  alive.records_per_s = 250.04;
  alive.updates_per_s = 200.06;
  alive.uptime_s = 3600;
  out.clear();
  append_alive_json(out, alive, 5);
  EXPECT_EQ(out, R"({"class":"ALIVE","seq":5,"t":1714400000.250,"tracks":123,"alerts":2,)"
                 R"("rates":{"records_per_s":250.0,"updates_per_s":200.1},"uptime_s":3600,)"
                 R"("degraded":false,"health":"healthy",)" + provenance);
  out.clear();
  append_alive_json(out, AliveStatus{}, 6);
  EXPECT_EQ(out, R"({"class":"ALIVE","seq":6,"t":null,"tracks":0,"alerts":0,)"
                 R"("rates":{"records_per_s":0.0,"updates_per_s":0.0},"uptime_s":0,)"
                 R"("degraded":false,"health":"healthy",)" + provenance);

  out.clear();
  append_error_json(out, "queue full: \"slow\" subscriber", 7);
  EXPECT_EQ(out, R"({"class":"ERROR","seq":7,"message":"queue full: \"slow\" subscriber"})" "\n");

  TrackReport track;
  track.t = 1714400000.5;
  track.id = "4CA123";
  track.source = "sbs";
  track.lat_deg = 51.47;
  track.lon_deg = -0.45;
  track.alt_ft = 35000.0;
  track.gs_kt = 450.0;
  out.clear();
  append_track_json(out, track, 8);
  EXPECT_EQ(out, R"({"class":"TRACK","seq":8,"t":1714400000.500,"id":"4CA123","src":"sbs",)"
                 R"("cs":"","lat":51.470000,"lon":-0.450000,"alt_ft":35000,"gs_kt":450.0})" "\n");
  track.trk_deg = 359.96;
  track.vr_fpm = 640.0;
  track.callsign = "BAW123";
  track.on_ground = true;
  out.clear();
  append_track_json(out, track, 9);
  EXPECT_EQ(out, R"({"class":"TRACK","seq":9,"t":1714400000.500,"id":"4CA123","src":"sbs",)"
                 R"("cs":"BAW123","lat":51.470000,"lon":-0.450000,"alt_ft":35000,"gs_kt":450.0,)"
                 R"("trk_deg":360.0,"vr_fpm":640,"gnd":true})" "\n");
}

// Strings reach the stream through the shared escaper (ndjson_writer.hpp); these check
// what a subscriber receives, through the message of an ERROR object.
std::string escaped(std::string_view text) {
  std::string line;
  append_error_json(line, text, 1);
  const std::string prefix = R"({"class":"ERROR","seq":1,"message":)";
  EXPECT_EQ(line.substr(0, prefix.size()), prefix);
  EXPECT_EQ(line.substr(line.size() - 2), "}\n");
  return line.substr(prefix.size(), line.size() - prefix.size() - 2);
}

TEST(AlertJson, AckObjectIsByteExactAndReadsBack) {
  std::string out;
  const std::vector<std::string> ids = {"9f3c2a51d0e4b7c8", "0123456789abcdef"};
  append_ack_json(out, {ids, 1714400000.25, "modbus", "127.0.0.1:50312"}, 42);
  EXPECT_EQ(out, R"({"class":"ACK","seq":42,"t":1714400000.250,"by":"modbus","client":"127.0.0.1:50312",)"
                 R"("ids":["9f3c2a51d0e4b7c8","0123456789abcdef"]})" "\n");
  AlertStreamReader reader;
  ASSERT_TRUE(reader.read(out)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Ack);
  EXPECT_EQ(reader.seq(), 42u);
  EXPECT_EQ(reader.text(), "modbus");
  EXPECT_EQ(reader.acknowledging_client(), "127.0.0.1:50312");
  EXPECT_EQ(reader.acknowledged(), ids);

  out.clear();
  append_ack_json(out, {{}, 0.0, "modbus", "[::1]:4000"}, 0);
  ASSERT_TRUE(reader.read(out)) << reader.error();
  EXPECT_TRUE(reader.acknowledged().empty());
  EXPECT_FALSE(reader.read(R"({"class":"ACK","seq":1,"t":0,"by":"modbus","ids":[1]})"));
  EXPECT_FALSE(reader.read(R"({"class":"ACK","seq":1,"t":0,"ids":[]})"));
}

TEST(AlertJsonEscaping, QuotesBackslashAndControlCharacters) {
  EXPECT_EQ(escaped(""), R"("")");
  EXPECT_EQ(escaped("BAW123"), R"("BAW123")");
  EXPECT_EQ(escaped(R"(a"b\c/d)"), R"("a\"b\\c/d")");
  EXPECT_EQ(escaped("\b\f\n\r\t"), R"("\b\f\n\r\t")");
  EXPECT_EQ(escaped(std::string_view("a\0b", 3)), R"("a\u0000b")");
  EXPECT_EQ(escaped("\x01\x1f"), R"("\u0001\u001f")");
  EXPECT_EQ(escaped("\x7f"), "\"\x7f\"");  // DEL is valid in a JSON string
}

TEST(AlertJsonEscaping, ValidUtf8PassesThrough) {
  EXPECT_EQ(escaped("Z\xC3\xBCrich"), "\"Z\xC3\xBCrich\"");       // ü
  EXPECT_EQ(escaped("\xE2\x9C\x88"), "\"\xE2\x9C\x88\"");          // ✈
  EXPECT_EQ(escaped("\xF0\x9D\x84\x9E"), "\"\xF0\x9D\x84\x9E\"");  // U+1D11E
  EXPECT_EQ(escaped("\xF4\x8F\xBF\xBF"), "\"\xF4\x8F\xBF\xBF\"");  // U+10FFFF
}

TEST(AlertJsonEscaping, EachInvalidUtf8ByteBecomesOneReplacement) {
  EXPECT_EQ(escaped("\xFF"), R"("\ufffd")");
  EXPECT_EQ(escaped("a\x80z"), R"("a\ufffdz")");                          // stray continuation
  EXPECT_EQ(escaped("\xC0\xAF"), R"("\ufffd\ufffd")");                    // overlong '/'
  EXPECT_EQ(escaped("\xE0\x80\xAF"), R"("\ufffd\ufffd\ufffd")");          // overlong
  EXPECT_EQ(escaped("\xED\xA0\x80"), R"("\ufffd\ufffd\ufffd")");          // surrogate D800
  EXPECT_EQ(escaped("\xF4\x90\x80\x80"), R"("\ufffd\ufffd\ufffd\ufffd")");  // > U+10FFFF
  EXPECT_EQ(escaped("ok\xE2\x82"), R"("ok\ufffd\ufffd")");                // truncated at end
  EXPECT_EQ(escaped("\xC3" "A"), R"("\ufffdA")");                        // lead without tail
}

TEST(AlertJsonEscaping, IdentifiersAndCallsignsOfAlertsAreEscapedToo) {
  AlertEvent e = update_event();
  e.id = "q\"";
  e.a.callsign = "\xFF\n";
  e.b.source = "c\\d";
  std::string line;
  append_alert_json(line, e, 1);
  EXPECT_NE(line.find(R"("id":"q\"")"), std::string::npos) << line;
  EXPECT_NE(line.find(R"("cs":"\ufffd\n")"), std::string::npos) << line;
  EXPECT_NE(line.find(R"("src":"c\\d")"), std::string::npos) << line;
  EXPECT_EQ(line.find('\n'), line.size() - 1);  // one line, whatever the strings hold
}

TEST(AlertJsonEscaping, OutputOfArbitraryBytesReadsBackAsJson) {
  std::mt19937 random(7);
  AlertStreamReader reader;
  for (int i = 0; i < 1000; ++i) {
    // Even rounds: any bytes, which must give valid JSON. Odd rounds: 7-bit bytes, which
    // must also come back unchanged.
    const unsigned mask = i % 2 == 0 ? 0xFF : 0x7F;
    std::string message(static_cast<std::size_t>(random() % 40), '\0');
    for (char& c : message) c = static_cast<char>(random() & mask);
    std::string line;
    append_error_json(line, message, 1);
    ASSERT_TRUE(reader.read(line)) << reader.error() << " in " << line;
    if (mask == 0x7F) {
      EXPECT_EQ(reader.text(), message);
    }
  }
}

TEST(WatchRequest, AcceptsTheSpecExampleAndGpsdForms) {
  auto r = parse_watch_request(R"(?WATCH={"enable":true,"min_severity":"caution","tracks":false})");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.request.enable);
  EXPECT_EQ(r.request.min_severity, Severity::Caution);
  EXPECT_FALSE(r.request.tracks);

  r = parse_watch_request("?WATCH={\"min_severity\":\"warning\",\"tracks\":true,\"json\":true};\r\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.request.enable);  // default
  EXPECT_EQ(r.request.min_severity, Severity::Warning);
  EXPECT_TRUE(r.request.tracks);

  r = parse_watch_request(R"(?WATCH={"enable":false,"min_severity":"loss"})");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_FALSE(r.request.enable);
  EXPECT_EQ(r.request.min_severity, Severity::Loss);

  r = parse_watch_request("?WATCH;\n");
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.request.enable);
  EXPECT_EQ(r.request.min_severity, Severity::Caution);
  EXPECT_FALSE(r.request.tracks);

  EXPECT_TRUE(parse_watch_request("  ?WATCH={}  ").ok);
}

TEST(WatchRequest, RefusesMalformedRequestsWithAReason) {
  const auto refused = [](std::string_view line, std::string_view expected_in_error) {
    const WatchParseResult r = parse_watch_request(line);
    EXPECT_FALSE(r.ok) << line;
    EXPECT_NE(r.error.find(expected_in_error), std::string::npos)
        << "request " << line << " gave error: " << r.error;
  };
  refused("?POLL;", "unknown command");
  refused("", "unknown command");
  refused("?WATCHX", "expected '='");
  refused("?WATCH=", "invalid JSON");
  refused("?WATCH={\"enable\":true", "invalid JSON");
  refused("?WATCH={} {}", "invalid JSON");
  refused("?WATCH=[true]", "not a JSON object");
  refused(R"(?WATCH={"enable":1})", "\"enable\" must be true or false");
  refused(R"(?WATCH={"tracks":"yes"})", "\"tracks\" must be true or false");
  refused(R"(?WATCH={"min_severity":3})", "\"min_severity\" must be a string");
  refused(R"(?WATCH={"min_severity":"severe"})", "unknown severity \"severe\"");
  refused("?WATCH={\"x\":\"" + std::string(kMaxWatchRequestBytes, 'a') + "\"}", "longer than");
}

TEST(AlertStreamReader, ReadsEveryObjectClassBack) {
  AlertStreamReader reader;
  std::string line;
  append_version_json(line, 0);
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Version);
  EXPECT_EQ(reader.text(), release());
  EXPECT_EQ(reader.revision(), revision());
  EXPECT_EQ(reader.proto(), kAlertStreamProtocol);

  line.clear();
  append_start_json(line, StartInfo{"00112233445566778899aabbccddeeff", 1714400000.25}, 41);
  EXPECT_EQ(line, std::string(R"({"class":"START","seq":41,"run":"00112233445566778899aabbccddeeff","release":")") +
                      std::string(release()) + R"(","revision":")" + std::string(revision()) +
                      R"(","t":1714400000.250})" + "\n");
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Start);
  EXPECT_EQ(reader.seq(), 41u);
  EXPECT_EQ(reader.run(), "00112233445566778899aabbccddeeff");
  EXPECT_EQ(reader.text(), release());
  EXPECT_EQ(reader.revision(), revision());
  EXPECT_EQ(reader.start_t(), 1714400000.25);

  line.clear();
  append_alert_json(line, update_event(), 17);
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Alert);
  EXPECT_EQ(reader.seq(), 17u);
  const AlertEvent& a = reader.alert();
  EXPECT_EQ(a.id, "9f3c2a51d0e4b7c8");
  EXPECT_EQ(a.number, 42);
  EXPECT_EQ(a.state, AlertState::Update);
  EXPECT_EQ(a.severity, Severity::Warning);
  EXPECT_EQ(a.a.track_number, 12);
  EXPECT_EQ(a.b.callsign, "DLH4AB");
  EXPECT_DOUBLE_EQ(a.b.lat_deg, 51.512346);
  EXPECT_DOUBLE_EQ(a.cpa_h_m, 1234.6);

  line.clear();
  AlertEvent other = update_event();
  other.seq = 3;
  append_alerts_snapshot_json(line, std::vector<AlertEvent>{update_event(), other}, 40);
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Alerts);
  EXPECT_EQ(reader.seq(), 40u);
  ASSERT_EQ(reader.alerts().size(), 2u);
  EXPECT_EQ(reader.alerts()[0].seq, 17u);
  EXPECT_EQ(reader.alerts()[1].seq, 3u);

  line.clear();
  AliveStatus alive;
  alive.tracks = 9;
  alive.records_per_s = 12.5;
  alive.health = HealthReason::RecordsRefused;
  append_alive_json(line, alive, 41);
  EXPECT_NE(line.find("\"degraded\":true,\"health\":\"records_refused\""), std::string::npos) << line;
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Alive);
  EXPECT_FALSE(reader.alive().last_data_t);
  EXPECT_EQ(reader.alive().tracks, 9u);
  EXPECT_DOUBLE_EQ(reader.alive().records_per_s, 12.5);
  EXPECT_TRUE(reader.alive().degraded());
  EXPECT_EQ(reader.alive().health, HealthReason::RecordsRefused);
  // A server before "health" sent only "degraded", which meant a stale feed.
  ASSERT_TRUE(reader.read(R"({"class":"ALIVE","seq":1,"t":null,"tracks":0,"alerts":0,)"
                          R"("rates":{"records_per_s":0,"updates_per_s":0},"degraded":true})"))
      << reader.error();
  EXPECT_EQ(reader.alive().health, HealthReason::FeedStale);
  EXPECT_FALSE(reader.read(R"({"class":"ALIVE","seq":1,"t":null,"tracks":0,"alerts":0,)"
                           R"("rates":{"records_per_s":0,"updates_per_s":0},"health":"fine"})"));

  line.clear();
  TrackReport track;
  track.t = 5.0;
  track.id = "77";
  track.vr_fpm = -300.0;
  append_track_json(line, track, 42);
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Track);
  EXPECT_EQ(reader.track().id, "77");
  EXPECT_FALSE(reader.track().gs_kt);
  EXPECT_EQ(reader.track().vr_fpm, -300.0);

  line.clear();
  append_error_json(line, "bye", 43);
  ASSERT_TRUE(reader.read(line)) << reader.error();
  EXPECT_EQ(reader.object_class(), StreamObjectClass::Error);
  EXPECT_EQ(reader.text(), "bye");
}

TEST(AlertStreamReader, RefusesBrokenLinesWithAReason) {
  AlertStreamReader reader;
  const auto refused = [&](const std::string& line, std::string_view expected_in_error) {
    EXPECT_FALSE(reader.read(line)) << line;
    EXPECT_NE(reader.error().find(expected_in_error), std::string::npos)
        << "line " << line << " gave error: " << reader.error();
  };
  refused("not json", "invalid JSON");
  refused("[1,2]", "not a JSON object");
  refused(R"({"class":"ALERT"})", "missing member \"seq\"");
  refused(R"({"class":"POSITION","seq":1})", "unknown class \"POSITION\"");
  refused(R"({"class":"ALERTS","seq":1})", "missing member \"alerts\"");
  refused(R"({"class":"ALERTS","seq":1,"alerts":[1]})", "must hold objects");
  std::string line = kUpdateLine;
  refused(line.replace(line.find("\"warning\""), 9, "\"severe\""), "unknown severity");
  line = kUpdateLine;
  refused(line.replace(line.find("\"update\""), 8, "\"open\""), "unknown state");
  line = kUpdateLine;
  refused(line.replace(line.find("\"lat\":51.470000"), 15, "\"lat\":\"N51\""),
          "member \"a\".\"lat\" must be a number");
  line = kUpdateLine;
  refused(line.replace(line.find("\"tn\":13"), 7, "\"tn\":70000"),
          "member \"b\".\"tn\" must be an integer in [0, 65535]");
  line = kUpdateLine;
  refused(line.replace(line.find(",\"sep_v_ft\":500"), 15, ""), "missing member \"sep_v_ft\"");
  line = kUpdateLine;
  refused(line.replace(line.find("\"linear\""), 8, "\"curved\""), "unknown hypothesis \"curved\"");
  line = kUpdateLine;
  refused(line.replace(line.find("\"region\":\"\""), 11, "\"region\":7"),
          "member \"region\" must be a string");
}

// --- round trip ------------------------------------------------------------------------

std::string random_text(std::mt19937& random) {
  static const std::vector<std::string> kPieces{
      "A", "Z", "0", "9", " ", "\"", "\\", "/", "\n", "\t", "\x01", "\x7f",
      "\xC3\xBC", "\xE2\x9C\x88", "\xF0\x9D\x84\x9E", "-", "_", "{", "}"};
  std::string text;
  const auto length = random() % 10;
  for (unsigned i = 0; i < length; ++i) text += kPieces[random() % kPieces.size()];
  return text;
}

AlertParty random_party(std::mt19937& random) {
  std::uniform_real_distribution<double> lat(-90.0, 90.0), lon(-180.0, 180.0),
      alt(-1500.0, 60000.0), gs(0.0, 1200.0), trk(0.0, 360.0), vr(-8000.0, 8000.0);
  AlertParty p;
  p.id = random_text(random);
  p.source = random_text(random);
  p.callsign = random_text(random);
  p.track_number = static_cast<std::uint16_t>(random() & 0xFFFF);
  p.lat_deg = lat(random);
  p.lon_deg = lon(random);
  p.alt_ft = alt(random);
  p.gs_kt = gs(random);
  p.trk_deg = trk(random);
  p.vr_fpm = vr(random);
  return p;
}

AlertEvent random_event(std::mt19937& random) {
  std::uniform_real_distribution<double> t(1.0e9, 2.0e9), seconds(0.0, 300.0),
      metres(0.0, 2.0e5), feet(0.0, 5.0e4);
  AlertEvent e;
  e.id = random_text(random);
  e.number = static_cast<std::uint16_t>(random() & 0xFFFF);
  e.seq = (std::uint64_t{random()} << 32) | random();
  e.state = static_cast<AlertState>(random() % 3);
  if (e.state == AlertState::End) e.end_reason = static_cast<AlertEndReason>(1 + random() % 2);
  e.severity = static_cast<Severity>(random() % 4);
  e.t = t(random);
  e.opened_t = e.t - seconds(random);
  e.a = random_party(random);
  e.b = random_party(random);
  e.t_los_s = seconds(random);
  e.t_cpa_s = seconds(random);
  e.cpa_h_m = metres(random);
  e.cpa_v_ft = feet(random);
  e.sep_h_m = metres(random);
  e.sep_v_ft = feet(random);
  const auto& hypotheses = kHypothesisNames.entries();
  e.hypothesis = hypotheses[random() % hypotheses.size()].value;
  e.region = random_text(random);
  e.acknowledged = (random() & 1) != 0;
  if (random() % 4 == 0) {  // an area proximity warning: one aircraft, a volume, no pair figures
    e.kind = AlertKind::Apw;
    e.b = AlertParty{};
    e.t_cpa_s = e.cpa_h_m = e.cpa_v_ft = e.sep_h_m = e.sep_v_ft = 0.0;
    e.region.clear();
    e.volume = random_text(random);
    e.volume_kind = random_text(random);
  }
  return e;
}

// Half a unit of the last printed decimal, plus the double's own rounding at that size.
void expect_within(double read, double written, int decimals, const char* name) {
  const double tolerance = 0.5 * std::pow(10.0, -decimals) + std::abs(written) * 1e-15;
  EXPECT_NEAR(read, written, tolerance) << name;
}

void expect_party_equal(const AlertParty& read, const AlertParty& written) {
  EXPECT_EQ(read.id, written.id);
  EXPECT_EQ(read.source, written.source);
  EXPECT_EQ(read.callsign, written.callsign);
  EXPECT_EQ(read.track_number, written.track_number);
  expect_within(read.lat_deg, written.lat_deg, 6, "lat");
  expect_within(read.lon_deg, written.lon_deg, 6, "lon");
  expect_within(read.alt_ft, written.alt_ft, 0, "alt_ft");
  expect_within(read.gs_kt, written.gs_kt, 1, "gs_kt");
  expect_within(read.trk_deg, written.trk_deg, 1, "trk_deg");
  expect_within(read.vr_fpm, written.vr_fpm, 0, "vr_fpm");
}

TEST(AlertJsonRoundTrip, RandomEventsReadBackWithinThePrintedPrecision) {
  std::mt19937 random(20240429);
  AlertStreamReader reader;
  std::string line;
  for (int i = 0; i < 2000; ++i) {
    const AlertEvent written = random_event(random);
    line.clear();
    append_alert_json(line, written, written.seq);
    ASSERT_TRUE(reader.read(line)) << reader.error() << "\n" << line;
    ASSERT_EQ(reader.object_class(), StreamObjectClass::Alert);
    const AlertEvent& read = reader.alert();
    SCOPED_TRACE(line);
    EXPECT_EQ(read.kind, written.kind);
    EXPECT_EQ(read.volume, written.volume);
    EXPECT_EQ(read.volume_kind, written.volume_kind);
    EXPECT_EQ(read.id, written.id);
    EXPECT_EQ(read.number, written.number);
    EXPECT_EQ(read.seq, written.seq);
    EXPECT_EQ(read.state, written.state);
    EXPECT_EQ(read.end_reason, written.end_reason);
    EXPECT_EQ(read.severity, written.severity);
    expect_within(read.t, written.t, 3, "t");
    expect_within(read.opened_t, written.opened_t, 3, "t_open");
    expect_party_equal(read.a, written.a);
    expect_party_equal(read.b, written.b);
    expect_within(read.t_los_s, written.t_los_s, 1, "t_los_s");
    expect_within(read.t_cpa_s, written.t_cpa_s, 1, "t_cpa_s");
    expect_within(read.cpa_h_m, written.cpa_h_m, 1, "cpa_h_m");
    expect_within(read.cpa_v_ft, written.cpa_v_ft, 0, "cpa_v_ft");
    expect_within(read.sep_h_m, written.sep_h_m, 1, "sep_h_m");
    expect_within(read.sep_v_ft, written.sep_v_ft, 0, "sep_v_ft");
    EXPECT_EQ(read.hypothesis, written.hypothesis);
    EXPECT_EQ(read.region, written.region);
    EXPECT_EQ(read.acknowledged, written.acknowledged);

    // Encoding what was read gives the same bytes: the printed form is a fixed point.
    std::string again;
    append_alert_json(again, read, read.seq);
    EXPECT_EQ(again, line);
    if (HasFailure()) break;
  }
}

}  // namespace
}  // namespace kew::protocol
