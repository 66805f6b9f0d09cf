#include "kew/track/vertical_intent.hpp"

#include <cmath>
#include "kew/util/units.hpp"

namespace kew::track {

namespace {
constexpr double kStandardGravity = 9.80665;  // m/s²
}  // namespace

double stopping_distance_ft(double vr_fpm, double deceleration_g) {
  const double rate_mps = vr_fpm * units::kMpsPerFpm;
  return rate_mps * rate_mps / (2.0 * deceleration_g * kStandardGravity) / units::kMetresPerFoot;
}

std::optional<double> update_intent(IntentState& state, const IntentConfig& config, double t,
                                    const std::optional<double>& sel_ft, SelectedAltitudeSource sel_src,
                                    double alt_ft, double vr_fpm) {
  if (sel_ft) {
    if (state.sel_ft != sel_ft) {  // a new selection: judged afresh
      state = IntentState{};
      state.sel_ft = sel_ft;
    }
    state.sel_src = sel_src;
    state.sel_t = t;
  }
  if (!config.enabled || !state.sel_ft || t - state.sel_t > config.max_age_s) return std::nullopt;
  const double to_go_ft = *state.sel_ft - alt_ft;
  if (state.approach_sign == 0 && to_go_ft != 0.0) state.approach_sign = to_go_ft > 0.0 ? 1 : -1;
  if (state.approach_sign != 0 && to_go_ft * state.approach_sign < -config.bust_ft) state.busted = true;
  if (state.busted) return std::nullopt;
  if (!(to_go_ft * vr_fpm > 0.0)) {  // level, or moving away from the selection
    state.band_entry_rate_fpm.reset();
    return std::nullopt;
  }
  const double distance_ft = std::abs(to_go_ft);
  const double rate_fpm = std::abs(vr_fpm);
  if (distance_ft > config.capture_band_ft) {
    state.band_entry_rate_fpm.reset();
    return state.sel_ft;
  }
  if (!state.band_entry_rate_fpm) state.band_entry_rate_fpm = rate_fpm;
  const bool falling = rate_fpm < config.fallen_fraction * *state.band_entry_rate_fpm;
  if (!falling && distance_ft < stopping_distance_ft(rate_fpm, config.capture_deceleration_g)) return std::nullopt;
  return state.sel_ft;
}

}  // namespace kew::track
