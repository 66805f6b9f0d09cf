// A directory or pattern of readsb traces read by RecordingReader (src/trace_merge.hpp):
// one stream in data-time order across the files, not file after file, gzip or not;
// segments split at gaps and at their size limit; a point in two files once; each
// file's refusals counted once.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "kew/protocol/readsb_trace.hpp"
#include "kew/replay/recording_reader.hpp"
#include "test_formats_support.hpp"

namespace kew::replay {
namespace {

std::vector<TrackReport> read_all(RecordingReader& reader) {
  std::vector<TrackReport> reports;
  for (TrackReport r; reader.next(r);) reports.push_back(r);
  return reports;
}

/// A scratch directory, removed at the end of the test.
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDirectory() { std::filesystem::remove_all(path_); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string file = (path_ / name).string();
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
  }
  std::string path() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

/// A trace of `icao` with a row at each of `offsets` (s after 1700000000), its altitude
/// the offset.
std::string trace(const std::string& icao, const std::vector<int>& offsets) {
  std::string rows;
  for (const int offset : offsets) {
    if (!rows.empty()) rows += ",\n";
    rows += "[" + std::to_string(offset) + ",50.0,8.0," + std::to_string(offset) + ",400,90,0,null,null,\"adsb_icao\"]";
  }
  return "{\"icao\":\"" + icao + "\",\n\"timestamp\": 1700000000.000,\n\"trace\":[ \n" + rows + " ]\n }\n";
}

std::vector<int> every(int from, int to, int step) {
  std::vector<int> offsets;
  for (int t = from; t < to; t += step) offsets.push_back(t);
  return offsets;
}

void expect_in_data_order(const std::vector<TrackReport>& r) {
  for (std::size_t i = 1; i < r.size(); ++i) ASSERT_LE(r[i - 1].t, r[i].t) << i << " " << r[i].id;
}

TEST(TraceMerge, TheBundledTracesAreOneStreamInDataOrder) {
  const std::string dir = protocol::test::bundled_path("readsb_traces");
  // Each file alone, its records stamped with the file's place in name order: the merge
  // gives them all, by data time, ties to the earlier file.
  std::vector<std::tuple<double, std::size_t, std::string>> expected;
  RecordingReader set(dir, protocol::Format::Auto, {});
  ASSERT_EQ(set.files().size(), 19u);
  for (std::size_t f = 0; f < set.files().size(); ++f) {
    RecordingReader alone(set.files()[f], protocol::Format::Auto, {});
    for (const TrackReport& r : read_all(alone)) expected.emplace_back(r.t, f, r.id);
  }
  std::stable_sort(expected.begin(), expected.end(),
                   [](const auto& a, const auto& b) { return std::tie(std::get<0>(a), std::get<1>(a)) <
                                                             std::tie(std::get<0>(b), std::get<1>(b)); });
  ASSERT_EQ(expected.size(), 1182u);
  const std::vector<TrackReport> got = read_all(set);
  EXPECT_EQ(set.rejections().total(), 0u) << set.rejections().last_reason();
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].t, std::get<0>(expected[i])) << i;
    EXPECT_EQ(got[i].id, std::get<2>(expected[i])) << i;
  }
  EXPECT_EQ(set.records(), 1182u);
  std::uint64_t bytes = 0;
  for (const std::string& file : set.files()) bytes += std::filesystem::file_size(file);
  EXPECT_EQ(set.bytes_read(), bytes) << "each file counted once";
  // Not file after file: the first minute holds records of several aircraft.
  std::vector<std::string> first_minute;
  for (const TrackReport& r : got)
    if (r.t < got.front().t + 60) first_minute.push_back(r.id);
  std::sort(first_minute.begin(), first_minute.end());
  first_minute.erase(std::unique(first_minute.begin(), first_minute.end()), first_minute.end());
  EXPECT_GE(first_minute.size(), 5u);

  // The format named, and a pattern, give the same.
  for (const auto& [path, format] : {std::pair{dir, protocol::Format::ReadsbTrace},
                                     std::pair{dir + "/trace_full_*.json", protocol::Format::Auto}}) {
    RecordingReader other(path, format, {});
    const std::vector<TrackReport> again = read_all(other);
    ASSERT_EQ(again.size(), got.size()) << path;
    for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(again[i].id, got[i].id) << path << " " << i;
  }
}

