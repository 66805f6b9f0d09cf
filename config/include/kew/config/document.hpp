#pragma once
// Reading a kew TOML file (design §5.7): the parsed document, and TableReader, which
// reads one table's keys with their types and ranges and then refuses every key it was
// not asked for, so that a typo never silently leaves a default in force. Every error is
// a ConfigError naming "file:line". Included by the code that parses sections (here and
// in daemon/), not by the users of the resulting configuration types.

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "kew/config/config_error.hpp"
#include "kew/geo/projection.hpp"
#include "kew/util/name_table.hpp"

namespace kew::config {

/// Reads the keys of one TOML table. Each reader leaves `out` untouched when the key is
/// absent (the default stays) and throws ConfigError when it is present but wrong.
class TableReader {
 public:
  /// `origin`: the file's name in messages; `name`: the table's ("tracks", "input 2").
  TableReader(const toml::table& table, std::string_view origin, std::string name);

  /// Throws "origin:line: [name] message"; the line is the node's, when known.
  [[noreturn]] void fail(const toml::node* node, std::string_view message) const;

  /// A number (integer or float) in [lo, hi].
  void number(std::string_view key, double& out, double lo, double hi);
  /// An integer in [lo, hi], stored as Int.
  template <class Int>
  void integer(std::string_view key, Int& out, std::int64_t lo, std::int64_t hi) {
    const toml::node* node = take(key);
    if (!node) return;
    const auto* i = node->as_integer();
    if (!i) fail(node, fmt::format("{} must be an integer", key));
    if (i->get() < lo || i->get() > hi) fail(node, fmt::format("{} = {} is outside [{}, {}]", key, i->get(), lo, hi));
    out = static_cast<Int>(i->get());
  }
  void boolean(std::string_view key, bool& out);
  void string(std::string_view key, std::string& out);
  /// A string that must be one of the names of `names` (but `except`); the error lists them.
  template <class Enum, std::size_t N>
  void choice(std::string_view key, Enum& out, const util::NameTable<Enum, N>& names,
              std::initializer_list<Enum> except = {}) {
    const toml::node* node = table_.get(key);
    std::string text;
    string(key, text);
    if (!node) return;
    const auto value = names.parse(text);
    bool excluded = false;
    for (const Enum x : except) excluded = excluded || (value && *value == x);
    if (!value || excluded) fail(node, fmt::format("{} = \"{}\": expected one of {}", key, text, names.list(except)));
    out = *value;
  }
  /// A list of names of `names` (["new", "ended"]); the error lists them.
  template <class Enum, std::size_t N>
  void choice_list(std::string_view key, std::vector<Enum>& out, const util::NameTable<Enum, N>& names) {
    const std::string each = "one of " + names.list();
    string_list(key, "names", each, out, [&](const std::string& text) { return names.parse(text); });
  }
  /// A list of non-empty strings without line breaks (["Mon-Fri 0600-1800"]).
  void text_list(std::string_view key, std::vector<std::string>& out);
  /// The node of `key`, taken as read (the caller reads it itself); nullptr when absent.
  const toml::node* take_node(std::string_view key) { return take(key); }
  /// A list of words: non-empty strings without blanks or control characters (callsign
  /// patterns, region names, addresses), kept as written.
  void word_list(std::string_view key, std::vector<std::string>& out);
  /// A list of 12-bit Mode 3/A codes, each a string of four octal digits ("7777").
  void mode3a_list(std::string_view key, std::vector<std::uint16_t>& out);
  /// A "HOST:PORT" string, checked with parse_host_port (address.hpp) and kept as text.
  void address(std::string_view key, std::string& out);
  /// A list of IPv4 or IPv6 addresses without ports (["127.0.0.1", "::1"]), each checked
  /// and kept in canonical_ip form (address.hpp), so that they compare as text.
  void ip_list(std::string_view key, std::vector<std::string>& out);
  /// A list of host names (["kew.example"]): letters, digits, '-' and '.', kept lower-case.
  void host_name_list(std::string_view key, std::vector<std::string>& out);
  /// An http:// or https:// URL with a host (a poll input's address), kept as written;
  /// a user or password in it (user:password@host) is refused: credentials come from files.
  void http_url(std::string_view key, std::string& out);
  /// HTTP request headers, ["Name: value", ...]: a name of token characters (RFC 9110
  /// §5.1), a colon, a value without line breaks.
  void http_header_list(std::string_view key, std::vector<std::string>& out);
  /// NATS servers: an array of URLs (["nats://h1:4222", "nats://h2:4222"]), or one string
  /// of comma-separated URLs, each checked with valid_nats_server (nats_servers.hpp); an
  /// error quotes the entry and says what is wrong. "" and [] name none (out empty).
  void nats_servers(std::string_view key, std::vector<std::string>& out);
  /// A file path that belongs with the configuration file (a table it names, as [regions]
  /// geojson): a relative path is resolved against the directory of the file being read
  /// (`origin`), kept absolute and normalised. "" stays "".
  void path_beside_file(std::string_view key, std::string& out);
  /// A file path. A relative path is resolved against the working directory kewd was
  /// started in and kept absolute and normalised ("../log/a" → "/srv/log/a"), so that
  /// what is checked, reported and opened is one file even after the daemon changes
  /// directory to /. "" stays "" (the file is disabled).
  void path(std::string_view key, std::string& out);
  /// A "YYYY-MM-DD" string, checked with parse_utc_day (utc_day.hpp) and kept as text.
  void utc_day(std::string_view key, std::string& out);
  /// A position [lat, lon] in WGS84 degrees, latitude first as everywhere in kew's TOML
  /// (latitude in [-90, 90], longitude in [-180, 180]).
  void position(std::string_view key, std::optional<geo::GeodeticPosition>& out);
  /// An array of positions [[lat, lon], ...], or a text of positions as an AIP writes
  /// them ("471234N 0083456E - 471500N 0084000E - ...", aip_coordinates.hpp); an error
  /// names the entry (from 1) and its line.
  void position_list(std::string_view key, std::vector<geo::GeodeticPosition>& out);

