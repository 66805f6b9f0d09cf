#pragma once
// The routes of design §5.8: a request in, a reply out. Knows nothing of sockets: the
// session gives it the request, the client's address and the listener's port.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <boost/beast/http/message.hpp>
#include <boost/beast/http/string_body.hpp>

#include "http_source.hpp"
#include "kew/daemon/config.hpp"
#include "kew/util/rejections.hpp"
#include "static_files.hpp"
#include "volumes_json.hpp"

namespace kew::daemon::http {

using Request = boost::beast::http::request<boost::beast::http::string_body>;

struct Reply {
  unsigned status = 200;
  std::string content_type = "application/json";
  std::string body;
};

class Router {
 public:
  /// `refusals` counts the requests refused (by reason: not_found, method_not_allowed,
  /// ack_*...). `map` gives GET /api/map-config its tile server.
  Router(std::string web_root, std::string leaflet_root, std::vector<std::string> host_names,
         const HttpSource& source, Rejections& refusals, const HttpConfig& map = {});

  /// Answers `request` from `client` ("HOST:PORT") received on `port`.
  Reply handle(const Request& request, std::string_view client, std::uint16_t port);

  /// Whether a WebSocket upgrade of /ws may proceed: an Origin, when sent, names this
  /// server (so that another site's page in a local browser cannot read the stream).
  bool websocket_allowed(const Request& request, std::uint16_t port);

  const StaticFiles& web() const { return web_; }

 private:
  Reply acknowledge(const Request& request, std::string_view client, std::uint16_t port);
  Reply file(const StaticFiles& files, std::string_view path);
  Reply refuse(unsigned status, std::string_view reason, std::string_view message);
  /// Host names this server (localhost, an IP literal or a configured name, with the
  /// listener's port), and Origin, when sent, is "http://" + Host.
  bool same_origin(const Request& request, std::uint16_t port, std::string& why) const;

  StaticFiles web_;
  StaticFiles leaflet_;
  std::vector<std::string> host_names_;
  std::string map_config_;  ///< GET /api/map-config, made once
  std::string aerodromes_;  ///< GET /api/aerodromes, made at the first request
  std::optional<VolumesGeoJson> volumes_;  ///< GET /api/volumes' shapes, made at the first request
  const HttpSource& source_;
  Rejections& refusals_;
};

}  // namespace kew::daemon::http
