#pragma once
// Conversion of CAT048 polar plots (slant range, azimuth) to WGS84 latitude/longitude.
//
// Method (protocol/docs/asterix.md, "CAT048 polar conversion"): the radar measures the
// slant range ρ along the line of sight. With the antenna at height h_r and the target at
// height h_t (from its flight level) on a sphere of radius R (the Gaussian radius of
// curvature of the WGS84 ellipsoid at the site), the Earth-centre angle γ between them
// follows from the triangle (R + h_r, R + h_t, ρ):
//     cos γ = ((R + h_r)² + (R + h_t)² − ρ²) / (2 (R + h_r)(R + h_t)),
// and the ground range is s = R·γ. The target is then placed with
// GeographicLib::Geodesic::Direct from the site along the measured azimuth over s.
// Refraction is ignored (straight line of sight).

#include <cstdint>
#include <span>
#include <vector>

#include "kew/protocol/asterix/asterix_decoder.hpp"

namespace kew::protocol::asterix {

/// Ground range, metres, for slant range `slant_range_m` (>= 0) between an antenna at
/// `radar_height_m` and a target at `target_height_m` (metres above the sphere) on a sphere
/// of radius `earth_radius_m`. When the heights are inconsistent with the range (ρ shorter
/// than the height difference), the target is taken to be overhead: 0.
double ground_range_m(double slant_range_m, double radar_height_m, double target_height_m,
                      double earth_radius_m);

/// Gaussian mean radius of curvature √(M·N) of the WGS84 ellipsoid at `lat_deg`, metres.
double gaussian_radius_m(double lat_deg);

struct GeodeticPoint {
  double lat_deg = 0;
  double lon_deg = 0;
};

class RadarProjector {
 public:
  explicit RadarProjector(std::span<const RadarSite> sites);

  /// Index of the site of radar SAC/SIC, or -1 when it is not configured.
  int find(std::uint8_t sac, std::uint8_t sic) const;

  /// Position of a target seen by site `site` (an index from find()) at slant range
  /// `slant_range_m` (metres) and azimuth `azimuth_deg` (degrees clockwise from true
  /// north), at `target_height_m` metres above mean sea level.
  GeodeticPoint project(int site, double slant_range_m, double azimuth_deg,
                        double target_height_m) const;

 private:
  struct Site {
    RadarSite site;
    double earth_radius_m;
  };
  std::vector<Site> sites_;
};

}  // namespace kew::protocol::asterix
