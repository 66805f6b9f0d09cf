#include "json_object_cutter.hpp"

namespace kew::protocol::text {

bool JsonObjectCutter::finish() {
  const bool cut = mode_ == Mode::InObject;
  mode_ = Mode::Between;
  object_.clear();
  objects_ = 0;
  stream_offset_ = 0;
  garbage_reported_ = false;
  return cut;
}

bool JsonObjectCutter::inside_object(char c) {
  if (in_string_) {
    if (escaped_) {
      escaped_ = false;
    } else if (c == '\\') {
      escaped_ = true;
    } else if (c == '"') {
      in_string_ = false;
    }
    return false;
  }
  if (c == '"') {
    in_string_ = true;
  } else if (c == '{' || c == '[') {
    ++depth_;
  } else if (c == '}' || c == ']') {
    if (--depth_ == 0) {
      mode_ = Mode::Between;
      return true;
    }
  }
  return false;
}

// After an over-long object: its end is not known (it may be garbage), so skip to what
// ends a flat element in an array or a JSON-lines file: "}," "}]" or "}\n".
void JsonObjectCutter::resync(char c) {
  if (c == '}') {
    resync_after_close_ = true;
  } else if (resync_after_close_ && (c == ',' || c == ']' || c == '\n')) {
    mode_ = Mode::Between;
  } else if (!is_blank(c)) {
    resync_after_close_ = false;
  }
}

}  // namespace kew::protocol::text
