#include "kew/config/document.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <cctype>
#include <filesystem>
#include <optional>

#include "kew/config/address.hpp"
#include "kew/config/aip_coordinates.hpp"
#include "kew/config/nats_servers.hpp"
#include "kew/config/utc_day.hpp"

namespace kew::config {

TableReader::TableReader(const toml::table& table, std::string_view origin, std::string name)
    : table_(table), origin_(origin), name_(std::move(name)) {}

void TableReader::fail(const toml::node* node, std::string_view message) const {
  std::string where(origin_);
  if (node && node->source().begin.line > 0) where += fmt::format(":{}", node->source().begin.line);
  throw ConfigError(fmt::format("{}: [{}] {}", where, name_, message));
}

const toml::node* TableReader::take(std::string_view key) {
  used_.insert(std::string(key));
  return table_.get(key);
}

void TableReader::number(std::string_view key, double& out, double lo, double hi) {
  const toml::node* node = take(key);
  if (!node) return;
  double v;
  if (const auto* i = node->as_integer()) v = static_cast<double>(i->get());
  else if (const auto* f = node->as_floating_point()) v = f->get();
  else fail(node, fmt::format("{} must be a number", key));
  if (!(v >= lo && v <= hi)) fail(node, fmt::format("{} = {} is outside [{}, {}]", key, v, lo, hi));
  out = v;
}

void TableReader::boolean(std::string_view key, bool& out) {
  const toml::node* node = take(key);
  if (!node) return;
  const auto* b = node->as_boolean();
  if (!b) fail(node, fmt::format("{} must be true or false", key));
  out = b->get();
}

void TableReader::string(std::string_view key, std::string& out) {
  const toml::node* node = take(key);
  if (!node) return;
  const auto* s = node->as_string();
  if (!s) fail(node, fmt::format("{} must be a string", key));
  out = s->get();
}

void TableReader::mode3a_list(std::string_view key, std::vector<std::uint16_t>& out) {
  string_list(key, "Mode 3/A codes (\"7777\")", "a string of four octal digits (\"7777\")", out,
              [](const std::string& text) -> std::optional<std::uint16_t> {
                if (text.size() != 4 || text.find_first_not_of("01234567") != std::string::npos) return std::nullopt;
                return static_cast<std::uint16_t>(std::stoul(text, nullptr, 8));
              });
}

void TableReader::address(std::string_view key, std::string& out) {
  const toml::node* node = table_.get(key);
  string(key, out);
  std::string error;
  if (node && !parse_host_port(out, &error)) fail(node, fmt::format("{} = {}", key, error));
}

void TableReader::ip_list(std::string_view key, std::vector<std::string>& out) {
  string_list(key, "IP addresses (\"127.0.0.1\")",
              "an IPv4 or IPv6 address without port or brackets (\"127.0.0.1\", \"::1\")", out,
              [](const std::string& text) { return canonical_ip(text); });
}

void TableReader::host_name_list(std::string_view key, std::vector<std::string>& out) {
  string_list(key, "host names (\"kew.example\")", "a host name of letters, digits, '-' and '.'", out,
              [](std::string text) -> std::optional<std::string> {
                if (text.empty() || text.size() > 253) return std::nullopt;
                for (char& c : text) {
                  if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') return std::nullopt;
                  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
                }
                return text;
              });
}

void TableReader::text_list(std::string_view key, std::vector<std::string>& out) {
  string_list(key, "strings", "a non-empty string on one line", out, [](std::string text) -> std::optional<std::string> {
    if (text.empty() || text.find_first_of("\r\n") != std::string::npos) return std::nullopt;
    return text;
  });
}

void TableReader::word_list(std::string_view key, std::vector<std::string>& out) {
  string_list(key, "words", "a word without blanks", out, [](std::string text) -> std::optional<std::string> {
    if (text.empty()) return std::nullopt;
    for (const char c : text)
      if (static_cast<unsigned char>(c) <= ' ' || c == 0x7f) return std::nullopt;
    return text;
  });
}

void TableReader::http_url(std::string_view key, std::string& out) {
  const toml::node* node = take(key);
  if (!node) return;
  const auto* text = node->as_string();
  const std::string_view url = text ? std::string_view(text->get()) : std::string_view();
  const std::size_t scheme_end = url.find("://");
  const std::string_view scheme = scheme_end == std::string_view::npos ? "" : url.substr(0, scheme_end);
  const std::string_view rest = scheme_end == std::string_view::npos ? "" : url.substr(scheme_end + 3);
  const bool spaces = url.find_first_of(" \t\r\n") != std::string_view::npos;
  if ((scheme != "http" && scheme != "https") || rest.empty() || rest.front() == '/' || spaces)
    fail(node, fmt::format("{} must be an http:// or https:// URL with a host (\"https://host/path\")", key));
  // A password in the URL would be in every log line that names the URL, and in the
  // configuration everyone may read: credentials come from files.
  if (rest.substr(0, rest.find_first_of("/?#")).find('@') != std::string_view::npos)
    fail(node, fmt::format("{}: a user or password in the URL (user:password@host) would be logged and readable "
                           "by everyone; give them in a file (credentials_file, token_file, url_file)",
                           key));
  out = url;
}

void TableReader::http_header_list(std::string_view key, std::vector<std::string>& out) {
  string_list(key, "HTTP headers (\"Name: value\")", "\"Name: value\" on one line", out,
              [](std::string text) -> std::optional<std::string> {
                const std::size_t colon = text.find(':');
                if (colon == 0 || colon == std::string::npos) return std::nullopt;
                for (std::size_t i = 0; i < colon; ++i) {
                  const unsigned char c = static_cast<unsigned char>(text[i]);
                  if (!std::isalnum(c) && std::string_view("!#$%&'*+-.^_`|~").find(static_cast<char>(c)) ==
                                              std::string_view::npos)
                    return std::nullopt;
                }
                if (text.find_first_of("\r\n") != std::string::npos) return std::nullopt;
                return text;
              });
}

void TableReader::nats_servers(std::string_view key, std::vector<std::string>& out) {
  const toml::node* node = take(key);
  if (!node) return;
  std::string error;
  if (const auto* text = node->as_string()) {
    if (text->get().empty()) {
      out.clear();
      return;
    }
    std::optional<std::vector<std::string>> servers = parse_nats_servers(text->get(), &error);
    // The error quotes the entry at fault: the whole string too when it is a list.
    if (!servers)
      fail(node, text->get().find(',') == std::string::npos ? fmt::format("{} = {}", key, error)
                                                           : fmt::format("{} = \"{}\": {}", key, text->get(), error));
    out = std::move(*servers);
    return;
  }
  const auto* array = node->as_array();
  if (!array) fail(node, fmt::format("{} must be an array of NATS server URLs (\"nats://HOST:PORT\")", key));
  std::vector<std::string> servers;
  for (const toml::node& element : *array) {
    const auto* text = element.as_string();
    if (!text) fail(&element, fmt::format("{}: each entry is a NATS server URL (\"nats://HOST:PORT\")", key));
    if (!valid_nats_server(text->get(), &error)) fail(&element, fmt::format("{}: {}", key, error));
    servers.push_back(text->get());
  }
  out = std::move(servers);
}

void TableReader::path(std::string_view key, std::string& out) {
  string(key, out);
  if (!out.empty()) out = std::filesystem::absolute(out).lexically_normal().string();
}

void TableReader::path_beside_file(std::string_view key, std::string& out) {
  string(key, out);
  if (!out.empty())
    out = std::filesystem::absolute(std::filesystem::path(origin_).parent_path() / out).lexically_normal().string();
}

void TableReader::utc_day(std::string_view key, std::string& out) {
  const toml::node* node = table_.get(key);
  string(key, out);
  if (node && !parse_utc_day(out)) fail(node, fmt::format("{} = \"{}\" is not YYYY-MM-DD", key, out));
}

namespace {
// [lat, lon] in range, or nullopt.
std::optional<geo::GeodeticPosition> lat_lon(const toml::node& node) {
  const toml::array* pair = node.as_array();
  if (!pair || pair->size() != 2) return std::nullopt;
  double degrees[2];
  for (std::size_t i = 0; i < 2; ++i) {
    const std::optional<double> value = (*pair)[i].value<double>();  // an integer or a float
    if (!value) return std::nullopt;
    degrees[i] = *value;
  }
  if (!(std::abs(degrees[0]) <= 90.0 && std::abs(degrees[1]) <= 180.0)) return std::nullopt;
  return geo::GeodeticPosition{degrees[0], degrees[1]};
}
constexpr std::string_view kLatLon = "[lat, lon]: latitude in [-90, 90] then longitude in [-180, 180], degrees";
}  // namespace

void TableReader::position(std::string_view key, std::optional<geo::GeodeticPosition>& out) {
  const toml::node* node = take(key);
  if (!node) return;
  const auto position = lat_lon(*node);
  if (!position) fail(node, fmt::format("{} must be {}", key, kLatLon));
  out = position;
}

void TableReader::position_list(std::string_view key, std::vector<geo::GeodeticPosition>& out) {
  const toml::node* node = take(key);
  if (!node) return;
  if (const std::optional<std::string> text = node->value<std::string>()) {
    std::string error;
    std::optional<std::vector<geo::GeodeticPosition>> positions = parse_aip_coordinates(*text, error);
    if (!positions) fail(node, fmt::format("{}: {}", key, error));
    out = std::move(*positions);
    return;
  }
  const toml::array* array = node->as_array();
  if (!array)
    fail(node, fmt::format("{} must be an array of positions [[lat, lon], ...] or a text of AIP coordinates "
                           "(\"471234N 0083456E - 471500N 0084000E - ...\")",
                           key));
  std::vector<geo::GeodeticPosition> positions;
  for (const toml::node& element : *array) {
    const auto position = lat_lon(element);
    if (!position) fail(&element, fmt::format("{}: entry {} must be {}", key, positions.size() + 1, kLatLon));
    positions.push_back(*position);
  }
  out = std::move(positions);
}

void TableReader::finish() const {
  for (const auto& [key, node] : table_)
    if (!used_.count(key.str())) fail(&node, fmt::format("unknown key \"{}\"", key.str()));
}

Document Document::parse(std::string_view text, std::string origin) {
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw ConfigError(fmt::format("{}:{}:{}: {}", origin, e.source().begin.line, e.source().begin.column,
                                  e.description()));
  }
  return Document(std::move(root), std::move(origin));
}

