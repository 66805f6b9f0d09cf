#include "kew/eligibility/eligibility.hpp"

#include <algorithm>
#include <cmath>
#include "kew/util/units.hpp"

namespace kew::eligibility {

namespace {
// Mode S and ASTERIX altitudes come in 25 ft steps: a rate derived from one step between
// two radar records (375 ft/min at 4 s) is quantisation, not a climb. One step in a
// second or two (750 ft/min and more, ADS-B) may well be a climb.
constexpr double kAltitudeQuantum_ft = 25.0;
constexpr double kQuantumRate_fpm = 400.0;
}

bool may_exclude_mode3a(std::uint16_t code) { return code != 07500 && code != 07600 && code != 07700; }

bool is_discrete_mode3a(std::uint16_t code) {
  // 1000: Mode S "conspicuity" (ICAO), 1200: VFR (North America), 2000: entering SSR
  // airspace without a code, 7000: VFR (ICAO Europe). Many aircraft share them.
  switch (code) {
    case 01000:
    case 01200:
    case 02000:
    case 07000:
      return false;
    default:
      return may_exclude_mode3a(code);
  }
}

Rules::Rules(const EligibilityConfig& config, const probe::SeparationMinima& minima)
    : config_(config),
      adjacent_level_ft_((minima.vertical_m - minima.altimetry_tolerance_m) / units::kMetresPerFoot),
      separation_ft_(minima.vertical_m / units::kMetresPerFoot),
      vertical_lookahead_s_(minima.vertical_lookahead_s) {
  // An emergency code must alert whatever the list says (the configuration refuses
  // them too; this keeps the rule true for programs that build the config themselves).
  std::erase_if(config_.excluded_mode3a, [](std::uint16_t c) { return !may_exclude_mode3a(c); });
}

double Rules::lower_limit_at(double lat_deg, double lon_deg, const Aerodrome** aerodrome) const {
  if (aerodrome) *aerodrome = nullptr;
  double limit = config_.lower_limit_ft;
  if (config_.aerodrome_height_ft <= 0.0 || !config_.aerodromes) return limit;
  const Aerodrome* near =
      config_.aerodromes->nearest(lat_deg, lon_deg, config_.aerodrome_radius_nm * units::kMetresPerNauticalMile);
  if (near && near->elevation_ft + config_.aerodrome_height_ft > limit) {
    limit = near->elevation_ft + config_.aerodrome_height_ft;
    if (aerodrome) *aerodrome = near;
  }
  return limit;
}

Exclusion Rules::exclusion(const track::Track& t, double now) const {
  if (t.alt_ft < config_.min_altitude_ft || t.alt_ft > config_.max_altitude_ft) return Exclusion::AltitudeBand;
  if (t.alt_ft < lower_limit_at(t.lat_deg, t.lon_deg)) return Exclusion::BelowLowerLimit;
  return area_exclusion(t, now);
}

Exclusion Rules::area_exclusion(const track::Track& t, double now) const {
  if (t.gs_kt < config_.min_ground_speed_kt) return Exclusion::Slow;
  if (t.mode3a && std::find(config_.excluded_mode3a.begin(), config_.excluded_mode3a.end(), *t.mode3a) !=
                      config_.excluded_mode3a.end())
    return Exclusion::ExcludedCode;
  if (config_.exclude_coasting && t.coasting) return Exclusion::Coasting;
  if (now - t.t > config_.max_position_age_s) return Exclusion::PositionStale;
  if (!t.address && t.records < static_cast<std::uint32_t>(config_.min_records)) return Exclusion::FirstRecords;
  return Exclusion::None;
}

bool Rules::same_address(const track::Track& a, const track::Track& b) const {
  return a.address && b.address && *a.address == *b.address;
}

namespace {
/// Positions within the configured distance and altitude, velocities alike.
bool coincide(const track::Track& a, const track::Track& b, double distance_m, const EligibilityConfig& c) {
  if (distance_m > c.same_code_distance_nm * units::kMetresPerNauticalMile || std::abs(a.alt_ft - b.alt_ft) > c.same_code_altitude_ft)
    return false;
  if (!a.has_velocity || !b.has_velocity) return false;
  if (std::abs(a.gs_kt - b.gs_kt) > Rules::kCoincidentSpeed_kt) return false;
  const double turn = std::abs(std::remainder(a.trk_deg - b.trk_deg, 360.0));
  return turn <= Rules::kCoincidentTrack_deg;
}
}  // namespace

bool Rules::one_aircraft_by_code(const track::Track& a, const track::Track& b, double distance_m) const {
  if (config_.same_code_distance_nm <= 0.0 || (a.address && b.address)) return false;
  if (!a.mode3a || !b.mode3a || *a.mode3a != *b.mode3a || !is_discrete_mode3a(*a.mode3a)) return false;
  return coincide(a, b, distance_m, config_);
}

std::optional<double> Rules::level_rate(const track::Track& t) const {
  // A first record without a vertical rate reads 0 ft/min: that is not "level".
  if (!t.vertical_rate_known) return std::nullopt;
  if (std::abs(t.vr_fpm) < config_.level_rate_fpm) return t.vr_fpm;
  if (t.vertical_rate_derived && t.altitude_step_ft <= kAltitudeQuantum_ft && std::abs(t.vr_fpm) <= kQuantumRate_fpm &&
      !t.altitude_moving_one_way)
    return 0.0;
  return std::nullopt;
}

bool Rules::level_pair(const track::Track& a, const track::Track& b) const {
  if (config_.level_rate_fpm <= 0.0) return false;
  const std::optional<double> rate_a = level_rate(a), rate_b = level_rate(b);
  if (!rate_a || !rate_b) return false;
  // "Level" tolerates a few hundred ft/min each: the pair must still be at adjacent levels
  // at the end of the vertical look-ahead, or two slow drifts towards each other could
  // cross levels unseen.
  const double dz_ft = b.alt_ft - a.alt_ft;
  const double later_ft = dz_ft + (*rate_b - *rate_a) / 60.0 * vertical_lookahead_s_;
  return std::abs(dz_ft) >= adjacent_level_ft_ && std::abs(later_ft) >= adjacent_level_ft_ &&
         (dz_ft > 0.0) == (later_ft > 0.0);
}

bool Rules::adjacent_level_off(const track::Track& a, const track::Track& b, double now) const {
  if (!config_.adjacent_level_off || config_.level_rate_fpm <= 0.0) return false;
  const auto levels_off_beside = [&](const track::Track& mover, const track::Track& level) {
    const std::optional<double> rate_level = level_rate(level);
    if (!rate_level || !mover.vertical_rate_known || level_rate(mover)) return false;
    // A selection, believed or not, is the mover's own word on where it stops: the
    // probe's intent model (design §4.4) has already judged it.
    if (mover.intent.sel_ft) return false;
    const double z_mover = mover.alt_ft + mover.vr_fpm / 60.0 * std::max(0.0, now - mover.t);
    const double z_level = level.alt_ft + *rate_level / 60.0 * std::max(0.0, now - level.t);
    const double towards = z_level > z_mover ? 1.0 : -1.0;  // the mover's way to the level one
    if (mover.vr_fpm * towards <= 0.0) return false;
    // Faster than ICAO's recommended rate near traffic at the adjacent level: not
    // behaving as an aircraft about to stop next to it.
    if (std::abs(mover.vr_fpm) > kLevelOffMaxRate_fpm) return false;
    // Below it much traffic flies under visual rules, climbing without a clearance to a
    // level beside anyone.
    if (level.alt_ft < config_.adjacent_level_off_above_ft) return false;
    const double stop_ft = track::stopping_distance_ft(mover.vr_fpm, track::kCaptureDeceleration_g);
    // Where the mover can stop, and where the level one is after T_v.
    const double gap_stopped_ft = (z_level - z_mover) * towards - stop_ft;
    const double gap_later_ft = gap_stopped_ft + *rate_level / 60.0 * vertical_lookahead_s_ * towards;
    return gap_stopped_ft >= separation_ft_ && gap_later_ft >= adjacent_level_ft_;
  };
  return levels_off_beside(a, b) || levels_off_beside(b, a);
}

PairVerdict Rules::verdict(const track::Track& a, const track::Track& b, const PairContext& context) const {
  PairVerdict v;
  if (same_address(a, b)) {
    v.rule = PairRule::SameAddress;
  } else if (level_pair(a, b)) {
    v.rule = PairRule::LevelPair;
  } else if (context.alert_open) {
    return v;
  } else if (adjacent_level_off(a, b, context.now)) {
    v.rule = PairRule::AdjacentLevelOff;
  } else if (context.inhibited) {
    v.rule = PairRule::Inhibited;
  } else if (one_aircraft_by_code(a, b, context.distance_m)) {
    v.rule = PairRule::SameCode;
  } else {
    v.exclusion = exclusion(a, context.now);
    if (v.exclusion == Exclusion::None) {
      v.exclusion = exclusion(b, context.now);
      v.second_excluded = true;
    }
    if (v.exclusion != Exclusion::None) v.rule = PairRule::Excluded;
  }
  return v;
}

}  // namespace kew::eligibility
