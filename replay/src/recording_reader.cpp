#include "kew/replay/recording_reader.hpp"

namespace kew::replay {

namespace {
constexpr std::size_t kChunkBytes = 256 * 1024;
}

RecordingReader::RecordingReader(std::string path, protocol::Format format, const protocol::DecoderOptions& options)
    : path_(std::move(path)) {
  file_ = path_ == kStandardInput ? stdin : std::fopen(path_.c_str(), "rb");
  if (!file_) {
    own_rejections_.reject("file_unreadable", path_);
    finished_ = true;
    return;
  }
  decoder_ = protocol::make_decoder(format, options);
  chunk_.resize(kChunkBytes);
}

RecordingReader::~RecordingReader() {
  if (file_ && file_ != stdin) std::fclose(file_);
}

bool RecordingReader::refill() {
  const auto sink = [this](const TrackReport& r) { ready_.push_back(r); };
  while (ready_.empty() && !finished_) {
    const std::size_t n = std::fread(chunk_.data(), 1, chunk_.size(), file_);
    bytes_read_ += n;
    if (n > 0) decoder_->feed(std::span<const std::byte>(chunk_.data(), n), sink);
    if (n < chunk_.size()) {
      if (std::ferror(file_)) decoder_->rejections().reject("file_unreadable", path_);
      decoder_->finish(sink);
      finished_ = true;
    }
  }
  return !ready_.empty();
}

bool RecordingReader::next(TrackReport& out) {
  if (ready_.empty() && !refill()) return false;
  out = std::move(ready_.front());
  ready_.pop_front();
  ++records_;
  return true;
}

void MergedRecordings::add(std::unique_ptr<RecordingReader> reader) {
  readers_.push_back(std::move(reader));
  heads_.emplace_back();
  primed_ = false;
}

bool MergedRecordings::next(TrackReport& out) {
  if (!primed_) {
    for (std::size_t i = 0; i < readers_.size(); ++i)
      if (!heads_[i].valid) heads_[i].valid = readers_[i]->next(heads_[i].report);
    primed_ = true;
  }
  // A linear scan: recordings are few, and this keeps ties deterministic.
  std::size_t best = heads_.size();
  for (std::size_t i = 0; i < heads_.size(); ++i) {
    if (!heads_[i].valid) continue;
    if (best == heads_.size() || heads_[i].report.t < heads_[best].report.t) best = i;
  }
  if (best == heads_.size()) return false;
  out = std::move(heads_[best].report);
  heads_[best].valid = readers_[best]->next(heads_[best].report);
  return true;
}

Rejections MergedRecordings::rejections() const {
  Rejections total;
  for (const auto& reader : readers_) total.merge(reader->rejections());
  return total;
}

}  // namespace kew::replay
