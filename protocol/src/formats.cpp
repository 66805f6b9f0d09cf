// Format names, detection and the decoder factory; described in formats.hpp.
#include "kew/protocol/formats.hpp"

#include <fmt/format.h>
#include <simdjson.h>

#include <array>
#include <cstdio>
#include <map>
#include <vector>

#include "kew/protocol/gzip.hpp"
#include "kew/protocol/ndjson.hpp"
#include "kew/protocol/opensky.hpp"
#include "kew/protocol/opensky_rest.hpp"
#include "kew/protocol/readsb.hpp"
#include "kew/protocol/readsb_trace.hpp"
#include "kew/protocol/sbs.hpp"
#include "text/decoder_chain.hpp"

namespace kew::protocol {
namespace {

// Detection reads at most this much inflated text, and the auto decoder buffers this much
// at most before deciding.
constexpr std::size_t kDetectMaxBytes = 64 * 1024;
// The auto decoder's first attempt: enough for a dozen lines of any text format.
constexpr std::size_t kDetectFirstTryBytes = 4 * 1024;
// Text lines looked at before giving up on a text format.
constexpr int kDetectMaxLines = 16;
// Least ASTERIX framing confidence accepted: 0.4 is what the heuristics give a file
// holding exactly one plausible data block (the single-record test vectors).
constexpr double kAsterixMinConfidence = 0.4;
// Bytes looked at to tell text from binary.
constexpr std::size_t kTextSampleBytes = 1024;
// Line starts tried after leading noise (a stream opening with garbage), within
// the 64 KiB the auto decoder buffers: bounds the work of one detection.
constexpr int kDetectMaxRestarts = 1024;

std::string_view as_text(std::span<const std::byte> bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

/// Text: valid UTF-8 without control bytes but tab, CR, LF (ASTERIX blocks are full of
/// zeros and small lengths; the GPS-framed recordings start with 2200 bytes of 0xCD).
bool looks_like_text(std::string_view head) {
  std::string_view sample = head.substr(0, kTextSampleBytes);
  if (sample.empty()) return false;
  for (const char c : sample) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\t' && c != '\n' && c != '\r') || byte == 0x7f) return false;
  }
  // The sample (or the head itself) may end inside a multi-byte character: drop up to
  // 3 bytes of it.
  for (int cut = 0; cut < 4 && !sample.empty(); ++cut) {
    if (simdjson::validate_utf8(sample.data(), sample.size())) return true;
    sample.remove_suffix(1);
  }
  return false;
}

bool contains(std::string_view line, std::string_view token) {
  return line.find(token) != std::string_view::npos;
}

bool starts_sbs_message(std::string_view line) {
  for (const std::string_view kind : {"MSG,", "SEL,", "ID,", "AIR,", "STA,", "CLK,"})
    if (line.starts_with(kind)) return true;
  return false;
}

/// The format one meaningful (non-blank, non-comment) line belongs to, Auto if none.
Format classify_line(std::string_view line) {
  if (starts_sbs_message(line)) return Format::Sbs;
  if (line.starts_with("[")) {
    const auto brace = line.find('{');
    if (brace == std::string_view::npos) return Format::Auto;
    line.remove_prefix(brace);
  }
  if (line.starts_with("{")) {
    if (contains(line, "\"alt_ft\"") && contains(line, "\"t\"")) return Format::Ndjson;
    if (contains(line, "\"icao24\"")) return Format::OpenskyJson;
    if (contains(line, "\"hex\"") || contains(line, "\"now\"")) return Format::ReadsbJson;
    return Format::Auto;
  }
  if (contains(line, "icao24") && contains(line, ",")) return Format::OpenskyCsv;
  return Format::Auto;
}

/// Where the value of a `"key":` member of the JSON `text` starts, for each such member
/// in turn (`from`: past the previous one); npos when there is none further. Text, not
/// JSON: a key inside a string may match too, so callers ask for keys no string of their
/// formats holds.
std::size_t member_value(std::string_view text, std::string_view key, std::size_t from = 0) {
  for (auto at = text.find(key, from); at != std::string_view::npos; at = text.find(key, at + 1)) {
    auto p = text.find_first_not_of(" \t\r\n", at + key.size());
    if (p == std::string_view::npos || text[p] != ':') continue;
    p = text.find_first_not_of(" \t\r\n", p + 1);
    if (p != std::string_view::npos) return p;
  }
  return std::string_view::npos;
}

/// True when some `"key":` member of `text` has a value starting with one of `starts`
/// ("[" for an array), and then, when `then` is given, the next non-blank byte after that
/// start is one of `then` ("[]": an array of arrays, or an empty one).
bool has_member(std::string_view text, std::string_view key, std::string_view starts, std::string_view then = {}) {
  for (auto p = member_value(text, key); p != std::string_view::npos; p = member_value(text, key, p)) {
    if (starts.find(text[p]) == std::string_view::npos) continue;
    if (then.empty()) return true;
    const auto next = text.find_first_not_of(" \t\r\n", p + 1);
    if (next != std::string_view::npos && then.find(text[next]) != std::string_view::npos) return true;
  }
  return false;
}

/// The formats whose stream is one JSON object after another, told apart by their members
/// wherever they stand in the head: an aircraft.json snapshot's "aircraft" or "ac" array
/// (readsb JSON lines never hold one), a readsb trace's "icao" and "trace" array, an OpenSky
/// REST response's "states" array of arrays (or null). None of these keys is one of
/// another of these formats, and no string of theirs holds one with its quotes.
Format detect_json_snapshots(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos || text[first] != '{') return Format::Auto;
  if (has_member(text, "\"aircraft\"", "[") || has_member(text, "\"ac\"", "[")) return Format::AircraftJson;
  if (has_member(text, "\"trace\"", "[") && member_value(text, "\"icao\"") != std::string_view::npos)
    return Format::ReadsbTrace;
  if (has_member(text, "\"states\"", "[", "[]") || has_member(text, "\"states\"", "n")) return Format::OpenskyRest;
  return Format::Auto;
}

Format detect_text(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);  // UTF-8 byte order mark
  if (const Format snapshots = detect_json_snapshots(text); snapshots != Format::Auto) return snapshots;
  int lines = 0;
  while (!text.empty() && lines < kDetectMaxLines) {
    const auto newline = text.find('\n');
    std::string_view line = text.substr(0, newline);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') continue;
    ++lines;
    // The JSON array of opensky-json has no newline at all: its first "line" is cut by
    // the end of the head, which still shows the first element's keys.
    const Format format = classify_line(line.substr(first));
    if (format != Format::Auto) return format;
  }
  return Format::Auto;
}

