// Canonical NDJSON output; described in ndjson_writer.hpp.
#include "kew/protocol/ndjson_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iterator>

namespace kew::protocol {
namespace {

/// Length of the valid UTF-8 sequence starting at text[i] (RFC 3629: no overlong forms,
/// no surrogates, nothing above U+10FFFF), or 0 when the bytes there are not one.
std::size_t utf8_sequence_length(std::string_view text, std::size_t i) {
  const auto at = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = at(i);
  std::size_t length = 0;
  unsigned char second_min = 0x80, second_max = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) second_min = 0xA0;  // overlong below U+0800
    if (lead == 0xED) second_max = 0x9F;  // UTF-16 surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) second_min = 0x90;  // overlong below U+10000
    if (lead == 0xF4) second_max = 0x8F;  // above U+10FFFF
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  if (at(i + 1) < second_min || at(i + 1) > second_max) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if (at(i + k) < 0x80 || at(i + k) > 0xBF) return 0;
  return length;
}

void append_number(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  // fmt writes -0.0 as "-0", which JSON parsers read as the integer 0: keep the sign.
  if (value == 0.0 && std::signbit(value)) {
    out += "-0.0";
    return;
  }
  fmt::format_to(std::back_inserter(out), "{}", value);
}

void append_member(std::string& out, std::string_view key, double value) {
  out += ",\"";
  out += key;
  out += "\":";
  append_number(out, value);
}

}  // namespace

void append_json_string(std::string& out, std::string_view text) {
  out += '"';
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x80) {
      const std::size_t length = utf8_sequence_length(text, i);
      if (length == 0) {
        out += "\\ufffd";
        ++i;
      } else {
        out.append(text.substr(i, length));
        i += length;
      }
      continue;
    }
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      default:
        if (byte < 0x20) {
          fmt::format_to(std::back_inserter(out), "\\u{:04x}", byte);
        } else {
          out += c;
        }
    }
    ++i;
  }
  out += '"';
}

void append_ndjson(std::string& out, const TrackReport& report) {
  out += "{\"t\":";
  append_number(out, report.t);
  out += ",\"id\":";
  append_json_string(out, report.id);
  append_member(out, "lat", report.lat_deg);
  append_member(out, "lon", report.lon_deg);
  append_member(out, "alt_ft", report.alt_ft);
  if (report.gs_kt) append_member(out, "gs_kt", *report.gs_kt);
  if (report.trk_deg) append_member(out, "trk_deg", *report.trk_deg);
  if (report.vr_fpm) append_member(out, "vr_fpm", *report.vr_fpm);
  if (report.sel_ft) {
    append_member(out, "sel_ft", *report.sel_ft);
    out += ",\"sel_src\":\"";
    out += to_string(report.sel_src);
    out += '"';
  }
  if (report.tar_dps) append_member(out, "tar_dps", *report.tar_dps);
  if (!report.callsign.empty()) {
    out += ",\"cs\":";
    append_json_string(out, report.callsign);
  }
  if (!report.source.empty()) {
    out += ",\"src\":";
    append_json_string(out, report.source);
  }
  if (!report.position_source.empty()) {
    out += ",\"pos_src\":";
    append_json_string(out, report.position_source);
  }
  if (report.on_ground) out += ",\"gnd\":true";
  if (report.mode3a) fmt::format_to(std::back_inserter(out), ",\"sq\":\"{:04o}\"", *report.mode3a & 07777u);
  if (report.address) fmt::format_to(std::back_inserter(out), ",\"addr\":\"{:06X}\"", *report.address & 0xFFFFFFu);
  if (report.coasting) out += ",\"coast\":true";
  if (report.track_end) out += ",\"end\":true";
  out += '}';
}

std::string to_ndjson_line(const TrackReport& report) {
  std::string line;
  append_ndjson(line, report);
  line += '\n';
  return line;
}

}  // namespace kew::protocol
