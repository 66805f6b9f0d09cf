#pragma once
// Units and the ranges of the separation and alert parameters, shared by [probe] and
// [alerts] and by every region that sets them (design §4.8): a region's horizontal_nm
// accepts exactly what [probe] horizontal_nm does. Internal to kew_config.

#include <cstdint>
#include "kew/util/units.hpp"

namespace kew::config::ranges {

inline constexpr double kNauticalMile = units::kMetresPerNauticalMile;  ///< m
inline constexpr double kFoot = units::kMetresPerFoot;                  ///< m

struct Range {
  double lo, hi;
};
inline constexpr Range kHorizontalNm{0.1, 100.0};
inline constexpr Range kVerticalFt{1.0, 100000.0};
inline constexpr Range kLookaheadS{0.0, 3600.0};
inline constexpr Range kWarningS{0.0, 3600.0};
/// confirm and clear: evaluations.
inline constexpr std::int64_t kEvaluationsMin = 1;
inline constexpr std::int64_t kEvaluationsMax = 1000;

}  // namespace kew::config::ranges