Format detect_binary(std::span<const std::byte> head) {
  Format best = Format::Auto;
  double best_confidence = 0.0;
  const std::pair<AsterixFraming, Format> kFramings[] = {
      {AsterixFraming::Pcap, Format::AsterixPcap},
      {AsterixFraming::FinalFormat, Format::AsterixFinalFormat},
      {AsterixFraming::RawBlocks, Format::AsterixRaw}};
  for (const auto& [framing, format] : kFramings) {
    const double confidence = asterix_framing_confidence(framing, head);
    if (confidence > best_confidence) {
      best_confidence = confidence;
      best = format;
    }
  }
  return best_confidence >= kAsterixMinConfidence ? best : Format::Auto;
}

/// Where a stream's format shows: its first byte, or the first line after noise.
struct Detection {
  Format format = Format::Auto;
  std::size_t start = 0;  // bytes of noise before the detected data
};

/// The format of `head`, else of the text after its first noise: the lines are tried from
/// each line start in turn (at most kDetectMaxRestarts), as text only (the ASTERIX
/// heuristics would find a "plausible block" somewhere in enough noise).
Detection detect_after_noise(std::span<const std::byte> head) {
  if (const Format format = detect_format(head); format != Format::Auto) return {format, 0};
  const std::string_view text = as_text(head);
  std::size_t start = 0;
  for (int restart = 0; restart < kDetectMaxRestarts; ++restart) {
    const std::size_t newline = text.find('\n', start);
    if (newline == std::string_view::npos || newline + 1 == text.size()) break;
    start = newline + 1;
    const std::string_view rest = text.substr(start);
    if (!looks_like_text(rest)) continue;
    if (const Format format = detect_text(rest); format != Format::Auto) return {format, start};
  }
  return {};
}

/// Buffers the start of a stream until its format is known, then hands everything after
/// any leading noise to the decoder of that format.
class AutoDecoder final : public Decoder {
 public:
  explicit AutoDecoder(const DecoderOptions& options) : options_(options) {}

  std::string_view format_name() const override {
    return inner_ ? inner_->format_name() : std::string_view("auto");
  }
  std::size_t max_message_bytes() const override {
    return inner_ ? std::max(inner_->max_message_bytes(), kDetectMaxBytes) : kDetectMaxBytes;
  }

  void feed(std::span<const std::byte> bytes, const ReportSink& sink) override {
    if (inner_) {
      inner_->feed(bytes, sink);
      return;
    }
    if (unknown_) return;
    const std::size_t take = std::min(kDetectMaxBytes - head_.size(), bytes.size());
    head_.insert(head_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(take));
    // Detection looks at exactly the first 4 KiB, then exactly the first 64 KiB, so the
    // outcome does not depend on how the stream was cut into feed() calls.
    bool decided = false;
    if (!tried_first_ && head_.size() >= kDetectFirstTryBytes) {
      tried_first_ = true;
      decided = try_detect(kDetectFirstTryBytes, false, sink);
    }
    if (!decided && head_.size() >= kDetectMaxBytes) decided = try_detect(kDetectMaxBytes, true, sink);
    if (decided) inner_->feed(bytes.subspan(take), sink);
  }

  void finish(const ReportSink& sink) override { end(false, sink); }
  void end_message(const ReportSink& sink) override { end(true, sink); }
  void set_receive_time(std::optional<double> utc_s) override {
    receive_time_ = utc_s;
    if (inner_) inner_->set_receive_time(utc_s);
  }

