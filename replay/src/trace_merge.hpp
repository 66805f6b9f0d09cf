#pragma once
// A set of readsb trace files (readsb_trace.hpp: one aircraft each, each spanning the day)
// read as one stream in data-time order across the files, for RecordingReader.
//
// Reading them one after another would give each aircraft's whole day in turn; holding
// every record of every file until the merge can start would hold the whole day. The
// merge works by segments instead:
//  1. index: each file is decoded once (gzip or not) and only the bounds of its
//     segments are kept: runs of records in time order with no gap longer than
//     kSegmentGap_s (10 min of data time) and at most kSegmentRecords (4096) records;
//  2. merge: a segment is decoded (its file read again, its records kept, the rest
//     dropped) when the merge reaches the segment's first data time, and let go when its
//     last record has left; the heads of the segments under way are merged in a heap.
// Memory: the records of the segments under way at the current data time (at most
// kSegmentRecords each, of the aircraft flying at that time, not of the whole day), plus
// a few numbers per segment of every file. Time: every file is decoded once to index it
// and once per segment. At most one file is open at a time.
//
// Ties go to the earlier file by name, then to the earlier record of a file. A record of
// an address not later than the last one given for that address (the same point in
// trace_full and trace_recent) is not given again (the decoder's rule, across files).
// Each file's refusals are counted once, when it is first decoded for the merge (the
// index pass counts nothing), with "file_unreadable" for one that cannot be read.
// Internal to kew_replay.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <queue>
#include <string>
#include <unordered_map>
#include <vector>

#include "kew/protocol/formats.hpp"

namespace kew::replay {

class TraceMerge {
 public:
  static constexpr double kSegmentGap_s = 600.0;
  static constexpr std::size_t kSegmentRecords = 4096;

  /// True when `files` are read by the merge: `format` is readsb-trace, or auto and
  /// every file whose first bytes name a format names readsb-trace (at least one does).
  static bool wanted(const std::vector<std::string>& files, protocol::Format format);

  /// Indexes `files` (step 1 above); refusals go to `rejections` as the merge goes.
  TraceMerge(std::vector<std::string> files, protocol::Format format, const protocol::DecoderOptions& options,
             Rejections& rejections);

  /// The next record in data-time order; false at the end.
  bool next(TrackReport& out);
  /// The bytes of the files decoded for the merge so far (each file counted once).
  std::uint64_t bytes_read() const { return bytes_read_; }

 private:
  struct Segment {
    double first_t = 0;          // -infinity: a file without a record, read first for its refusals
    std::size_t file = 0;        // index in files_
    std::size_t first = 0;       // index of its first record among the file's records
    std::size_t count = 0;
  };
  struct Active {
    std::vector<TrackReport> records;
    std::size_t next = 0;
    std::size_t file = 0;   // ties: the earlier file first,
    std::size_t first = 0;  // then the earlier record of the file (first + next)
  };
  struct LaterHead {
    bool operator()(const Active* a, const Active* b) const;
  };

  void index_file(std::size_t file);
  void activate(const Segment& segment);
  /// Decodes file `file`, calling `keep(index, record)` for each record; false when it
  /// cannot be opened. The first decode of a file counts its refusals and its bytes.
  template <class Keep>
  bool decode_file(std::size_t file, Keep&& keep);

  std::vector<std::string> files_;
  protocol::Format format_;
  protocol::DecoderOptions options_;
  Rejections& rejections_;
  std::vector<Segment> segments_;  // by first data time, then file, then first record
  std::size_t next_segment_ = 0;
  std::vector<bool> counted_;  // by file: refusals and bytes counted
  std::vector<std::unique_ptr<Active>> active_;
  std::priority_queue<Active*, std::vector<Active*>, LaterHead> heads_;
  std::unordered_map<std::string, double> last_given_;  // id → data time last given
  std::uint64_t bytes_read_ = 0;
};

}  // namespace kew::replay
