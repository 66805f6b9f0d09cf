#include "router.hpp"

#include <algorithm>
#include <cctype>
#include <iterator>

#include <boost/beast/http/field.hpp>
#include <boost/beast/http/verb.hpp>
#include <fmt/format.h>

#include "kew/config/address.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/util/clocks.hpp"

namespace kew::daemon::http {

namespace beast = boost::beast;
namespace bhttp = boost::beast::http;

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// A Host header ("name", "name:port", "[::1]:port"; the port may be left out, 80) read
/// by the one HOST:PORT reader; the host lower-cased. nullopt if malformed.
std::optional<config::HostPort> parse_host_header(std::string_view text) {
  const bool bracketed = !text.empty() && text.front() == '[';
  const bool has_port = text.find(bracketed ? "]:" : ":") != std::string_view::npos;
  std::optional<config::HostPort> host = config::parse_host_port(has_port ? std::string(text) : std::string(text) + ":80");
  if (host) host->host = lower(host->host);
  return host;
}

std::string_view path_of(std::string_view target) { return target.substr(0, target.find('?')); }

/// {"tile_url":"…","tile_attribution":"…"}: what the map's page needs of [http].
std::string map_config_json(const HttpConfig& map) {
  std::string out = "{\"tile_url\":";
  protocol::append_json_string(out, map.tile_url);
  out += ",\"tile_attribution\":";
  protocol::append_json_string(out, map.tile_attribution);
  out += "}\n";
  return out;
}

/// [{"icao":…,"name":…,"lat":…,"lon":…,"elevation_ft":…}, …] in the table's order; "name"
/// is "" when the table has none.
std::string aerodromes_json(const eligibility::AerodromeTable* table) {
  std::string out = "[";
  if (table) {
    out.reserve(table->size() * 80);
    for (const eligibility::Aerodrome& a : table->aerodromes()) {
      if (out.size() > 1) out += ",\n";
      out += "{\"icao\":";
      protocol::append_json_string(out, a.ident);
      out += ",\"name\":";
      protocol::append_json_string(out, a.name);
      fmt::format_to(std::back_inserter(out), ",\"lat\":{},\"lon\":{},\"elevation_ft\":{}}}", a.lat_deg, a.lon_deg,
                     a.elevation_ft);
    }
  }
  out += "]\n";
  return out;
}

}  // namespace

Router::Router(std::string web_root, std::string leaflet_root, std::vector<std::string> host_names,
               const HttpSource& source, Rejections& refusals, const HttpConfig& map)
    : web_(std::move(web_root)),
      leaflet_(std::move(leaflet_root)),
      host_names_(std::move(host_names)),
      map_config_(map_config_json(map)),
      source_(source),
      refusals_(refusals) {}

Reply Router::refuse(unsigned status, std::string_view reason, std::string_view message) {
  refusals_.reject(reason, message);
  Reply reply{status, "application/json", {}};
  reply.body = "{\"error\":";
  protocol::append_json_string(reply.body, message);
  reply.body += "}\n";
  return reply;
}

Reply Router::handle(const Request& request, std::string_view client, std::uint16_t port) {
  const std::string_view path = path_of(std::string_view(request.target().data(), request.target().size()));
  if (path == "/api/ack") return acknowledge(request, client, port);
  if (request.method() != bhttp::verb::get && request.method() != bhttp::verb::head)
    return refuse(405, "method_not_allowed", "only GET and HEAD here (POST for /api/ack)");
  if (path == "/api/tracks") return {200, "application/json", source_.tracks()};
  if (path == "/api/alerts") return {200, "application/json", source_.alerts()};
  if (path == "/api/status") return {200, "application/json", source_.status()};
  if (path == "/api/zones") return {200, "application/json", source_.zones()};
  if (path == "/api/map-config") return {200, "application/json", map_config_};
  if (path == "/api/aerodromes") {
    if (aerodromes_.empty()) aerodromes_ = aerodromes_json(source_.aerodromes.get());
    return {200, "application/json", aerodromes_};
  }
  if (path == "/api/volumes") {
    if (!volumes_) volumes_.emplace(source_.volumes ? *source_.volumes : std::vector<volume::WatchedVolume>{});
    const double now = util::unix_now_s();
    return {200, "application/geo+json", volumes_->text(now)};
  }
  if (path == "/metrics") return {200, "text/plain; version=0.0.4; charset=utf-8", source_.metrics()};
  if (path == "/ws") return refuse(426, "not_websocket", "/ws is a WebSocket: send an upgrade request");
  constexpr std::string_view kLeaflet = "/leaflet";
  if (path.substr(0, kLeaflet.size()) == kLeaflet && (path.size() == kLeaflet.size() || path[kLeaflet.size()] == '/'))
    return file(leaflet_, path.size() == kLeaflet.size() ? "/" : path.substr(kLeaflet.size()));
  return file(web_, path);
}

