#include "kew/eligibility/aerodromes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "kew/geo/projection.hpp"

namespace kew::eligibility {

namespace {
constexpr double kMetresPerDegree = 111000.0;  // below the meridian's 111,694 m at the poles
int lat_cell_of(double lat) { return std::clamp(static_cast<int>(std::floor(lat)), -90, 89); }
int lon_cell_of(double lon) { return std::clamp(static_cast<int>(std::floor(lon)), -180, 179); }

// "" when lo ≤ value ≤ hi (NaN is outside).
std::string outside(std::string_view name, double value, double lo, double hi) {
  if (value >= lo && value <= hi) return {};
  return fmt::format("{} = {} is outside [{}, {}]", name, value, lo, hi);
}
}  // namespace

std::string problem(const Aerodrome& a) {
  if (a.ident.empty()) return "the ident is empty";
  for (const std::string& p : {outside("lat_deg", a.lat_deg, -90.0, 90.0), outside("lon_deg", a.lon_deg, -180.0, 180.0),
                        outside("elevation_ft", a.elevation_ft, kMinElevation_ft, kMaxElevation_ft)})
    if (!p.empty()) return p;
  return {};
}

AerodromeTable::AerodromeTable(std::vector<Aerodrome> aerodromes) : aerodromes_(std::move(aerodromes)) {
  for (std::uint32_t i = 0; i < aerodromes_.size(); ++i) {
    const Aerodrome& a = aerodromes_[i];
    if (const std::string p = problem(a); !p.empty())
      throw std::invalid_argument(fmt::format("aerodrome {} (row {}): {}", a.ident, i + 1, p));
    if (!by_ident_.emplace(a.ident, i).second)
      throw std::invalid_argument(fmt::format("aerodrome {} is in the table twice", a.ident));
    cells_[cell(lat_cell_of(a.lat_deg), lon_cell_of(a.lon_deg))].push_back(i);
  }
}

const Aerodrome* AerodromeTable::find(std::string_view ident) const {
  const auto it = by_ident_.find(std::string(ident));
  return it == by_ident_.end() ? nullptr : &aerodromes_[it->second];
}

const Aerodrome* AerodromeTable::nearest(double lat_deg, double lon_deg, double radius_m) const {
  const double dlat = radius_m / kMetresPerDegree;
  const double cos_lat = std::cos(std::min(89.0, std::abs(lat_deg) + dlat) * M_PI / 180.0);
  // Near a pole the circle may hold every meridian.
  const double dlon = std::abs(lat_deg) + dlat >= 89.0 ? 180.0 : std::min(180.0, dlat / cos_lat);
  const Aerodrome* best = nullptr;
  double best_m = radius_m;
  std::uint32_t best_index = 0;
  for (int la = lat_cell_of(lat_deg - dlat); la <= lat_cell_of(lat_deg + dlat); ++la) {
    const int lon_cells = dlon >= 180.0 ? 360 : 2 * static_cast<int>(std::ceil(dlon)) + 1;
    const int first = lon_cell_of(lon_deg) - lon_cells / 2;
    for (int k = 0; k < std::min(lon_cells, 360); ++k) {
      int lo = first + k;
      lo = (lo + 180 + 360) % 360 - 180;  // across the antimeridian
      const auto it = cells_.find(cell(la, lo));
      if (it == cells_.end()) continue;
      for (const std::uint32_t i : it->second) {
        const Aerodrome& a = aerodromes_[i];
        // Most are farther than the radius by far: a flat estimate (within 1 % this close)
        // spares them the geodesic.
        const double north = (a.lat_deg - lat_deg) * kMetresPerDegree;
        const double east = std::remainder(a.lon_deg - lon_deg, 360.0) * kMetresPerDegree *
                            std::cos(0.5 * (a.lat_deg + lat_deg) * M_PI / 180.0);
        if (std::abs(lat_deg) < 80.0 && north * north + east * east > 1.1 * 1.1 * best_m * best_m) continue;
        const double d = geo::Projection::geodesic_distance_m({lat_deg, lon_deg}, {a.lat_deg, a.lon_deg});
        if (d < best_m || (d == best_m && best && i < best_index)) {
          best = &a;
          best_m = d;
          best_index = i;
        }
      }
    }
  }
  return best;
}

}  // namespace kew::eligibility