// The file's text, refused before anything large is read: a configuration is a small
// regular file, and a path to a device, a pipe or a huge file must fail at once rather
// than fill the memory of `--check-config` or of a daemon reloading on SIGHUP.
std::string read_config_file(const std::string& path, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO without a writer must not wait; it is refused just below.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw ConfigError(fmt::format("{}: cannot open ({})", path, std::strerror(errno)));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat status {};
  if (::fstat(fd, &status) != 0) throw ConfigError(fmt::format("{}: {}", path, std::strerror(errno)));
  if (!S_ISREG(status.st_mode))
    throw ConfigError(fmt::format("{}: not a regular file ({}), refused", path,
                                  S_ISDIR(status.st_mode) ? "a directory" : "a device, pipe or socket"));
  const auto too_large = [&] { return ConfigError(fmt::format("{}: larger than {} bytes, refused", path, max_bytes)); };
  if (static_cast<std::uint64_t>(status.st_size) > max_bytes) throw too_large();
  // The size may change under us: read at most one byte more than the cap.
  std::string text(max_bytes + 1, '\0');
  std::size_t used = 0;
  while (used < text.size()) {
    const ssize_t n = ::read(fd, text.data() + used, text.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw ConfigError(fmt::format("{}: read error ({})", path, std::strerror(errno)));
    if (n == 0) break;
    used += static_cast<std::size_t>(n);
  }
  if (used > max_bytes) throw too_large();
  text.resize(used);
  return text;
}

Document Document::load(const std::string& path) { return parse(read_config_file(path), path); }

void Document::refuse_unknown_sections(std::span<const std::string_view> known) const {
  for (const auto& [key, node] : root_) {
    bool found = false;
    for (const std::string_view name : known) found = found || key.str() == name;
    if (!found)
      throw ConfigError(fmt::format("{}:{}: unknown section or key \"{}\"", origin_, node.source().begin.line,
                                    key.str()));
  }
}

const toml::table* Document::table(std::string_view name) const {
  const toml::node* node = root_.get(name);
  if (!node) return nullptr;
  if (!node->is_table())
    throw ConfigError(fmt::format("{}:{}: {} must be a table", origin_, node->source().begin.line, name));
  return node->as_table();
}

const toml::array* Document::array_of_tables(std::string_view name) const {
  const toml::node* node = root_.get(name);
  if (!node) return nullptr;
  const toml::array* array = node->as_array();
  if (!array || !array->is_array_of_tables())
    throw ConfigError(fmt::format("{}:{}: {} must be written as [[{}]] tables", origin_, node->source().begin.line,
                                  name, name));
  return array;
}

}  // namespace kew::config
