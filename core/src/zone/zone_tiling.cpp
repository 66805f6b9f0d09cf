#include "kew/zone/zone_tiling.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <GeographicLib/Constants.hpp>
#include <fmt/format.h>

namespace kew::zone {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
// The smallest radius of curvature of WGS84, the meridian's at the equator, a(1 − e²).
// On the ellipsoid ds² = M²dφ² + N²cos²φ dλ² ≥ M_min²(dφ² + cos²φ dλ²), so a geodesic of
// length s spans at most s / M_min radians on the sphere of (φ, λ): distances bounded
// there are bounded on the ellipsoid.
const double kSmallestRadius_m =
    GeographicLib::Constants::WGS84_a() * (1.0 - GeographicLib::Constants::WGS84_f()) *
    (1.0 - GeographicLib::Constants::WGS84_f());
constexpr double kMarginWidening = 1.02;
// Extents are widened by this much beyond core and margin (metres), so that rounding
// in the corner geodesics never refuses a member.
constexpr double kExtentSlack_m = 10e3;
constexpr double kMaxMargin_m = 1.0e6;

double wrap_longitude(double lon) { return lon >= 180.0 ? lon - 360.0 : lon; }
}  // namespace

double ZoneTiling::band_south_deg(std::uint32_t band) {
  if (band == 0) return -90.0;
  if (band == kBands - 1) return kCapLatitude_deg;
  return -kCapLatitude_deg + kBandHeight_deg * static_cast<double>(band - 1);
}

ZoneTiling::ZoneTiling(double margin_m) : margin_m_(margin_m) {
  if (!(margin_m > 0.0) || margin_m > kMaxMargin_m)
    throw std::invalid_argument("zone margin must be in (0, 1000 km]");
  margin_rad_ = margin_m * kMarginWidening / kSmallestRadius_m;
  const double equator_m = 2.0 * kPi * GeographicLib::Constants::WGS84_a();
  for (std::uint32_t band = 0; band < kBands; ++band) {
    if (band == 0 || band == kBands - 1) {
      cells_[band] = 1;
      continue;
    }
    const double middle = band_south_deg(band) + 0.5 * kBandHeight_deg;
    const double around_m = equator_m * std::cos(middle * kDegToRad);
    cells_[band] = static_cast<std::uint32_t>(std::clamp(std::ceil(around_m / kCoreWidth_m), 1.0, double{kCellsMax}));
  }
}

bool ZoneTiling::valid(ZoneKey key) const {
  const std::uint32_t band = key / kCellsMax;
  return band < kBands && key % kCellsMax < cells_[band];
}

ZoneKey ZoneTiling::home(geo::GeodeticPosition p) const {
  std::uint32_t band = 0;
  if (p.lat_deg >= kCapLatitude_deg) {
    band = kBands - 1;
  } else if (p.lat_deg >= -kCapLatitude_deg) {
    const double b = std::floor((p.lat_deg + kCapLatitude_deg) / kBandHeight_deg);
    band = 1 + static_cast<std::uint32_t>(std::clamp(b, 0.0, double{kBands - 3}));
  }
  const std::uint32_t n = cells_[band];
  const double width = 360.0 / n;
  const double cell = std::floor((wrap_longitude(p.lon_deg) + 180.0) / width);
  return band * kCellsMax + static_cast<std::uint32_t>(std::clamp(cell, 0.0, double(n - 1)));
}

