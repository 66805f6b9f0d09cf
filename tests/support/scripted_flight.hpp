#pragma once
// Scripted aircraft for pipeline tests: straight or turning flights around (50° N, 8° E)
// reporting every 4 s, and a run of the pipeline over them.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "kew/pipeline/pipeline.hpp"

namespace kew::test_support {

inline constexpr double kT0 = 1714400000.0;
inline constexpr double kKnot = 1852.0 / 3600.0;  // m/s

/// One aircraft's records: at t = kT0 it is `east_m` east and `north_m` north of
/// (lat0_deg, lon0_deg), by default (50° N, 8° E), flying `trk_deg` at `gs_kt`; for the first `turn_s` seconds it turns at
/// `turn_dps` (deg/s, positive right), then flies straight on.
struct Flight {
  std::string id;
  std::string source = "test";
  double lat0_deg = 50.0;  ///< the origin that east_m and north_m are counted from
  double lon0_deg = 8.0;
  double east_m = 0.0;
  double north_m = 0.0;
  double alt_ft = 35000.0;
  double gs_kt = 450.0;
  double trk_deg = 90.0;
  double vr_fpm = 0.0;
  double turn_dps = 0.0;
  double turn_s = 0.0;
  std::function<void(TrackReport&)> edit = {};  // applied to every record

  TrackReport at(double t) const;
};

struct Outcome {
  std::unique_ptr<Pipeline> pipeline;
  std::vector<AlertEvent> events;
  std::size_t opened() const;
  /// Data time of the first New event, or a negative number when none opened.
  double first_opened_t() const;
};

/// Two aircraft "A" and "B" head-on 20 NM apart at 450 kt each (A eastbound), at the
/// given altitudes (ft): at one level they lose separation 60 s after kT0.
std::vector<Flight> head_on(double alt_a_ft = 35000.0, double alt_b_ft = 35000.0);

/// Every flight reports every 4 s from kT0 for `seconds`.
Outcome fly(const std::vector<Flight>& flights, double seconds = 40.0, const PipelineConfig& config = {});

}  // namespace kew::test_support
