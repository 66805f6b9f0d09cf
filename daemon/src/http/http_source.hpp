#pragma once
// What the HTTP server asks of the service (design §5.8). Every function runs on the I/O
// thread, so it reads the pipeline as it is between two records.

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "kew/eligibility/aerodromes.hpp"
#include "kew/protocol/encoders/alert_json_reader.hpp"
#include "kew/volume/watched_volume.hpp"

namespace kew::daemon::http {

struct HttpSource {
  std::function<std::string()> tracks;    ///< GET /api/tracks: the TRACKS object
  std::function<std::string()> alerts;    ///< GET /api/alerts: the ALERTS object
  std::function<std::string()> status;    ///< GET /api/status: ALIVE with data_t, wall_t
  std::function<std::string()> zones;     ///< GET /api/zones: ZONES (design §4.9)
  std::function<std::string()> metrics;   ///< GET /metrics: the Prometheus exposition
  /// The first WebSocket message: a JSON array of every live track, every active alert
  /// and ALIVE.
  std::function<std::string()> snapshot;
  /// POST /api/ack from `client` ("HOST:PORT"): the same acknowledgement as Modbus coil 0,
  /// reported "by":"web". Returns the ids acknowledged.
  std::function<std::vector<std::string>(const protocol::AckRequest& request, std::string_view client)> acknowledge;
  /// GET /api/aerodromes: the table the eligibility lower limit uses ([eligibility]
  /// aerodromes_file); null: an empty list.
  std::shared_ptr<const eligibility::AerodromeTable> aerodromes;
  /// GET /api/volumes: the volumes of the area proximity warning (the pipeline's
  /// PipelineConfig::volumes, design §4.11); null: none.
  std::shared_ptr<const std::vector<volume::WatchedVolume>> volumes;
};

}  // namespace kew::daemon::http
