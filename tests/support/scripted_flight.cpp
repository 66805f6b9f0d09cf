#include "scripted_flight.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cmath>

namespace kew::test_support {

TrackReport Flight::at(double t) const {
  const double speed = gs_kt * kKnot;
  const double elapsed = t - kT0;
  const double turning = turn_dps != 0.0 ? std::min(elapsed, turn_s) : 0.0;
  const double heading0 = trk_deg * M_PI / 180.0;
  // The arc first (heading h(u) = h0 + ω·u, clockwise), then a straight line on.
  double east = 0.0, north = 0.0, heading = heading0;
  if (turning > 0.0) {
    const double omega = turn_dps * M_PI / 180.0;
    heading = heading0 + omega * turning;
    east = speed / omega * (std::cos(heading0) - std::cos(heading));
    north = speed / omega * (std::sin(heading) - std::sin(heading0));
  }
  const double straight = elapsed - turning;
  east += speed * straight * std::sin(heading);
  north += speed * straight * std::cos(heading);

  const auto& wgs84 = GeographicLib::Geodesic::WGS84();
  double lat0, lon0, lat, lon;
  wgs84.Direct(lat0_deg, lon0_deg, 90.0, east_m + east, lat0, lon0);
  wgs84.Direct(lat0, lon0, 0.0, north_m + north, lat, lon);
  TrackReport r;
  r.t = t;
  r.id = id;
  r.source = source;
  r.lat_deg = lat;
  r.lon_deg = lon;
  r.alt_ft = alt_ft + vr_fpm * elapsed / 60.0;
  r.gs_kt = gs_kt;
  double track = turning > 0.0 ? std::fmod(heading * 180.0 / M_PI, 360.0) : trk_deg;
  if (track < 0.0) track += 360.0;
  r.trk_deg = track;
  r.vr_fpm = vr_fpm;
  if (edit) edit(r);
  return r;
}

std::size_t Outcome::opened() const {
  return static_cast<std::size_t>(
      std::count_if(events.begin(), events.end(), [](const AlertEvent& e) { return e.state == AlertState::New; }));
}

double Outcome::first_opened_t() const {
  for (const AlertEvent& e : events)
    if (e.state == AlertState::New) return e.t;
  return -1.0;
}

Outcome fly(const std::vector<Flight>& flights, double seconds, const PipelineConfig& config) {
  Outcome run;
  run.pipeline = std::make_unique<Pipeline>(config);
  run.pipeline->set_alert_sink([&run](const AlertEvent& e) { run.events.push_back(e); });
  for (double dt = 0.0; dt < seconds; dt += 4.0)
    for (const Flight& f : flights) run.pipeline->process(f.at(kT0 + dt));
  run.pipeline->set_alert_sink({});  // `run` is moved out: nothing may write to it after
  return run;
}

std::vector<Flight> head_on(double alt_a_ft, double alt_b_ft) {
  Flight a{"A"};
  a.east_m = -10.0 * 1852.0;
  a.alt_ft = alt_a_ft;
  Flight b{"B"};
  b.east_m = 10.0 * 1852.0;
  b.trk_deg = 270.0;
  b.alt_ft = alt_b_ft;
  return {a, b};
}

}  // namespace kew::test_support
