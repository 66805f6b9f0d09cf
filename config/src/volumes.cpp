#include "kew/config/volumes.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "geojson_features.hpp"
#include "kew/util/units.hpp"
#include "kew/volume/entry.hpp"
#include "name_places.hpp"

namespace kew::config {

namespace {

namespace dom = geojson::dom;
using volume::LatLon;
using volume::Ring;
using volume::VerticalBand;
using volume::WatchedVolume;

constexpr double kNoValue = NAN;
constexpr double kRadiusNmLo = 0.001, kRadiusNmHi = 4800.0;  // a circle's, fixed or followed
constexpr double kBandFtLo = -100000.0, kBandFtHi = 200000.0;

// ---- One reader of a volume's keys, in both forms ----

// A volume's shape, as its form (a [[volume]] table or a GeoJSON Feature) gives it.
struct Shape {
  enum class Kind { Polygon, Circle, Follow } kind = Kind::Polygon;
  Ring outer;                   ///< Polygon
  std::vector<Ring> holes;      ///< Polygon
  LatLon centre;                ///< Circle
  double radius_nm = kNoValue;  ///< Circle, Follow
  std::string follow;           ///< Follow: the followed aircraft's address or callsign
  /// Where a message about the outer ring, the holes or the circle points: a TOML key's
  /// line; nullptr in GeoJSON, whose messages name the Feature instead.
  const toml::node* outer_node = nullptr;
  const toml::node* holes_node = nullptr;
  const toml::node* circle_node = nullptr;
};

// The keys of a volume in a [[volume]] table or a GeoJSON Feature's properties. `form`
// reads the keys of its shape (form.read_keys(r), with the others) and, once every key
// is read and no unknown key is left (a misspelt key is named before what its absence
// implies), the shape itself (form.shape(r)).
template <class Form>
WatchedVolume read_volume(TableReader& r, Form& form, const eligibility::AerodromeTable* aerodromes) {
  WatchedVolume v;
  r.string("name", v.name);
  if (v.name.empty())
    r.fail(r.node("name") ? r.node("name") : r.table_node(), "a volume needs a name (a non-empty string)");
  r.choice("kind", v.kind, volume::kVolumeKindNames);
  form.read_keys(r);
  VerticalBand band{kNoValue, kNoValue};
  r.number("floor_ft", band.floor_ft, kBandFtLo, kBandFtHi);
  r.number("ceiling_ft", band.ceiling_ft, kBandFtLo, kBandFtHi);
  std::string reference = "msl", aerodrome;
  r.string("reference", reference);
  r.string("aerodrome", aerodrome);
  std::vector<std::string> active;
  r.text_list("active", active);
  r.word_list("callsigns", v.traffic.callsigns);
  r.word_list("addresses", v.traffic.addresses);
  r.mode3a_list("squawks", v.traffic.squawks);
  r.number("lookahead_s", v.lookahead_s, 1.0, volume::kMaxHorizon_s);
  r.number("warning_s", v.warning_s, 1.0, volume::kMaxHorizon_s);
  r.finish();

  const Shape shape = form.shape(r);
  if (std::isnan(band.floor_ft) || std::isnan(band.ceiling_ft))
    r.fail(r.table_node(), "a volume needs floor_ft and ceiling_ft");
  if (reference == "aerodrome") {
    if (aerodrome.empty()) r.fail(r.node("reference"), "reference = \"aerodrome\" needs aerodrome = \"ICAO\"");
    const eligibility::Aerodrome* a = aerodromes ? aerodromes->find(aerodrome) : nullptr;
    if (!a) r.fail(r.node("aerodrome"), fmt::format("aerodrome = \"{}\" is not in the aerodrome table", aerodrome));
    band.floor_ft += a->elevation_ft;
    band.ceiling_ft += a->elevation_ft;
  } else if (reference != "msl") {
    r.fail(r.node("reference"), fmt::format("reference = \"{}\": expected msl or aerodrome", reference));
  } else if (!aerodrome.empty()) {
    r.fail(r.node("aerodrome"), "aerodrome names the elevation of reference = \"aerodrome\"");
  }

  if (shape.kind == Shape::Kind::Follow) {
    if (reference == "aerodrome")
      r.fail(r.node("reference"), "a followed volume's band is relative to the followed aircraft");
    if (!(band.floor_ft < band.ceiling_ft)) r.fail(r.node("ceiling_ft"), "ceiling_ft must be above floor_ft");
    v.follow = shape.follow;
    v.follow_radius_m = shape.radius_nm * units::kMetresPerNauticalMile;
    v.follow_band = band;
  } else {
    const bool circle = shape.kind == Shape::Kind::Circle;
    const volume::VolumeResult made =
        circle ? volume::Volume::circle(shape.centre, shape.radius_nm * units::kMetresPerNauticalMile, band)
               : volume::Volume::polygon(shape.outer, shape.holes, band);
    if (!made.volume) {
      const toml::node* where = made.error == volume::VolumeError::BandInverted ? r.node("ceiling_ft")
                                : circle                                        ? shape.circle_node
                                : made.ring == 0                                ? shape.outer_node
                                                                                : shape.holes_node;
      const std::string hole = !circle && made.ring > 0 ? fmt::format(" (hole {})", made.ring) : "";
      r.fail(where, fmt::format("the volume is refused: {}{}", volume::kVolumeErrorNames.name(made.error), hole));
    }
    v.area = made.volume;
  }

  std::string error;
  const auto schedule = volume::WeeklySchedule::parse(active, error);
  if (!schedule) r.fail(r.node("active"), "active: " + error);
  v.schedule = *schedule;
  if (v.warning_s > v.lookahead_s)
    r.fail(r.node("warning_s"), fmt::format("warning_s = {} is beyond lookahead_s = {}", v.warning_s, v.lookahead_s));
  return v;
}

// ---- TOML: [[volume]] ----

Ring ring_of(const std::vector<geo::GeodeticPosition>& positions) {
  Ring ring;
  for (const geo::GeodeticPosition& p : positions) ring.push_back({p.lat_deg, p.lon_deg});
  return ring;
}

/// holes = [[[lat, lon], ...], ...]: each an array of positions.
std::vector<Ring> read_holes(TableReader& r) {
  std::vector<Ring> holes;
  const toml::node* node = r.take_node("holes");
  if (!node) return holes;
  const toml::array* array = node->as_array();
  if (!array) r.fail(node, "holes must be an array of rings [[[lat, lon], ...], ...]");
  for (std::size_t i = 0; i < array->size(); ++i) {
    // Each ring is read as a position list of a table of its own, so its errors name it.
    toml::table ring_table;
    ring_table.insert("ring", *array->get(i));
    TableReader ring_reader(ring_table, r.origin(), fmt::format("hole {}", i + 1));
    std::vector<geo::GeodeticPosition> positions;
    ring_reader.position_list("ring", positions);
    holes.push_back(ring_of(positions));
  }
  return holes;
}

// The shape of a [[volume]] table: polygon with holes, circle, or follow with radius_nm.
class TableShape {
 public:
  void read_keys(TableReader& r) {
    r.position_list("polygon", polygon_);
    holes_ = read_holes(r);
    circle_ = r.subtable("circle", [&](TableReader& c) {
      double lat = kNoValue, lon = kNoValue;
      c.number("lat", lat, -90.0, 90.0);
      c.number("lon", lon, -180.0, 180.0);
      c.number("radius_nm", circle_radius_nm_, kRadiusNmLo, kRadiusNmHi);
      if (std::isnan(lat) || std::isnan(lon) || std::isnan(circle_radius_nm_))
        c.fail(c.table_node(), "a circle needs lat, lon and radius_nm");
      centre_ = LatLon{lat, lon};
    });
    r.string("follow", follow_);
    r.number("radius_nm", follow_radius_nm_, kRadiusNmLo, kRadiusNmHi);
  }