  /// An inline or nested table `key` ({ lat = 1.0, lon = 2.0 }): calls read(TableReader&)
  /// on it, then refuses the keys `read` did not take; false when the key is absent.
  template <class Read>
  bool subtable(std::string_view key, Read&& read) {
    const toml::node* node = take(key);
    if (!node) return false;
    const toml::table* t = node->as_table();
    if (!t) fail(node, fmt::format("{} must be a table ({{ key = value, ... }})", key));
    TableReader reader(*t, origin_, name_ + " " + std::string(key));
    read(reader);
    reader.finish();
    return true;
  }

  /// The file's name in messages.
  std::string_view origin() const { return origin_; }
  /// The node of `key`, nullptr when absent (to point a message about it at its line).
  const toml::node* node(std::string_view key) const { return table_.get(key); }
  /// The table itself (a message about the table as a whole: its header's line).
  const toml::node* table_node() const { return &table_; }

  /// Refuses every key of the table that no reader above took.
  void finish() const;

 private:
  const toml::node* take(std::string_view key);
  /// An array of strings, each turned into a T by `convert` (nullopt: refused). `what`
  /// names the array's entries, `each` what one entry must be, in the error messages.
  template <class T, class Convert>
  void string_list(std::string_view key, std::string_view what, std::string_view each, std::vector<T>& out,
                   Convert convert) {
    const toml::node* node = take(key);
    if (!node) return;
    const auto* array = node->as_array();
    if (!array) fail(node, fmt::format("{} must be an array of {}", key, what));
    std::vector<T> values;
    for (const toml::node& element : *array) {
      const auto* text = element.as_string();
      std::optional<T> value = text ? convert(text->get()) : std::nullopt;
      if (!value) fail(&element, fmt::format("{}: each entry is {}", key, each));
      values.push_back(std::move(*value));
    }
    out = std::move(values);
  }

  const toml::table& table_;
  std::string_view origin_;
  std::string name_;
  std::set<std::string, std::less<>> used_;
};

/// Largest configuration file read, bytes (1 MiB; the shipped kew.toml is a few KB).
inline constexpr std::size_t kMaxConfigBytes = 1 << 20;

/// The text of a configuration file (a kew TOML file, or a GeoJSON or aerodrome file it
/// names). Throws ConfigError naming the file when it cannot be read, is not a regular
/// file (/dev/zero, a pipe) or is larger than max_bytes; nothing more than the cap is
/// ever read.
std::string read_config_file(const std::string& path, std::size_t max_bytes = kMaxConfigBytes);

/// A parsed configuration file.
class Document {
 public:
  /// Parses TOML text; `origin` names it in messages. Throws ConfigError
  /// ("origin:line:column: ...") on a syntax error.
  static Document parse(std::string_view text, std::string origin);
  /// Reads (read_config_file) and parses the file at `path`. Throws ConfigError.
  static Document load(const std::string& path);

  const std::string& origin() const { return origin_; }
  /// Throws ConfigError naming the first top-level key that is none of `known`.
  void refuse_unknown_sections(std::span<const std::string_view> known) const;
  /// Calls read(TableReader&) on table [name] when the file has one, then refuses the
  /// keys `read` did not take.
  template <class Read>
  void section(std::string_view name, Read&& read) const {
    if (const toml::table* t = table(name)) {
      TableReader reader(*t, origin_, std::string(name));
      read(reader);
      reader.finish();
    }
  }
  /// Calls read(TableReader&, index) on each table of the array [[name]], in file order
  /// (index from 0; messages number them from 1: "[input 2]").
  template <class Read>
  void each_table(std::string_view name, Read&& read) const {
    const toml::array* array = array_of_tables(name);
    if (!array) return;
    std::size_t index = 0;
    for (const toml::node& element : *array) {
      TableReader reader(*element.as_table(), origin_, fmt::format("{} {}", name, index + 1));
      read(reader, index++);
      reader.finish();
    }
  }

 private:
  Document(toml::table root, std::string origin) : root_(std::move(root)), origin_(std::move(origin)) {}
  const toml::table* table(std::string_view name) const;
  const toml::array* array_of_tables(std::string_view name) const;

  toml::table root_;
  std::string origin_;
};

}  // namespace kew::config
