// replay::RecordingReader, the one reader of recordings (kew-replay and kewd's file
// inputs): format detection, gzip, counted rejections with rate-limited messages, and
// files that cannot be opened, recognised or read.
#include "kew/replay/recording_reader.hpp"

#include <gtest/gtest.h>

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

  // A directory opens (on Linux) but every read fails: a read error, not an empty file.
  RecordingReader directory(dir.string(), protocol::Format::Ndjson, {});
  EXPECT_TRUE(read_all(directory).empty());
  EXPECT_EQ(directory.rejections().count("file_unreadable"), 1u);
  std::filesystem::remove_all(dir);
}

TEST(RecordingReader, SharedSwitzerlandWhole) {
  const std::string path = protocol::test::shared_path("traffic-opensky/switzerland.json.gz");
  if (!protocol::test::exists(path)) GTEST_SKIP() << "shared recordings absent: " << path;
  RecordingReader reader(path, protocol::Format::Auto, {});
  EXPECT_EQ(read_all(reader).size(), 139098u);
  EXPECT_EQ(reader.rejections().total(), 0u);
}

}  // namespace
}  // namespace kew::replay
