#include "kew/protocol/asterix/radar_projection.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kew::protocol::asterix {

double ground_range_m(double slant_range_m, double radar_height_m, double target_height_m,
                      double earth_radius_m) {
  const double a = earth_radius_m + radar_height_m;
  const double b = earth_radius_m + target_height_m;
  const double cos_gamma = (a * a + b * b - slant_range_m * slant_range_m) / (2.0 * a * b);
  // Below |h_t - h_r| the triangle does not close (Mode C error, or a target right above
  // the antenna): clamp rather than produce NaN.
  return earth_radius_m * std::acos(std::clamp(cos_gamma, -1.0, 1.0));
}

double gaussian_radius_m(double lat_deg) {
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  const double a = wgs84.EquatorialRadius();
  const double f = wgs84.Flattening();
  const double e2 = f * (2.0 - f);
  const double s = std::sin(lat_deg * std::numbers::pi / 180.0);
  const double w = 1.0 - e2 * s * s;
  const double meridional = a * (1.0 - e2) / (w * std::sqrt(w));
  const double normal = a / std::sqrt(w);
  return std::sqrt(meridional * normal);
}

RadarProjector::RadarProjector(std::span<const RadarSite> sites) {
  sites_.reserve(sites.size());
  for (const RadarSite& site : sites) sites_.push_back({site, gaussian_radius_m(site.lat_deg)});
}

int RadarProjector::find(std::uint8_t sac, std::uint8_t sic) const {
  for (std::size_t i = 0; i < sites_.size(); ++i) {
    if (sites_[i].site.sac == sac && sites_[i].site.sic == sic) return static_cast<int>(i);
  }
  return -1;
}

GeodeticPoint RadarProjector::project(int site, double slant_range_m, double azimuth_deg,
                                      double target_height_m) const {
  const Site& s = sites_[static_cast<std::size_t>(site)];
  const double ground =
      ground_range_m(slant_range_m, s.site.height_m, target_height_m, s.earth_radius_m);
  GeodeticPoint point;
  GeographicLib::Geodesic::WGS84().Direct(s.site.lat_deg, s.site.lon_deg, azimuth_deg, ground,
                                          point.lat_deg, point.lon_deg);
  return point;
}

}  // namespace kew::protocol::asterix