void ZoneTiling::zones_near(geo::GeodeticPosition p, ZoneKeys& out) const {
  out.clear();
  const double r_deg = margin_rad_ / kDegToRad;
  const std::uint32_t south = home({std::max(-90.0, p.lat_deg - r_deg), p.lon_deg}) / kCellsMax;
  const std::uint32_t north = home({std::min(90.0, p.lat_deg + r_deg), p.lon_deg}) / kCellsMax;
  // The widest longitude spread of the spherical cap of radius r around p; a cap that
  // holds a pole spans every longitude.
  double spread_deg = 180.0;
  if (std::abs(p.lat_deg) + r_deg < 90.0)
    spread_deg = std::asin(std::min(1.0, std::sin(margin_rad_) / std::cos(p.lat_deg * kDegToRad))) / kDegToRad;
  const double lon = wrap_longitude(p.lon_deg);
  for (std::uint32_t band = south; band <= north; ++band) {
    const std::uint32_t n = cells_[band];
    const double width = 360.0 / n;
    const auto first = static_cast<long>(std::floor((lon - spread_deg + 180.0) / width));
    const auto last = static_cast<long>(std::floor((lon + spread_deg + 180.0) / width));
    if (spread_deg >= 180.0 || last - first + 1 >= static_cast<long>(n)) {
      for (std::uint32_t cell = 0; cell < n; ++cell) out.push_back(band * kCellsMax + cell);
      continue;
    }
    for (long cell = first; cell <= last; ++cell) {
      const long wrapped = ((cell % static_cast<long>(n)) + static_cast<long>(n)) % static_cast<long>(n);
      out.push_back(band * kCellsMax + static_cast<ZoneKey>(wrapped));
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

geo::GeodeticPosition ZoneTiling::centre(ZoneKey key) const {
  const std::uint32_t band = key / kCellsMax;
  if (band == 0) return {-90.0, 0.0};
  if (band == kBands - 1) return {90.0, 0.0};
  const double width = 360.0 / cells_[band];
  return {band_south_deg(band) + 0.5 * kBandHeight_deg, -180.0 + width * (key % kCellsMax + 0.5)};
}

ZoneTiling::Core ZoneTiling::core(ZoneKey key) const {
  const std::uint32_t band = key / kCellsMax;
  if (band == 0) return {-90.0, -kCapLatitude_deg, -180.0, 180.0};
  if (band == kBands - 1) return {kCapLatitude_deg, 90.0, -180.0, 180.0};
  const double width = 360.0 / cells_[band];
  const double west = -180.0 + width * (key % kCellsMax);
  return {band_south_deg(band), band_south_deg(band) + kBandHeight_deg, west, west + width};
}

double ZoneTiling::extent_m(ZoneKey key) const {
  const std::uint32_t band = key / kCellsMax;
  const geo::GeodeticPosition c = centre(key);
  double farthest = 0.0;
  if (band == 0 || band == kBands - 1) {
    farthest = geo::Projection::geodesic_distance_m(c, {band == 0 ? -kCapLatitude_deg : kCapLatitude_deg, 0.0});
  } else {
    const double half_width = 180.0 / cells_[band];
    const double half_height = 0.5 * kBandHeight_deg;
    for (const double dlat : {-half_height, 0.0, half_height})
      for (const double dlon : {-half_width, 0.0, half_width})
        farthest = std::max(farthest, geo::Projection::geodesic_distance_m(c, {c.lat_deg + dlat, c.lon_deg + dlon}));
  }
  // zones_near() takes the zones that meet the latitude–longitude box around a cap of
  // angle margin_rad_: a member lies within √2 such angles of the core, an angle being
  // at most the largest radius of curvature (the polar one, a/√(1 − e²)) long.
  const double f = GeographicLib::Constants::WGS84_f();
  const double largest_radius_m = GeographicLib::Constants::WGS84_a() / (1.0 - f);
  return farthest + std::sqrt(2.0) * margin_rad_ * largest_radius_m + kExtentSlack_m;
}

std::string ZoneTiling::name(ZoneKey key) const {
  const std::uint32_t band = key / kCellsMax;
  if (band == 0) return "S90";
  if (band == kBands - 1) return "N90";
  const geo::GeodeticPosition c = centre(key);
  return fmt::format("{}{:04.1f}{}{:05.1f}", c.lat_deg < 0 ? 'S' : 'N', std::abs(c.lat_deg), c.lon_deg < 0 ? 'W' : 'E',
                     std::abs(c.lon_deg));
}

geo::GeodeticPosition ZoneTiling::midpoint(geo::GeodeticPosition a, geo::GeodeticPosition b) {
  const auto unit = [](geo::GeodeticPosition p, double v[3]) {
    const double lat = p.lat_deg * kDegToRad, lon = p.lon_deg * kDegToRad;
    v[0] = std::cos(lat) * std::cos(lon);
    v[1] = std::cos(lat) * std::sin(lon);
    v[2] = std::sin(lat);
  };
  double u[3], w[3];
  unit(a, u);
  unit(b, w);
  const double x = u[0] + w[0], y = u[1] + w[1], z = u[2] + w[2];
  const double norm = std::sqrt(x * x + y * y + z * z);
  if (!(norm > 1e-9)) return a;
  return {std::asin(std::clamp(z / norm, -1.0, 1.0)) / kDegToRad, std::atan2(y, x) / kDegToRad};
}

}  // namespace kew::zone
