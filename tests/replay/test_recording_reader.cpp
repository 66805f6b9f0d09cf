// replay::RecordingReader, the one reader of recordings (kew-replay and kewd's file
// inputs): format detection, gzip, counted rejections with rate-limited messages, and
// files that cannot be opened, recognised or read.
#include "kew/replay/recording_reader.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_formats_support.hpp"

namespace kew::replay {
namespace {

std::vector<TrackReport> read_all(RecordingReader& reader) {
  std::vector<TrackReport> reports;
  TrackReport r;
  while (reader.next(r)) reports.push_back(r);
  return reports;
}

TEST(RecordingReader, AutoDetectsDecodesAndCounts) {
  RecordingReader reader(protocol::test::bundled_path("readsb_20minutes.json"), protocol::Format::Auto, {});
  std::vector<std::string> messages;
  reader.rejections().set_reporter([&](std::string_view, std::string_view m) { messages.emplace_back(m); });
  EXPECT_TRUE(reader.is_open());
  EXPECT_EQ(read_all(reader).size(), 1194u);
  EXPECT_EQ(reader.records(), 1194u);
  EXPECT_EQ(reader.rejections().count("no_position"), 418u);
  ASSERT_EQ(messages.size(), 10u + 5u);  // a burst of 10, then the 20th, 40th, ..., 320th
  EXPECT_NE(messages[0].find("readsb line 3"), std::string::npos) << messages[0];

  RecordingReader gzipped(protocol::test::bundled_path("opensky_switzerland_first2000.json.gz"),
                          protocol::Format::OpenskyJson, {});
  EXPECT_EQ(read_all(gzipped).size(), 2000u);
  EXPECT_EQ(gzipped.rejections().total(), 0u);
}

TEST(RecordingReader, MissingUnknownAndUnreadableFilesAreCounted) {
  RecordingReader missing("/nonexistent/kew/file.ndjson", protocol::Format::Auto, {});
  EXPECT_FALSE(missing.is_open());
  EXPECT_TRUE(read_all(missing).empty());
  EXPECT_EQ(missing.rejections().count("file_unreadable"), 1u);

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("kew_test_reader_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string words = (dir / "words.txt").string();
  std::ofstream(words) << "just some words\n";
  RecordingReader unknown(words, protocol::Format::Auto, {});
  EXPECT_TRUE(read_all(unknown).empty());
  EXPECT_EQ(unknown.rejections().count("unknown_format"), 1u);

  // A file that opens but whose every read fails (/proc/self/mem at offset 0): a read
  // error, not an empty file.
  RecordingReader unreadable("/proc/self/mem", protocol::Format::Ndjson, {});
  EXPECT_TRUE(read_all(unreadable).empty());
  EXPECT_EQ(unreadable.rejections().count("file_unreadable"), 1u);
  // A directory is the recording of its files (RecordingReader.ADirectory… below): here
  // the words, refused line by line.
  RecordingReader directory(dir.string(), protocol::Format::Ndjson, {});
  EXPECT_TRUE(read_all(directory).empty());
  EXPECT_EQ(directory.files().size(), 1u);
  EXPECT_EQ(directory.rejections().count("bad_json"), 1u);
  std::filesystem::remove_all(dir);
}

TEST(RecordingReader, SharedSwitzerlandWhole) {
  const std::string path = protocol::test::shared_path("traffic-opensky/switzerland.json.gz");
  if (!protocol::test::exists(path)) GTEST_SKIP() << "shared recordings absent: " << path;
  RecordingReader reader(path, protocol::Format::Auto, {});
  EXPECT_EQ(read_all(reader).size(), 139098u);
  EXPECT_EQ(reader.rejections().total(), 0u);
}

// A receiver's history: readsb keeps history_0.json … history_119.json round a ring, so
// their names are not their order. A directory of them, or a glob, is read as one stream
// in the order of their data, gzip or not, and gives what the snapshots give in one file.
TEST(RecordingReader, ADirectoryOrAPatternOfSnapshotsIsOneStreamInDataOrder) {
  const std::string whole = protocol::test::read_file(protocol::test::bundled_path("aircraft_json_history.json"));
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("kew_history_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::size_t at = 0;
  for (int i = 0; at < whole.size(); ++i) {
    const std::size_t end = whole.find('\n', at) + 1;
    const std::string snapshot = whole.substr(at, end - at - (i % 3 == 0 ? 1 : 0));  // some without a newline
    at = end;
    const std::string name = (dir / ("history_" + std::to_string((i + 70) % 120) + ".json")).string();
    std::ofstream(name, std::ios::binary) << snapshot;
    if (i % 2 == 0) {
      ASSERT_EQ(std::system(("gzip -n '" + name + "'").c_str()), 0);  // history_N.json.gz
    }
  }
  std::ofstream(dir / ".hidden") << "not a snapshot";

  RecordingReader one(protocol::test::bundled_path("aircraft_json_history.json"), protocol::Format::Auto, {});
  const std::vector<TrackReport> expected = read_all(one);
  ASSERT_GT(expected.size(), 90u);
  for (const std::string& path : {dir.string(), (dir / "history_*.json*").string()}) {
    SCOPED_TRACE(path);
    RecordingReader set(path, protocol::Format::Auto, {});
    const std::vector<TrackReport> got = read_all(set);
    EXPECT_EQ(set.files().size(), 120u);
    EXPECT_EQ(set.rejections().total(), 0u) << set.rejections().last_reason();
    ASSERT_EQ(got.size(), expected.size());
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].id, expected[i].id) << i;
      EXPECT_EQ(got[i].t, expected[i].t) << i;
    }
  }
  RecordingReader none((dir / "nothing_*.json").string(), protocol::Format::Auto, {});
  EXPECT_EQ(read_all(none).size(), 0u);
  EXPECT_EQ(none.rejections().count("no_files"), 1u);
  std::filesystem::remove_all(dir);
}

// The aggregators' answers end with "now" (in milliseconds) after their "ac" list: a
// directory of answers larger than the head read for the time is ordered by it all the
// same, and read once each.
TEST(RecordingReader, AggregatorAnswersAreOrderedByTheNowTheyEndWith) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("kew_answers_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const double t0 = 1700000000.0;
  for (int i = 0; i < 3; ++i) {
    std::string ac;
    for (int k = 0; k < 400; ++k) {  // ~100 KB: "now" beyond the first 64 KiB
      ac += fmt::format("{}{{\"hex\":\"{:06x}\",\"alt_baro\":{},\"lat\":{:.5f},\"lon\":{:.5f},\"seen_pos\":0.5,"
                        "\"flight\":\"PAD{:05d}\",\"category\":\"A3\",\"nav_qnh\":1013.6,\"rssi\":-20.1}}",
                        k ? "," : "", 0xa00000 + k, 20000 + 100 * k, 40.0 + 0.01 * k + 0.001 * i, -100.0 + 0.01 * k, k);
    }
    // Named against their order: answer_2 is the oldest.
    std::ofstream(dir / ("answer_" + std::to_string(2 - i) + ".json"))
        << fmt::format("{{\"ac\":[{}],\"msg\":\"No error\",\"now\":{:.0f},\"total\":400}}", ac, (t0 + i) * 1000);
  }
  RecordingReader set(dir.string(), protocol::Format::Auto, {});
  const std::vector<TrackReport> got = read_all(set);
  EXPECT_EQ(set.rejections().total(), 0u) << set.rejections().last_reason();
  ASSERT_EQ(set.files().size(), 3u);
  EXPECT_EQ(std::filesystem::path(set.files()[0]).filename(), "answer_2.json");
  EXPECT_EQ(std::filesystem::path(set.files()[2]).filename(), "answer_0.json");
  ASSERT_EQ(got.size(), 1200u);
  for (std::size_t i = 1; i < got.size(); ++i) EXPECT_LE(got[i - 1].t, got[i].t) << i;
  std::filesystem::remove_all(dir);
}

// Line formats too: a recording cut into files (the last line of one without its
// newline) reads as the whole.
TEST(RecordingReader, ARecordingCutIntoFilesReadsAsTheWhole) {
  const std::string whole = protocol::test::read_file(protocol::test::bundled_path("readsb_20minutes.json"));
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("kew_parts_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::size_t cut = whole.find('\n', whole.size() / 2);
  std::ofstream(dir / "b.json", std::ios::binary) << whole.substr(0, cut);  // named after the second part
  std::ofstream(dir / "a.json", std::ios::binary) << whole.substr(cut + 1);
  RecordingReader one(protocol::test::bundled_path("readsb_20minutes.json"), protocol::Format::Auto, {});
  RecordingReader parts(dir.string(), protocol::Format::Auto, {});
  const std::vector<TrackReport> expected = read_all(one);
  const std::vector<TrackReport> got = read_all(parts);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i].t, expected[i].t) << i;
  EXPECT_EQ(parts.rejections().count("no_position"), one.rejections().count("no_position"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kew::replay
