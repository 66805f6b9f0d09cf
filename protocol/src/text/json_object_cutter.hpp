#pragma once
// Cuts top-level JSON objects out of a byte stream without parsing them: the elements of
// an array, or whole documents one after another, split anywhere between feed() calls.
// A bracket counter that skips strings; memory is bounded by the longest object
// accepted. Used by the opensky-json decoder (array elements) and the aircraft.json
// decoder (snapshots). Internal to kew_protocol.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace kew::protocol::text {

class JsonObjectCutter {
 public:
  /// `what`: how messages name an object ("opensky-json element"); `max_object_bytes`:
  /// the longest object passed on.
  JsonObjectCutter(std::string what, std::size_t max_object_bytes)
      : what_(std::move(what)), max_object_bytes_(max_object_bytes) {}

  /// Calls `on_object(text)` for each complete object (`text` valid during the call) and
  /// `on_problem(reason, message)` for an object longer than the limit ("object_too_long",
  /// skipped to what ends a flat element: "}," "}]" or "}\n") and for each run of bytes
  /// between objects that are not blanks, ',', '[' or ']' ("bad_json").
  template <class OnObject, class OnProblem>
  void feed(std::span<const std::byte> bytes, OnObject&& on_object, OnProblem&& on_problem);

  /// End of stream: true when an object was cut short by it. Starts afresh.
  bool finish();
  /// The 1-based number of the current (or last) object since the start.
  std::uint64_t object_number() const { return objects_; }
  const std::string& what() const { return what_; }

 private:
  enum class Mode { Between, InObject, Resync };
  static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  /// Advances the bracket counter; true when `c` closes the object.
  bool inside_object(char c);
  /// Advances the bracket counter over [p, stop): the byte that closes the object, or
  /// `stop`. Bytes that neither open nor close a string or a bracket are skipped in a
  /// tight loop (most of a snapshot's bytes: numbers, keys, values).
  const char* scan(const char* p, const char* stop);
  void resync(char c);

  std::string what_;
  std::size_t max_object_bytes_;
  Mode mode_ = Mode::Between;
  std::size_t depth_ = 0;
  bool in_string_ = false;
  bool escaped_ = false;
  bool garbage_reported_ = false;
  bool resync_after_close_ = false;
  std::string object_;           // the start of an object begun in an earlier chunk
  std::uint64_t objects_ = 0;
  std::uint64_t stream_offset_ = 0;  // bytes before the current chunk
};

inline const char* JsonObjectCutter::scan(const char* p, const char* stop) {
  while (p < stop) {
    if (in_string_) {
      if (escaped_) {
        escaped_ = false;
        ++p;
        continue;
      }
      while (p < stop && *p != '"' && *p != '\\') ++p;
      if (p == stop) break;
      if (*p == '\\')
        escaped_ = true;
      else
        in_string_ = false;
      ++p;
      continue;
    }
    while (p < stop && *p != '"' && *p != '{' && *p != '}' && *p != '[' && *p != ']') ++p;
    if (p == stop) break;
    if (*p == '"') {
      in_string_ = true;
    } else if (*p == '{' || *p == '[') {
      ++depth_;
    } else if (--depth_ == 0) {
      mode_ = Mode::Between;
      return p;
    }
    ++p;
  }
  return stop;
}

template <class OnObject, class OnProblem>
void JsonObjectCutter::feed(std::span<const std::byte> bytes, OnObject&& on_object, OnProblem&& on_problem) {
  const char* const begin = reinterpret_cast<const char*>(bytes.data());
  const char* const end = begin + bytes.size();
  const char* object_begin = mode_ == Mode::InObject ? begin : nullptr;
  for (const char* p = begin; p < end; ++p) {
    switch (mode_) {
      case Mode::Between:
        if (*p == '{') {
          mode_ = Mode::InObject;
          depth_ = 1;
          in_string_ = escaped_ = garbage_reported_ = false;
          ++objects_;
          object_begin = p;
        } else if (!is_blank(*p) && *p != ',' && *p != '[' && *p != ']' && !garbage_reported_) {
          // One count per run of garbage, not one per byte.
          on_problem("bad_json", fmt::format("{}: unexpected byte 0x{:02x} at offset {} after object {}", what_,
                                             static_cast<unsigned char>(*p),
                                             stream_offset_ + static_cast<std::uint64_t>(p - begin), objects_));
          garbage_reported_ = true;
        }
        break;
      case Mode::InObject: {
        // The bytes up to the limit, then the one at the limit only if it closes the object.
        const char* const limit = object_begin + (max_object_bytes_ - object_.size());
        p = scan(p, std::min(end, limit));
        if (p == end) {
          p = end - 1;  // the loop's step ends it
          break;
        }
        if (p < limit || inside_object(*p)) {
          std::string_view object(object_begin, static_cast<std::size_t>(p + 1 - object_begin));
          if (!object_.empty()) {
            object_.append(object);
            object = object_;
          }
          on_object(object);
          object_.clear();
          object_begin = nullptr;
        } else {
          on_problem("object_too_long",
                     fmt::format("{} {}: longer than {} bytes, skipped", what_, objects_, max_object_bytes_));
          object_.clear();
          object_begin = nullptr;
          mode_ = Mode::Resync;
          resync_after_close_ = false;
        }
        break;
      }
      case Mode::Resync:
        resync(*p);
        break;
    }
  }
  if (mode_ == Mode::InObject) object_.append(object_begin, end);
  stream_offset_ += bytes.size();
}

}  // namespace kew::protocol::text
