#include "kew/volume/volume_index.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

namespace kew::volume {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {

using Point = bg::model::point<double, 2, bg::cs::cartesian>;  // (lon, lat) in degrees
using Box = bg::model::box<Point>;
using Indexed = std::pair<Box, std::uint32_t>;

/// The shortest length of a degree of latitude on WGS84 (m), at the equator: dividing a
/// distance by it overestimates the latitudes it spans.
constexpr double kShortestDegreeOfLatitude_m = 110574.0;
/// A disk coming this close to a pole (degrees) spans every longitude.
constexpr double kPolarCap_deg = 1.0;

Box box_of(const DegreeBox& b) { return {{b.west_deg, b.south_deg}, {b.east_deg, b.north_deg}}; }

}  // namespace

std::vector<DegreeBox> disk_boxes(LatLon centre, double radius_m) {
  // 1 % and a metre more than the spherical bound, for the ellipsoid's flattening.
  const double dlat = (radius_m * 1.01 + 1.0) / kShortestDegreeOfLatitude_m;
  const double south = centre.lat_deg - dlat, north = centre.lat_deg + dlat;
  if (north >= 90.0 - kPolarCap_deg || south <= -90.0 + kPolarCap_deg)
    return {{std::max(south, -90.0), -180.0, std::min(north, 90.0), 180.0}};
  // A small circle of angular radius a about latitude φ spans asin(sin a / cos φ) of
  // longitude, no more than a / cos of the disk's latitude farthest from the equator.
  const double widest = std::max(std::abs(south), std::abs(north)) * std::numbers::pi / 180.0;
  const double dlon = dlat / std::cos(widest);
  if (dlon >= 180.0) return {{south, -180.0, north, 180.0}};
  const double west = centre.lon_deg - dlon, east = centre.lon_deg + dlon;
  if (west < -180.0) return {{south, west + 360.0, north, 180.0}, {south, -180.0, north, east}};
  if (east > 180.0) return {{south, west, north, 180.0}, {south, -180.0, north, east - 360.0}};
  return {{south, west, north, east}};
}

struct VolumeIndex::Tree {
  bgi::rtree<Indexed, bgi::quadratic<16>> rtree;
};

VolumeIndex::VolumeIndex(const std::vector<Volume>& areas) : tree_(std::make_unique<Tree>()), size_(areas.size()) {
  std::vector<Indexed> entries;
  for (std::uint32_t i = 0; i < areas.size(); ++i)
    for (const DegreeBox& b : disk_boxes(areas[i].centre(), areas[i].extent_m())) entries.emplace_back(box_of(b), i);
  // Bulk loading (packing) gives a better tree than inserting one by one.
  tree_->rtree = bgi::rtree<Indexed, bgi::quadratic<16>>(entries.begin(), entries.end());
}

VolumeIndex::~VolumeIndex() = default;
VolumeIndex::VolumeIndex(VolumeIndex&&) noexcept = default;
VolumeIndex& VolumeIndex::operator=(VolumeIndex&&) noexcept = default;

std::vector<std::uint32_t> VolumeIndex::near(LatLon centre, double radius_m) const {
  std::vector<std::uint32_t> found;
  for (const DegreeBox& b : disk_boxes(centre, radius_m))
    for (auto it = tree_->rtree.qbegin(bgi::intersects(box_of(b))); it != tree_->rtree.qend(); ++it)
      found.push_back(it->second);
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

std::vector<std::uint32_t> VolumeIndex::candidates(const Motion& motion, double horizon_s) const {
  // Every point of the path lies within its length of the start.
  return near(motion.start, ground_speed_mps(motion) * std::max(0.0, horizon_s));
}

}  // namespace kew::volume
