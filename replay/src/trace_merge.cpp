#include "trace_merge.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <tuple>

#include "kew/protocol/readsb_trace.hpp"
#include "kew/replay/recording_reader.hpp"

namespace kew::replay {

namespace {

// Detection looks at this much of a file (compressed or not).
constexpr std::size_t kHeadBytes = 64 * 1024;

protocol::Format detect_file(const std::string& path) {
  std::vector<std::byte> head(kHeadBytes);
  std::size_t n = 0;
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    n = std::fread(head.data(), 1, head.size(), f);
    std::fclose(f);
  }
  return protocol::detect_format(std::span<const std::byte>(head.data(), n));
}

}  // namespace

bool TraceMerge::wanted(const std::vector<std::string>& files, protocol::Format format) {
  if (format == protocol::Format::ReadsbTrace) return !files.empty();
  if (format != protocol::Format::Auto) return false;
  bool traces = false;
  for (const std::string& file : files) {
    const protocol::Format detected = detect_file(file);
    if (detected == protocol::Format::ReadsbTrace) {
      traces = true;
    } else if (detected != protocol::Format::Auto) {
      return false;
    }
  }
  return traces;
}

bool TraceMerge::LaterHead::operator()(const Active* a, const Active* b) const {
  const double ta = a->records[a->next].t;
  const double tb = b->records[b->next].t;
  const std::size_t ia = a->first + a->next;
  const std::size_t ib = b->first + b->next;
  return std::tie(ta, a->file, ia) > std::tie(tb, b->file, ib);
}

TraceMerge::TraceMerge(std::vector<std::string> files, protocol::Format format, const protocol::DecoderOptions& options,
                       Rejections& rejections)
    : files_(std::move(files)), format_(format), options_(options), rejections_(rejections), counted_(files_.size()) {
  for (std::size_t file = 0; file < files_.size(); ++file) index_file(file);
  std::stable_sort(segments_.begin(), segments_.end(), [](const Segment& a, const Segment& b) {
    return std::tie(a.first_t, a.file, a.first) < std::tie(b.first_t, b.file, b.first);
  });
}

void TraceMerge::index_file(std::size_t file) {
  RecordingReader alone(files_[file], format_, options_);
  const std::size_t before = segments_.size();
  std::size_t index = 0;
  double last_t = 0;
  for (TrackReport r; alone.next(r); ++index) {
    const bool same_segment = segments_.size() > before && r.t >= last_t && r.t - last_t <= kSegmentGap_s &&
                              segments_.back().count < kSegmentRecords;
    if (same_segment) {
      ++segments_.back().count;
    } else {
      segments_.push_back({.first_t = r.t, .file = file, .first = index, .count = 1});
    }
    last_t = r.t;
  }
  // A file without a record is read first, for its refusals.
  if (segments_.size() == before)
    segments_.push_back({.first_t = -std::numeric_limits<double>::infinity(), .file = file});
}

template <class Keep>
bool TraceMerge::decode_file(std::size_t file, Keep&& keep) {
  RecordingReader reader(files_[file], format_, options_);
  const bool first = !counted_[file];
  counted_[file] = true;
  if (!reader.is_open()) {
    if (first) rejections_.reject("file_unreadable", files_[file]);
    return false;
  }
  if (first) {
    reader.rejections() = Rejections(std::numeric_limits<std::uint64_t>::max());
    reader.rejections().set_reporter(
        [this](std::string_view reason, std::string_view message) { rejections_.reject(reason, message); });
  }
  std::size_t index = 0;
  for (TrackReport r; reader.next(r); ++index) keep(index, r);
  if (first) bytes_read_ += reader.bytes_read();
  return true;
}

void TraceMerge::activate(const Segment& segment) {
  auto active = std::make_unique<Active>();
  active->file = segment.file;
  active->first = segment.first;
  active->records.reserve(segment.count);
  decode_file(segment.file, [&](std::size_t index, TrackReport& r) {
    if (index >= segment.first && index - segment.first < segment.count) active->records.push_back(std::move(r));
  });
  if (active->records.empty()) return;
  heads_.push(active.get());
  active_.push_back(std::move(active));
}

bool TraceMerge::next(TrackReport& out) {
  while (true) {
    // Every segment that starts no later than the earliest head joins the merge first.
    while (next_segment_ < segments_.size() &&
           (heads_.empty() || segments_[next_segment_].first_t <= heads_.top()->records[heads_.top()->next].t)) {
      activate(segments_[next_segment_]);
      ++next_segment_;
    }
    if (heads_.empty()) return false;
    Active* head = heads_.top();
    heads_.pop();
    out = std::move(head->records[head->next++]);
    if (head->next < head->records.size()) {
      heads_.push(head);
    } else {
      const auto done = std::find_if(active_.begin(), active_.end(), [head](const auto& a) { return a.get() == head; });
      *done = std::move(active_.back());
      active_.pop_back();
    }
    const auto [given, fresh] = last_given_.try_emplace(out.id, out.t);
    if (fresh) return true;
    if (out.t <= given->second + protocol::kReadsbTraceSamePosition_s) continue;  // given already
    given->second = out.t;
    return true;
  }
}

}  // namespace kew::replay