  Shape shape(const TableReader& r) const {
    const int shapes = !polygon_.empty() + circle_ + !follow_.empty();
    if (shapes != 1)
      r.fail(r.table_node(), "a volume is one of polygon = [[lat, lon], ...], circle = { lat, lon, radius_nm } "
                             "or follow = \"ADDRESS or CALLSIGN\" with radius_nm");
    if (!holes_.empty() && polygon_.empty()) r.fail(r.node("holes"), "holes belong to a polygon");
    if (!std::isnan(follow_radius_nm_) && follow_.empty())
      r.fail(r.node("radius_nm"), "radius_nm (beside follow) is a followed circle's; a fixed circle is "
                                  "circle = { lat, lon, radius_nm }");
    Shape s;
    s.outer_node = r.node("polygon");
    s.holes_node = r.node("holes");
    s.circle_node = r.node("circle");
    if (!follow_.empty()) {
      if (std::isnan(follow_radius_nm_)) r.fail(r.node("follow"), "follow needs radius_nm");
      s.kind = Shape::Kind::Follow;
      s.follow = follow_;
      s.radius_nm = follow_radius_nm_;
    } else if (circle_) {
      s.kind = Shape::Kind::Circle;
      s.centre = centre_;
      s.radius_nm = circle_radius_nm_;
    } else {
      s.outer = ring_of(polygon_);
      s.holes = holes_;
    }
    return s;
  }

 private:
  std::vector<geo::GeodeticPosition> polygon_;
  std::vector<Ring> holes_;
  bool circle_ = false;
  LatLon centre_;
  double circle_radius_nm_ = kNoValue;
  std::string follow_;
  double follow_radius_nm_ = kNoValue;
};

// ---- GeoJSON (RFC 7946) ----

// The shape of a Feature: its geometry, a Polygon or a Point with properties.radius_nm.
class FeatureShape {
 public:
  explicit FeatureShape(dom::object feature) : feature_(feature) {}