 private:
  /// finish() (`message` false) or end_message(): a stream or a datagram is judged on
  /// what arrived, and the next bytes are detected afresh. After a datagram the decoder
  /// of its format is kept for the next datagram of that format: what a format carries
  /// from one message to the next (aircraft.json's positions reported, SBS's merges)
  /// holds across datagrams as it does for an explicit format; finish() forgets it.
  void end(bool message, const ReportSink& sink) {
    if (!inner_ && !unknown_ && !head_.empty()) try_detect(head_.size(), true, sink);
    if (inner_ && message) {
      inner_->end_message(sink);
      parked_[inner_format_] = std::move(inner_);
    } else if (inner_) {
      inner_->finish(sink);
    }
    if (!message) parked_.clear();
    inner_.reset();
    unknown_ = false;
    tried_first_ = false;
    head_.clear();
  }

  /// Detects on the first `head_bytes` of the buffered head; on success makes the decoder
  /// and feeds it the head from the detected start on (noise before it is counted). When
  /// `last_try`, an unknown format is final (counted).
  bool try_detect(std::size_t head_bytes, bool last_try, const ReportSink& sink) {
    const Detection detection = detect_after_noise(std::span<const std::byte>(head_).first(head_bytes));
    if (detection.format == Format::Auto) {
      if (last_try) {
        rejections().reject("unknown_format",
                            fmt::format("auto: the first {} bytes match no known format; "
                                        "stream ignored", head_bytes));
        unknown_ = true;
        head_.clear();
      }
      return false;
    }
    if (detection.start > 0)
      rejections().reject("unknown_format",
                          fmt::format("auto: the first {} bytes match no known format; skipped, {} after them",
                                      detection.start, to_string(detection.format)));
    inner_format_ = detection.format;
    if (const auto kept = parked_.find(detection.format); kept != parked_.end()) {
      inner_ = std::move(kept->second);
      parked_.erase(kept);
    } else {
      inner_ = make_decoder(detection.format, options_);
      text::forward_rejections(*inner_, rejections());
    }
    inner_->set_receive_time(receive_time_);
    inner_->feed(std::span<const std::byte>(head_).subspan(detection.start), sink);
    head_.clear();
    return true;
  }

  DecoderOptions options_;
  std::optional<double> receive_time_;
  std::unique_ptr<Decoder> inner_;
  Format inner_format_ = Format::Auto;
  std::map<Format, std::unique_ptr<Decoder>> parked_;  // after a datagram, by format
  std::vector<std::byte> head_;
  bool tried_first_ = false;
  bool unknown_ = false;
};

std::unique_ptr<Decoder> make_plain_decoder(Format format, const DecoderOptions& options) {
  switch (format) {
    case Format::Ndjson:
      return make_ndjson_decoder({.max_line_bytes = options.max_line_bytes});
    case Format::Sbs:
      return make_sbs_decoder(
          {.utc_offset_s = options.sbs_utc_offset_s, .max_line_bytes = options.max_line_bytes});
    case Format::OpenskyCsv:
      return make_opensky_csv_decoder({.max_line_bytes = options.max_line_bytes});
    case Format::OpenskyJson:
      return make_opensky_json_decoder({.max_object_bytes = options.max_line_bytes});
    case Format::ReadsbJson:
      return make_readsb_decoder({.max_line_bytes = options.max_line_bytes});
    case Format::AircraftJson:
      return make_aircraft_json_decoder(options.aircraft_json);
    case Format::OpenskyRest:
      return make_opensky_rest_decoder(options.aircraft_json);
    case Format::ReadsbTrace:
      return make_readsb_trace_decoder(options.aircraft_json);
    case Format::AsterixRaw:
      return make_asterix_decoder(AsterixFraming::RawBlocks, options.asterix);
    case Format::AsterixFinalFormat:
      return make_asterix_decoder(AsterixFraming::FinalFormat, options.asterix);
    case Format::AsterixPcap:
      return make_asterix_decoder(AsterixFraming::Pcap, options.asterix);
    case Format::AsterixDatagram:
      return make_asterix_decoder(AsterixFraming::Datagram, options.asterix);
    case Format::Auto:
      break;
  }
  return std::make_unique<AutoDecoder>(options);
}

}  // namespace

Format detect_format(std::span<const std::byte> head) {
  if (has_gzip_magic(head)) {
    const std::vector<std::byte> inflated = gunzip_prefix(head, kDetectMaxBytes);
    // A gzip file holding gzip is not a recording format.
    if (has_gzip_magic(inflated)) return Format::Auto;
    return detect_format(inflated);
  }
  const std::string_view text = as_text(head);
  if (looks_like_text(text)) return detect_text(text);
  return detect_binary(head);
}

std::unique_ptr<Decoder> make_decoder(Format format, const DecoderOptions& options) {
  std::unique_ptr<Decoder> decoder = make_plain_decoder(format, options);
  // A datagram decoder needs each feed() to be one datagram, which the gzip sniffer
  // could split; live UDP is never compressed anyway. The auto decoder wraps what it makes.
  if (format == Format::AsterixDatagram || format == Format::Auto) return decoder;
  return make_gzip_decoder(std::move(decoder), GzipMode::WhenMagic);
}

}  // namespace kew::protocol
