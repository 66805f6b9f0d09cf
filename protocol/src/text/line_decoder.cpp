#include "line_decoder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace kew::protocol::text {

LineDecoder::LineDecoder(std::size_t max_line_bytes)
    : max_line_bytes_(std::max<std::size_t>(max_line_bytes, 16)) {}

void LineDecoder::feed(std::span<const std::byte> bytes, const ReportSink& sink) {
  const char* next = reinterpret_cast<const char*>(bytes.data());
  const char* const end = next + bytes.size();
  while (next < end) {
    const auto* newline =
        static_cast<const char*>(std::memchr(next, '\n', static_cast<std::size_t>(end - next)));
    const char* const stop = newline != nullptr ? newline : end;
    const std::string_view piece(next, static_cast<std::size_t>(stop - next));
    if (skipping_) {
      // The rest of an over-long line, already counted.
    } else if (partial_.size() + piece.size() > max_line_bytes_) {
      reject_too_long();
      partial_.clear();
      skipping_ = newline == nullptr;
    } else if (partial_.empty() && newline != nullptr) {
      // The common case: a whole line inside this chunk, decoded without copying.
      dispatch(piece, true, sink);
    } else {
      partial_.append(piece);
      if (newline != nullptr) {
        dispatch(partial_, true, sink);
        partial_.clear();
      }
    }
    if (newline != nullptr) {
      skipping_ = false;
      ++line_number_;
    }
    next = stop + (newline != nullptr ? 1 : 0);
  }
}

void LineDecoder::finish(const ReportSink& sink) { end(false, sink); }

void LineDecoder::end_message(const ReportSink& sink) { end(true, sink); }

void LineDecoder::end(bool complete, const ReportSink& sink) {
  if (!skipping_ && !partial_.empty()) dispatch(partial_, complete, sink);
  partial_.clear();
  skipping_ = false;
  line_number_ = 1;
  end_of_stream(sink);
}

void LineDecoder::reject_too_long() {
  rejections().reject("line_too_long", fmt::format("{} line {}: longer than {} bytes, skipped",
                                                   format_name(), line_number_, max_line_bytes_));
}

void LineDecoder::dispatch(std::string_view line, bool terminated, const ReportSink& sink) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const auto first = line.find_first_not_of(" \t");
  if (first == std::string_view::npos || line[first] == '#') return;
  LineResult result = decode_line(line, sink);
  if (!result) return;
  if (terminated) {
    rejections().reject(result->reason, fmt::format("{} line {}: {}: {}", format_name(),
                                                    line_number_, result->reason, result->detail));
  } else {
    rejections().reject("truncated",
                        fmt::format("{} line {} (cut by the end of the stream): {}: {}",
                                    format_name(), line_number_, result->reason, result->detail));
  }
}

}  // namespace kew::protocol::text