  void read_keys(TableReader& r) {
    if (r.node("follow"))
      r.fail(r.node("follow"), "follow is refused in GeoJSON: a followed volume has no geometry of its own; write "
                               "it as a [[volume]] table with follow and radius_nm");
    for (const std::string_view key : {"polygon", "holes", "circle"})
      if (r.node(key))
        r.fail(r.node(key), fmt::format("properties.{} is refused: the Feature's geometry is the volume's shape (a "
                                        "Polygon with its holes, or a Point with properties.radius_nm)",
                                        key));
    r.number("radius_nm", radius_nm_, kRadiusNmLo, kRadiusNmHi);
  }

  Shape shape(const TableReader& r) const {
    const geojson::Geometry geometry = geojson::polygon_or_point(r, feature_, "volume", radius_nm_);
    Shape s;
    if (geometry.polygon) {
      std::vector<Ring> rings = polygon_rings(r, geometry.coordinates);
      s.outer = std::move(rings.front());
      s.holes.assign(std::make_move_iterator(rings.begin() + 1), std::make_move_iterator(rings.end()));
    } else {
      const geo::GeodeticPosition centre = geojson::point_position(r, geometry.coordinates);
      s.kind = Shape::Kind::Circle;
      s.centre = LatLon{centre.lat_deg, centre.lon_deg};
      s.radius_nm = radius_nm_;
    }
    return s;
  }

 private:
  // A Polygon's rings, the exterior one first, each without its closing position.
  static std::vector<Ring> polygon_rings(const TableReader& r, dom::element coordinates) {
    constexpr std::string_view kRings = "a Polygon's coordinates are an array of rings, each an array of positions";
    dom::array rings;
    if (coordinates.get_array().get(rings) != simdjson::SUCCESS) r.fail(nullptr, kRings);
    if (rings.size() == 0) r.fail(nullptr, "a Polygon needs its exterior ring");
    std::vector<Ring> out;
    for (const dom::element element : rings) {
      const std::string which = out.empty() ? "exterior ring" : fmt::format("hole {}", out.size());
      const geojson::Ring ring = geojson::read_ring(element);
      switch (ring.fault) {
        case geojson::RingFault::None: break;
        case geojson::RingFault::NotArray: r.fail(nullptr, kRings);
        case geojson::RingFault::BadPosition:
          r.fail(nullptr,
                 fmt::format("Polygon {}: position {} must be {}", which, ring.bad_position, geojson::kLonLat));
        case geojson::RingFault::NotClosed:
          r.fail(nullptr, fmt::format("Polygon {} is not closed: at least 4 positions, the last equal to the first "
                                      "(RFC 7946 §3.1.6)",
                                      which));
      }
      out.push_back(ring_of(ring.positions));
    }
    return out;
  }

  dom::object feature_;
  double radius_nm_ = kNoValue;
};

// "feature 2 "ED-R 138"" (or "feature 2" without a name): how messages name a Feature.
std::string feature_label(std::size_t index, const toml::table& properties) {
  const toml::node* name = properties.get("name");
  if (name && name->is_string() && !name->as_string()->get().empty())
    return fmt::format("feature {} \"{}\"", index + 1, name->as_string()->get());
  return fmt::format("feature {}", index + 1);
}

WatchedVolume read_feature(dom::element element, const std::string& origin, std::size_t index,
                           const eligibility::AerodromeTable* aerodromes) {
  const geojson::Feature feature = geojson::open_feature(element);
  TableReader r(feature.properties, origin, feature_label(index, feature.properties));
  if (!feature.problem.empty()) r.fail(nullptr, feature.problem);
  FeatureShape shape(feature.object);
  return read_volume(r, shape, aerodromes);
}

std::string feature_place(std::size_t index, const WatchedVolume& v) {
  return fmt::format("[feature {} \"{}\"]", index + 1, v.name);
}

}  // namespace

std::vector<WatchedVolume> parse_volumes_geojson(std::string_view text, const std::string& origin,
                                                 const eligibility::AerodromeTable* aerodromes) {
  return geojson::read_features<WatchedVolume>(
      text, origin,
      [&](dom::element feature, std::size_t index) { return read_feature(feature, origin, index, aerodromes); },
      feature_place);
}

std::vector<WatchedVolume> read_volumes(const Document& document, const eligibility::AerodromeTable* aerodromes,
                                        std::string* geojson_path) {
  std::vector<WatchedVolume> volumes;
  NamePlaces names;
  document.each_table("volume", [&](TableReader& r, std::size_t index) {
    TableShape shape;
    WatchedVolume v = read_volume(r, shape, aerodromes);
    if (const std::string* earlier = names.taken(v.name))
      r.fail(r.node("name"), fmt::format("name \"{}\" is already the name of {}", v.name, *earlier));
    names.add(v.name, fmt::format("[volume {}]", index + 1));
    volumes.push_back(std::move(v));
  });
  const std::string path = append_geojson_items(
      document, "volumes", names, volumes,
      [&](const std::string& text, const std::string& origin) {
        return parse_volumes_geojson(text, origin, aerodromes);
      },
      feature_place);
  if (geojson_path) *geojson_path = path;
  return volumes;
}

}  // namespace kew::config