Reply Router::file(const StaticFiles& files, std::string_view path) {
  StaticFile f;
  switch (files.read(path, f)) {
    case StaticResult::Found:
      return {200, std::move(f.content_type), std::move(f.body)};
    case StaticResult::NotFound:
      return refuse(404, "not_found", "no such file");
    case StaticResult::TooLarge:
      return refuse(403, "file_too_large", "file larger than the server sends");
    case StaticResult::Forbidden:
      break;
  }
  return refuse(403, "forbidden_path", "path outside the served files");
}

bool Router::same_origin(const Request& request, std::uint16_t port, std::string& why) const {
  const auto host_field = request.find(bhttp::field::host);
  if (host_field == request.end()) {
    why = "no Host header";
    return false;
  }
  const std::string_view host_text(host_field->value().data(), host_field->value().size());
  const std::optional<config::HostPort> host = parse_host_header(host_text);
  if (!host) {
    why = "malformed Host header";
    return false;
  }
  const bool known = host->host == "localhost" || config::canonical_ip(host->host) ||
                     std::find(host_names_.begin(), host_names_.end(), host->host) != host_names_.end();
  if (!known || host->port != port) {
    why = fmt::format("Host {} does not name this server", host_text);
    return false;
  }
  const auto origin = request.find(bhttp::field::origin);
  if (origin != request.end()) {
    const std::string_view origin_text(origin->value().data(), origin->value().size());
    if (lower(origin_text) != "http://" + lower(host_text)) {
      why = fmt::format("Origin {} is not this server", origin_text);
      return false;
    }
  }
  return true;
}

bool Router::websocket_allowed(const Request& request, std::uint16_t port) {
  std::string why;
  if (request.find(bhttp::field::origin) == request.end() || same_origin(request, port, why)) return true;
  refusals_.reject("websocket_foreign_origin", why);
  return false;
}

Reply Router::acknowledge(const Request& request, std::string_view client, std::uint16_t port) {
  if (request.method() != bhttp::verb::post) return refuse(405, "method_not_allowed", "/api/ack takes POST");
  const auto header = request.find("X-Kew-Ack");
  if (header == request.end() || header->value() != "1") return refuse(403, "ack_no_header", "X-Kew-Ack: 1 missing");
  std::string why;
  if (!same_origin(request, port, why)) return refuse(403, "ack_foreign_origin", why);
  const auto type = request.find(bhttp::field::content_type);
  const std::string media =
      type == request.end() ? std::string() : lower(std::string_view(type->value().data(), type->value().size()));
  if (media.substr(0, media.find(';')) != "application/json")
    return refuse(400, "ack_not_json", "Content-Type must be application/json");
  const protocol::AckParseResult parsed = protocol::parse_ack_request(request.body());
  if (!parsed.ok) return refuse(400, "ack_bad_body", parsed.error);
  const std::vector<std::string> ids = source_.acknowledge(parsed.request, client);
  Reply reply{200, "application/json", "{\"acknowledged\":["};
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i) reply.body.push_back(',');
    protocol::append_json_string(reply.body, ids[i]);
  }
  reply.body += "]}\n";
  return reply;
}

}  // namespace kew::daemon::http
