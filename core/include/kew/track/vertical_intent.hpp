#pragma once
// Vertical intent (design §4.4): when may the prediction stop a climb or descent at the
// aircraft's selected altitude? kew has no cleared level, so the selection must never
// hide a level bust: it is believed only while the aircraft behaves as one that will
// level off there.

#include <optional>

#include "kew/track/track_report.hpp"

namespace kew::track {

/// The gentle vertical deceleration of a capture (g): what the intent model and the
/// adjacent level-off (design §4.4, §4.5) assume an aircraft levels off with.
inline constexpr double kCaptureDeceleration_g = 0.05;

/// The height (ft, ≥ 0) an aircraft at vertical rate `vr_fpm` (ft/min, either sign)
/// needs to stop at `deceleration_g` (> 0): w²/2a.
double stopping_distance_ft(double vr_fpm, double deceleration_g);

struct IntentConfig {
  /// Use selected altitudes at all (false: every vertical prediction is linear).
  bool enabled = true;
  /// A selection older than this (s, data time) is forgotten: it may have changed since.
  double max_age_s = 20.0;
  /// More than this past the selection (ft), the aircraft is busting it: linear until
  /// the selection changes.
  double bust_ft = 200.0;
  /// Within this of the selection (ft) the aircraft must be seen to capture it ...
  double capture_band_ft = 1000.0;
  /// ... by the distance it needs to stop at this vertical deceleration (g): closer
  /// than that with its rate not yet falling, it is not levelling off.
  double capture_deceleration_g = kCaptureDeceleration_g;
  /// "Falling": |rate| below this fraction of the |rate| it had on entering the band
  /// (one 64 ft/min ADS-B step is noise at 1,000 ft/min and more).
  double fallen_fraction = 0.9;
};

/// What a track remembers of its selected altitude between records.
struct IntentState {
  std::optional<double> sel_ft;  ///< the last selection reported (ft)
  SelectedAltitudeSource sel_src = SelectedAltitudeSource::Mcp;
  double sel_t = 0.0;  ///< data time of the record that last reported it (UTC s)
  /// +1 / −1: the selection was above / below the aircraft when first seen (0: not yet
  /// decided, the aircraft was at it).
  int approach_sign = 0;
  bool busted = false;  ///< went more than bust_ft past this selection
  /// |vertical rate| (ft/min) on entering the capture band, while inside it.
  std::optional<double> band_entry_rate_fpm;
};

/// Folds one accepted record into `state` (its selection, if any, and the track's
/// altitude and vertical rate at data time t) and returns the altitude (ft) at which
/// the vertical prediction levels off, or nothing: the prediction is linear. It levels
/// off only when all hold: a selection reported within max_age_s; the aircraft climbing
/// or descending towards it; never more than bust_ft past it since it was selected;
/// and, within capture_band_ft of it, either its rate has begun to fall or it is still
/// farther than it needs to stop at capture_deceleration_g.
std::optional<double> update_intent(IntentState& state, const IntentConfig& config, double t,
                                    const std::optional<double>& sel_ft, SelectedAltitudeSource sel_src,
                                    double alt_ft, double vr_fpm);

}  // namespace kew::track
