#include "volumes_json.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string_view>
#include <vector>

#include <GeographicLib/Geodesic.hpp>
#include <fmt/format.h>

#include "kew/protocol/ndjson_writer.hpp"

namespace kew::daemon::http {

namespace {

/// Writes JSON values in call order, objects and arrays nested, handling the commas: a
/// value after key() is that member's, any other is the next element of its array.
class JsonWriter {
 public:
  explicit JsonWriter(std::string& out) : out_(out) {}

  void begin_object() { open('{'); }
  void end_object() { close('}'); }
  void begin_array() { open('['); }
  void end_array() { close(']'); }

  void key(std::string_view name) {
    separate();
    protocol::append_json_string(out_, name);
    out_.push_back(':');
    after_key_ = true;
  }
  void string(std::string_view value) {
    prefix();
    protocol::append_json_string(out_, value);
  }
  /// The shortest text that reads back to `value`; null when not finite (JSON has no NaN).
  void number(double value) {
    prefix();
    if (std::isfinite(value))
      fmt::format_to(std::back_inserter(out_), "{}", value);
    else
      out_.append("null");
  }
  void boolean(bool value) {
    prefix();
    out_.append(value ? "true" : "false");
  }
  void null() {
    prefix();
    out_.append("null");
  }
  /// A value already written as JSON (by another JsonWriter).
  void json(std::string_view value) {
    prefix();
    out_.append(value);
  }

  void member(std::string_view name, std::string_view value) {
    key(name);
    string(value);
  }
  void member(std::string_view name, const char* value) { member(name, std::string_view(value)); }
  void member(std::string_view name, double value) {
    key(name);
    number(value);
  }
  void member(std::string_view name, bool value) {
    key(name);
    boolean(value);
  }

 private:
  void open(char bracket) {
    prefix();
    out_.push_back(bracket);
    first_.push_back(true);
  }
  void close(char bracket) {
    out_.push_back(bracket);
    first_.pop_back();
  }
  void prefix() {
    if (after_key_)
      after_key_ = false;
    else
      separate();
  }
  void separate() {
    if (first_.empty()) return;
    if (!first_.back()) out_.push_back(',');
    first_.back() = false;
  }

  std::string& out_;
  std::vector<bool> first_;  ///< per open object or array: nothing written in it yet
  bool after_key_ = false;
};

/// Twice the signed area of a ring of the gnomonic plane (x east, y north): positive
/// when counter-clockwise.
double signed_area2(const std::vector<geometry::Point2>& ring) {
  double sum = 0.0;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    sum += ring[j].x * ring[i].y - ring[i].x * ring[j].y;
  return sum;
}

/// `ring` closed, in the wanted sense, its longitudes continuous: each vertex's
/// longitude within 180° of the one before (a ring across the antimeridian goes beyond
/// ±180° rather than round the world).
volume::Ring geojson_ring(volume::Ring ring, bool counter_clockwise, bool is_counter_clockwise) {
  if (counter_clockwise != is_counter_clockwise) std::reverse(ring.begin() + 1, ring.end());
  for (std::size_t i = 1; i < ring.size(); ++i)
    ring[i].lon_deg = ring[i - 1].lon_deg + std::remainder(ring[i].lon_deg - ring[i - 1].lon_deg, 360.0);
  if (!ring.empty()) ring.push_back(ring.front());
  return ring;
}

void write_ring(JsonWriter& w, const volume::Ring& ring) {
  w.begin_array();
  for (const volume::LatLon& p : ring) {
    w.begin_array();
    w.number(p.lon_deg);
    w.number(p.lat_deg);
    w.end_array();
  }
  w.end_array();
}

/// A computed coordinate rounded to 1e-7° (about 1 cm), so that it prints short.
double rounded(double deg) { return std::round(deg * 1e7) / 1e7; }

/// kCirclePoints points at `radius_m` along geodesics from `centre`, counter-clockwise
/// (azimuth decreasing from north).
volume::Ring circle_ring(volume::LatLon centre, double radius_m) {
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  volume::Ring ring;
  ring.reserve(kCirclePoints + 1);
  for (int i = 0; i < kCirclePoints; ++i) {
    const double azimuth = -360.0 * i / kCirclePoints;
    double lat = 0.0, lon = 0.0;
    wgs84.Direct(centre.lat_deg, centre.lon_deg, azimuth, radius_m, lat, lon);
    ring.push_back({rounded(lat), rounded(lon)});
  }
  return ring;
}

std::string geometry_json(const volume::WatchedVolume& v) {
  std::string out;
  JsonWriter w(out);
  if (!v.area) {
    w.null();
    return out;
  }
  w.begin_object();
  w.member("type", "Polygon");
  w.key("coordinates");
  w.begin_array();
  if (v.area->is_circle()) {
    write_ring(w, geojson_ring(circle_ring(v.area->centre(), v.area->extent_m()), true, true));
  } else {
    const std::vector<volume::Ring>& rings = v.area->rings();
    const auto& plane = v.area->plane_rings();
    for (std::size_t i = 0; i < rings.size(); ++i) {
      const bool outer = i == 0;
      write_ring(w, geojson_ring(rings[i], outer, signed_area2(plane[i]) > 0.0));
    }
  }
  w.end_array();
  w.end_object();
  return out;
}

}  // namespace

VolumesGeoJson::VolumesGeoJson(const std::vector<volume::WatchedVolume>& volumes) : volumes_(volumes) {
  geometries_.reserve(volumes_.size());
  for (const volume::WatchedVolume& v : volumes_) {
    geometries_.push_back(geometry_json(v));
    bytes_ += geometries_.back().size();
  }
}

std::string VolumesGeoJson::text(double now_unix_s) const {
  std::string out;
  out.reserve(bytes_ + volumes_.size() * 300 + 64);
  JsonWriter w(out);
  w.begin_object();
  w.member("type", "FeatureCollection");
  w.member("t", now_unix_s);
  w.key("features");
  w.begin_array();
  for (std::size_t i = 0; i < volumes_.size(); ++i) {
    const volume::WatchedVolume& v = volumes_[i];
    w.begin_object();
    w.member("type", "Feature");
    w.member("id", v.name);
    w.key("geometry");
    w.json(geometries_[i]);
    w.key("properties");
    w.begin_object();
    w.member("name", v.name);
    w.member("kind", volume::kVolumeKindNames.name(v.kind));
    const volume::VerticalBand band = v.area ? v.area->band() : v.follow_band;
    w.member("floor_ft", band.floor_ft);
    w.member("ceiling_ft", band.ceiling_ft);
    w.member("active_now", v.schedule.active_at(now_unix_s));
    w.member("lookahead_s", v.lookahead_s);
    w.member("warning_s", v.warning_s);
    if (!v.area) {
      w.member("follow", v.follow);
      w.member("radius_m", v.follow_radius_m);
    } else if (v.area->is_circle()) {
      w.key("circle");
      w.begin_object();
      w.member("lat", v.area->centre().lat_deg);
      w.member("lon", v.area->centre().lon_deg);
      w.member("radius_m", v.area->extent_m());
      w.end_object();
    }
    w.end_object();
    w.end_object();
  }
  w.end_array();
  w.end_object();
  out.push_back('\n');
  return out;
}

}  // namespace kew::daemon::http
