// JsonObjectCutter (protocol/src/text, internal): the objects and problems it reports for
// a stream equal those of a plain byte-by-byte bracket counter, however the stream is cut
// into chunks and whatever the limit: random streams of nested objects, strings holding
// brackets, quotes and escapes, blanks, commas, garbage between objects.
#include <gtest/gtest.h>

#include <cstddef>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "json_object_cutter.hpp"

namespace kew::protocol::text {
namespace {

struct Cut {
  std::vector<std::string> objects;
  std::vector<std::string> problems;  // reasons
  bool truncated = false;
  bool operator==(const Cut&) const = default;
};

// The reference: one byte at a time, the limit checked at every byte that does not close
// the object; after an over-long object, skip to "}," "}]" or "}\n".
Cut reference_cut(std::string_view stream, std::size_t max) {
  Cut out;
  enum { Between, In, Resync } mode = Between;
  std::size_t depth = 0, start = 0;
  bool in_string = false, escaped = false, garbage = false, after_close = false;
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  for (std::size_t i = 0; i < stream.size(); ++i) {
    const char c = stream[i];
    if (mode == Between) {
      if (c == '{') {
        mode = In;
        depth = 1;
        in_string = escaped = garbage = false;
        start = i;
      } else if (!blank(c) && c != ',' && c != '[' && c != ']' && !garbage) {
        out.problems.push_back("bad_json");
        garbage = true;
      }
    } else if (mode == In) {
      bool closed = false;
      if (in_string) {
        if (escaped) escaped = false;
        else if (c == '\\') escaped = true;
        else if (c == '"') in_string = false;
      } else if (c == '"') {
        in_string = true;
      } else if (c == '{' || c == '[') {
        ++depth;
      } else if ((c == '}' || c == ']') && --depth == 0) {
        closed = true;
      }
      if (closed) {
        out.objects.emplace_back(stream.substr(start, i + 1 - start));
        mode = Between;
      } else if (i + 1 - start > max) {
        out.problems.push_back("object_too_long");
        mode = Resync;
        after_close = false;
      }
    } else {
      if (c == '}') after_close = true;
      else if (after_close && (c == ',' || c == ']' || c == '\n')) mode = Between;
      else if (!blank(c)) after_close = false;
    }
  }
  out.truncated = mode == In;
  return out;
}

Cut cutter_cut(std::string_view stream, std::size_t max, const std::vector<std::size_t>& cuts) {
  Cut out;
  JsonObjectCutter cutter("element", max);
  std::size_t at = 0;
  const auto feed_to = [&](std::size_t to) {
    const auto* bytes = reinterpret_cast<const std::byte*>(stream.data() + at);
    cutter.feed(
        std::span<const std::byte>(bytes, to - at), [&](std::string_view object) { out.objects.emplace_back(object); },
        [&](std::string_view reason, const std::string&) { out.problems.emplace_back(reason); });
    at = to;
  };
  for (const std::size_t cut : cuts) feed_to(cut);
  feed_to(stream.size());
  out.truncated = cutter.finish();
  return out;
}

std::string random_value(std::mt19937& random, int depth);

std::string random_string(std::mt19937& random) {
  static const std::string alphabet = "ab{}[]\",:\\ 1";
  std::string s = "\"";
  const int n = std::uniform_int_distribution<int>(0, 8)(random);
  for (int i = 0; i < n; ++i) {
    const char c = alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(random)];
    if (c == '"' || c == '\\') s += '\\';
    s += c;
  }
  return s + "\"";
}

std::string random_object(std::mt19937& random, int depth) {
  std::string s = "{";
  const int n = std::uniform_int_distribution<int>(0, 4)(random);
  for (int i = 0; i < n; ++i) s += (i ? "," : "") + random_string(random) + ":" + random_value(random, depth + 1);
  return s + "}";
}

std::string random_value(std::mt19937& random, int depth) {
  switch (std::uniform_int_distribution<int>(0, depth > 3 ? 1 : 3)(random)) {
    case 0: return std::to_string(std::uniform_int_distribution<int>(-999, 99999)(random));
    case 1: return random_string(random);
    case 2: return random_object(random, depth);
    default: {
      std::string s = "[";
      const int n = std::uniform_int_distribution<int>(0, 3)(random);
      for (int i = 0; i < n; ++i) s += (i ? "," : "") + random_value(random, depth + 1);
      return s + "]";
    }
  }
}

std::string random_stream(std::mt19937& random) {
  static const std::vector<std::string> between = {"", " ", ",", "\n", "[", "]", "},", "x", "}\n", " \t"};
  std::string s;
  const int n = std::uniform_int_distribution<int>(0, 12)(random);
  for (int i = 0; i < n; ++i) {
    s += between[std::uniform_int_distribution<std::size_t>(0, between.size() - 1)(random)];
    s += random_object(random, 0);
  }
  // Sometimes an object cut short by the end of the stream.
  if (std::uniform_int_distribution<int>(0, 4)(random) == 0) {
    const std::string last = random_object(random, 0);
    s += last.substr(0, last.size() / 2);
  }
  return s;
}

TEST(JsonObjectCutter, EqualsAByteByByteCounterHoweverCutAndLimited) {
  std::mt19937 random(20261206);
  int too_long = 0;
  for (int round = 0; round < 4000; ++round) {
    const std::string stream = random_stream(random);
    const std::size_t max = std::uniform_int_distribution<std::size_t>(2, 120)(random);
    std::vector<std::size_t> cuts;
    const int pieces = std::uniform_int_distribution<int>(0, 6)(random);
    for (int i = 0; i < pieces && !stream.empty(); ++i)
      cuts.push_back(std::uniform_int_distribution<std::size_t>(0, stream.size())(random));
    std::sort(cuts.begin(), cuts.end());
    const Cut expected = reference_cut(stream, max);
    ASSERT_EQ(cutter_cut(stream, max, cuts), expected) << "stream: " << stream << "\nlimit: " << max;
    for (const std::string& p : expected.problems) too_long += p == "object_too_long";
  }
  EXPECT_GT(too_long, 500) << "the limit must be exercised";
}

}  // namespace
}  // namespace kew::protocol::text
