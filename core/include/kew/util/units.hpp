#pragma once
// The unit conversions kew uses, each defined once. Aviation units are exact by
// definition: 1 ft = 0.3048 m and 1 NM = 1,852 m (International Yard and Pound
// Agreement, 1959; ICAO Annex 5, Table 3-3).

namespace kew::units {

inline constexpr double kMetresPerFoot = 0.3048;
inline constexpr double kMetresPerNauticalMile = 1852.0;
inline constexpr double kSecondsPerMinute = 60.0;
inline constexpr double kSecondsPerHour = 3600.0;
inline constexpr double kFeetPerFlightLevel = 100.0;
/// 1 kt = 1 NM/h in m/s.
inline constexpr double kMpsPerKnot = kMetresPerNauticalMile / kSecondsPerHour;
/// 1 m/s in kt.
inline constexpr double kKnotsPerMps = kSecondsPerHour / kMetresPerNauticalMile;
/// 1 ft/min in m/s.
inline constexpr double kMpsPerFpm = kMetresPerFoot / kSecondsPerMinute;

}  // namespace kew::units
