// The volume index (design §4.11) never hides a volume a path can enter: for random
// volumes over the whole earth (the antimeridian and both poles included) and random
// paths, every volume entry() finds an entry in is among the index's candidates, and the
// candidates are exactly those whose boxes a linear scan finds meeting the path's.
#include <gtest/gtest.h>

#include <random>

#include "kew/volume/entry.hpp"
#include "kew/volume/volume_index.hpp"

namespace kew::volume {
namespace {

bool boxes_meet(const std::vector<DegreeBox>& a, const std::vector<DegreeBox>& b) {
  for (const DegreeBox& x : a)
    for (const DegreeBox& y : b)
      if (x.west_deg <= y.east_deg && y.west_deg <= x.east_deg && x.south_deg <= y.north_deg &&
          y.south_deg <= x.north_deg)
        return true;
  return false;
}

/// A position near a pole or the antimeridian a third of the time each.
LatLon random_place(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double pick = unit(rng);
  if (pick < 0.33) return {(unit(rng) < 0.5 ? -1 : 1) * (87.0 + 3.0 * unit(rng)), -180.0 + 360.0 * unit(rng)};
  if (pick < 0.66) return {-60.0 + 120.0 * unit(rng), (unit(rng) < 0.5 ? -1 : 1) * (178.0 + 2.0 * unit(rng))};
  return {-80.0 + 160.0 * unit(rng), -180.0 + 360.0 * unit(rng)};
}

TEST(VolumeIndexProperty, CandidatesHoldEveryVolumeAPathCanEnter) {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Volume> areas;
  while (areas.size() < 3000) {
    const LatLon c = random_place(rng);
    const double radius_m = 500.0 + 60000.0 * unit(rng);
    const VerticalBand band{0.0, 60000.0};
    if (unit(rng) < 0.5) {
      if (auto made = Volume::circle(c, radius_m, band); made.volume) areas.push_back(*made.volume);
    } else {
      // A square of vertices on the circle: its extent is the circle's.
      Ring ring;
      const double dlat = radius_m / 111320.0;
      for (const auto& [a, b] : {std::pair{1, 1}, {1, -1}, {-1, -1}, {-1, 1}}) {
        const double lat = std::clamp(c.lat_deg + a * dlat * 0.7, -89.9, 89.9);
        double lon = c.lon_deg + b * dlat * 0.7 / std::max(0.02, std::cos(lat * M_PI / 180.0));
        lon = std::remainder(lon, 360.0);
        ring.push_back({lat, lon});
      }
      if (auto made = Volume::polygon(ring, {}, band); made.volume) areas.push_back(*made.volume);
    }
  }
  const VolumeIndex index(areas);
  std::vector<std::vector<DegreeBox>> area_boxes;
  for (const Volume& v : areas) area_boxes.push_back(disk_boxes(v.centre(), v.extent_m()));
  std::size_t entries = 0, paths = 0;
  for (int i = 0; i < 3000; ++i) {
    Motion m;
    // Half the paths start beside a volume, so that entries are common.
    m.start = unit(rng) < 0.5 ? areas[rng() % areas.size()].centre() : random_place(rng);
    if (unit(rng) < 0.5) m.start.lat_deg = std::clamp(m.start.lat_deg + (unit(rng) - 0.5), -90.0, 90.0);
    m.alt_ft = 10000.0;
    m.track_deg = 360.0 * unit(rng);
    m.gs_kt = 600.0 * unit(rng);
    const double horizon_s = 600.0 * unit(rng);
    const std::vector<std::uint32_t> found = index.candidates(m, horizon_s);
    const std::vector<DegreeBox> path = disk_boxes(m.start, ground_speed_mps(m) * horizon_s);
    std::vector<std::uint32_t> scanned;
    for (std::uint32_t k = 0; k < areas.size(); ++k)
      if (boxes_meet(path, area_boxes[k])) scanned.push_back(k);
    ASSERT_EQ(found, scanned) << "path " << i;
    // Every volume the path enters is a candidate (checked on a sample of the rest).
    for (std::uint32_t k = 0; k < areas.size(); k += (std::binary_search(found.begin(), found.end(), k) ? 1 : 7)) {
      const Entry e = entry(areas[k], m, horizon_s);
      if (!e.entry_s) continue;
      ++entries;
      ASSERT_TRUE(std::binary_search(found.begin(), found.end(), k)) << "path " << i << " enters volume " << k;
    }
    ++paths;
  }
  EXPECT_GT(entries, 300u) << "too few entries to test";
  std::printf("volume index: %zu paths, %zu entries, every one a candidate\n", paths, entries);
}

TEST(VolumeIndexProperty, DiskBoxesHoldTheDisk) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const LatLon c = random_place(rng);
    const double radius_m = 200000.0 * unit(rng);
    Motion m;
    m.start = c;
    m.track_deg = 360.0 * unit(rng);
    m.gs_kt = 1.0;
    const LatLon p = position_at(m, radius_m / ground_speed_mps(m) * unit(rng));
    bool inside = false;
    for (const DegreeBox& b : disk_boxes(c, radius_m))
      inside = inside || (p.lat_deg >= b.south_deg && p.lat_deg <= b.north_deg && p.lon_deg >= b.west_deg &&
                          p.lon_deg <= b.east_deg);
    ASSERT_TRUE(inside) << c.lat_deg << "," << c.lon_deg << " r " << radius_m << " point " << p.lat_deg << ","
                        << p.lon_deg;
  }
}

}  // namespace
}  // namespace kew::volume
