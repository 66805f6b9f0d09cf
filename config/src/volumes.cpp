#include "kew/config/volumes.hpp"

#include <cmath>

#include <fmt/format.h>

#include "kew/util/units.hpp"
#include "kew/volume/entry.hpp"

namespace kew::config {

namespace {

using volume::LatLon;
using volume::Ring;
using volume::VerticalBand;
using volume::WatchedVolume;

constexpr double kNoValue = NAN;

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

}  // namespace

std::vector<WatchedVolume> read_volumes(const Document& document, const eligibility::AerodromeTable* aerodromes) {
  std::vector<WatchedVolume> volumes;
  document.each_table("volume", [&](TableReader& r, std::size_t) {
    WatchedVolume v;
    r.string("name", v.name);
    if (v.name.empty()) r.fail(r.node("name") ? r.node("name") : r.table_node(), "a volume needs a name");
    for (const WatchedVolume& other : volumes)
      if (other.name == v.name) r.fail(r.node("name"), fmt::format("name \"{}\" is another volume's already", v.name));
    r.choice("kind", v.kind, volume::kVolumeKindNames);

    std::vector<geo::GeodeticPosition> polygon;
    r.position_list("polygon", polygon);
    const std::vector<Ring> holes = read_holes(r);
    std::optional<geo::GeodeticPosition> centre;
    double radius_nm = kNoValue;
    const bool circle = r.subtable("circle", [&](TableReader& c) {
      double lat = kNoValue, lon = kNoValue;
      c.number("lat", lat, -90.0, 90.0);
      c.number("lon", lon, -180.0, 180.0);
      c.number("radius_nm", radius_nm, 0.001, 4800.0);
      if (std::isnan(lat) || std::isnan(lon) || std::isnan(radius_nm))
        c.fail(c.table_node(), "a circle needs lat, lon and radius_nm");
      centre = geo::GeodeticPosition{lat, lon};
    });
    r.string("follow", v.follow);
    double follow_radius_nm = kNoValue;
    r.number("radius_nm", follow_radius_nm, 0.001, 4800.0);
    const int shapes = !polygon.empty() + circle + !v.follow.empty();
    if (shapes != 1)
      r.fail(r.table_node(), "a volume is one of polygon = [[lat, lon], ...], circle = { lat, lon, radius_nm } "
                             "or follow = \"ADDRESS or CALLSIGN\" with radius_nm");
    if (!holes.empty() && polygon.empty()) r.fail(r.node("holes"), "holes belong to a polygon");
    if (!std::isnan(follow_radius_nm) && v.follow.empty())
      r.fail(r.node("radius_nm"), "radius_nm (beside follow) is a followed circle's; a fixed circle is "
                                  "circle = { lat, lon, radius_nm }");

    VerticalBand band{kNoValue, kNoValue};
    r.number("floor_ft", band.floor_ft, -100000.0, 200000.0);
    r.number("ceiling_ft", band.ceiling_ft, -100000.0, 200000.0);
    if (std::isnan(band.floor_ft) || std::isnan(band.ceiling_ft))
      r.fail(r.table_node(), "a volume needs floor_ft and ceiling_ft");
    std::string reference = "msl", aerodrome;
    r.string("reference", reference);
    r.string("aerodrome", aerodrome);
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
    if (!v.follow.empty() && reference == "aerodrome")
      r.fail(r.node("reference"), "a followed volume's band is relative to the followed aircraft");

    if (!v.follow.empty()) {
      if (std::isnan(follow_radius_nm)) r.fail(r.node("follow"), "follow needs radius_nm");
      if (!(band.floor_ft < band.ceiling_ft)) r.fail(r.node("ceiling_ft"), "ceiling_ft must be above floor_ft");
      v.follow_radius_m = follow_radius_nm * units::kMetresPerNauticalMile;
      v.follow_band = band;
    } else {
      const volume::VolumeResult made =
          circle ? volume::Volume::circle({centre->lat_deg, centre->lon_deg}, radius_nm * units::kMetresPerNauticalMile, band)
                 : volume::Volume::polygon(ring_of(polygon), holes, band);
      if (!made.volume) {
        const char* key = circle ? "circle" : made.ring == 0 ? "polygon" : "holes";
        const std::string where = !circle && made.ring > 0 ? fmt::format(" (hole {})", made.ring) : "";
        r.fail(made.error == volume::VolumeError::BandInverted ? r.node("ceiling_ft") : r.node(key),
               fmt::format("the volume is refused: {}{}", volume::kVolumeErrorNames.name(made.error), where));
      }
      v.area = made.volume;
    }

    std::vector<std::string> active;
    r.text_list("active", active);
    std::string error;
    const auto schedule = volume::WeeklySchedule::parse(active, error);
    if (!schedule) r.fail(r.node("active"), "active: " + error);
    v.schedule = *schedule;
    r.word_list("callsigns", v.traffic.callsigns);
    r.word_list("addresses", v.traffic.addresses);
    r.mode3a_list("squawks", v.traffic.squawks);
    r.number("lookahead_s", v.lookahead_s, 1.0, volume::kMaxHorizon_s);
    r.number("warning_s", v.warning_s, 1.0, volume::kMaxHorizon_s);
    if (v.warning_s > v.lookahead_s)
      r.fail(r.node("warning_s"), fmt::format("warning_s = {} is beyond lookahead_s = {}", v.warning_s, v.lookahead_s));
    volumes.push_back(std::move(v));
  });
  return volumes;
}

}  // namespace kew::config