TEST(TraceMerge, SegmentsSplitAtGapsAndAtTheirSizeLimitMergeInOrder) {
  ScratchDirectory dir("kew_traces");
  // a: two legs 40 min apart (a gap splits its segments); b: one leg between them; c:
  // 10,000 rows, more than a segment holds (4,096), under everything; d (gzip): one row,
  // at the start, with a and c; trace_recent of c: its last 100 rows again, given once.
  const std::vector<int> a = [] {
    std::vector<int> legs = every(0, 600, 7);
    for (const int t : every(3000, 3600, 7)) legs.push_back(t);
    return legs;
  }();
  const std::vector<int> b = every(1000, 2000, 13);
  const std::vector<int> c = every(0, 10000, 1);
  const std::vector<int> d = {0};
  dir.write("trace_full_aaaaaa.json", trace("aaaaaa", a));
  dir.write("trace_full_bbbbbb.json", trace("bbbbbb", b));
  dir.write("trace_full_cccccc.json", protocol::test::gzip_member(trace("cccccc", c)));
  dir.write("trace_full_dddddd.json", protocol::test::gzip_member(trace("dddddd", d)));
  dir.write("trace_recent_cccccc.json", trace("cccccc", every(9900, 10000, 1)));
  std::vector<std::tuple<int, std::size_t, std::string>> expected;  // by time, then file
  const std::pair<const std::vector<int>*, std::string> files[] = {{&a, "AAAAAA"}, {&b, "BBBBBB"}, {&c, "CCCCCC"},
                                                                   {&d, "DDDDDD"}};
  for (std::size_t f = 0; f < std::size(files); ++f)
    for (const int t : *files[f].first) expected.emplace_back(t, f, files[f].second);
  std::sort(expected.begin(), expected.end());

  RecordingReader set(dir.path(), protocol::Format::Auto, {});
  const std::vector<TrackReport> got = read_all(set);
  EXPECT_EQ(set.files().size(), 5u);
  EXPECT_EQ(set.rejections().total(), 0u) << set.rejections().last_reason();
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].t, 1700000000.0 + std::get<0>(expected[i])) << i;
    ASSERT_EQ(got[i].id, std::get<2>(expected[i])) << i;
    ASSERT_EQ(got[i].alt_ft, std::get<0>(expected[i])) << i;
  }
}

TEST(TraceMerge, EachFilesRefusalsAreCountedOnce) {
  ScratchDirectory dir("kew_traces_bad");
  // Two segments (an hour apart) around a row without a position: the file is decoded
  // for each segment, its refusal counted once. A file of prose has no record at all.
  dir.write("trace_full_aaaaaa.json",
            "{\"icao\":\"aaaaaa\",\"timestamp\":1700000000,\"trace\":[[0,1,2,3],[1,null,2,3],[3600,1,2,3]]}");
  dir.write("trace_full_bbbbbb.json", trace("bbbbbb", every(0, 100, 10)));
  dir.write("notes.txt", "not a trace\n");
  for (const protocol::Format format : {protocol::Format::Auto, protocol::Format::ReadsbTrace}) {
    RecordingReader set(dir.path(), format, {});
    std::vector<std::string> messages;
    set.rejections().set_reporter([&](std::string_view, std::string_view m) { messages.emplace_back(m); });
    const std::vector<TrackReport> got = read_all(set);
    EXPECT_EQ(got.size(), 12u);
    expect_in_data_order(got);
    EXPECT_EQ(set.rejections().count("no_position"), 1u);
    EXPECT_EQ(set.rejections().count(format == protocol::Format::Auto ? "unknown_format" : "bad_json"), 1u);
    EXPECT_EQ(set.rejections().total(), 2u);
    ASSERT_EQ(messages.size(), 2u) << "the messages reach the set's reporter";
  }
  // A directory whose files name another format is read as before, file after file.
  dir.write("readsb.json", R"({"now":1700000000,"hex":"cccccc","lat":1,"lon":2,"alt_baro":3})" "\n");
  RecordingReader mixed(dir.path(), protocol::Format::Auto, {});
  EXPECT_EQ(mixed.files().front(), dir.path() + "/notes.txt") << "the file-after-file order: no record first";
}
}  // namespace
}  // namespace kew::replay
