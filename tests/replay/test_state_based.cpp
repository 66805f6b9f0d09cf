// The state-based peer baseline (kew-eval --baseline statebased, design §2.6): BlueSky's
// all-pairs linear test, 5 NM / 1,000 ft / 300 s, no filters. Reference cases with the
// opening and end times their geometry gives.
#include "kew/replay/state_based.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace kew::replay {
namespace {

constexpr double kT0 = 1714400000.0;
constexpr double kNm = 1852.0;
constexpr double kLat = 50.0;

struct Aircraft {
  std::string id;
  double east_nm = 0.0;  // at kT0, from (50° N, 8° E)
  double north_nm = 0.0;
  double alt_ft = 35000.0;
  double gs_kt = 450.0;
  double trk_deg = 90.0;
  double vr_fpm = 0.0;
  double last_s = 1e9;  // no record after kT0 + this
  bool on_ground = false;
};

/// Every aircraft reports every second for `seconds`, in time order.
std::vector<TrackReport> fly(const std::vector<Aircraft>& aircraft, double seconds) {
  std::vector<TrackReport> out;
  const double metres_per_degree_lat = 111229.0;  // at 50° N
  const double metres_per_degree_lon = 71696.0;
  for (double s = 0.0; s <= seconds; s += 1.0) {
    for (const Aircraft& a : aircraft) {
      if (s > a.last_s) continue;
      const double v = a.gs_kt * kNm / 3600.0;
      const double east = a.east_nm * kNm + v * std::sin(a.trk_deg * M_PI / 180.0) * s;
      const double north = a.north_nm * kNm + v * std::cos(a.trk_deg * M_PI / 180.0) * s;
      TrackReport r;
      r.t = kT0 + s;
      r.source = "test";
      r.id = a.id;
      r.lat_deg = kLat + north / metres_per_degree_lat;
      r.lon_deg = 8.0 + east / metres_per_degree_lon;
      r.alt_ft = a.alt_ft + a.vr_fpm * s / 60.0;
      r.gs_kt = a.gs_kt;
      r.trk_deg = a.trk_deg;
      r.vr_fpm = a.vr_fpm;
      r.on_ground = a.on_ground;
      out.push_back(r);
    }
  }
  return out;
}

// Head-on at 450 kt each, 40 NM apart: closer than 5 NM from 140 s to 180 s.
std::vector<Aircraft> head_on(double alt_b_ft = 35000.0, double offset_nm = 0.0) {
  Aircraft a{"A", -20.0, 0.0};
  Aircraft b{"B", 20.0, offset_nm, alt_b_ft, 450.0, 270.0};
  return {a, b};
}

TEST(StateBased, AHeadOnPairAlertsFromItsFirstStepUntilItHasPassed) {
  const std::vector<AlertSpan> alerts = state_based_alerts(fly(head_on(), 240.0));
  ASSERT_EQ(alerts.size(), 1u);
  // The loss is 140 s ahead, inside 300 s: in conflict at the first step with both states.
  EXPECT_EQ(alerts[0].opened_t, kT0 + 1.0);
  ASSERT_TRUE(alerts[0].ended_t);
  EXPECT_NEAR(*alerts[0].ended_t, kT0 + 180.0, 1.0);
  EXPECT_EQ(alerts[0].a_id, "A");
  EXPECT_EQ(alerts[0].b_id, "B");
  EXPECT_EQ(alerts[0].max_severity, Severity::Loss);
}

TEST(StateBased, ReferenceCases) {
  struct Case {
    const char* name;
    std::vector<Aircraft> aircraft;
    std::size_t alerts;
  };
  Aircraft climber = head_on(33000.0)[1];
  climber.vr_fpm = 1000.0;  // within 1,000 ft of FL350 from 60 s to 180 s
  Aircraft far = head_on()[1];
  far.east_nm = 80.0;  // 100 NM apart: the loss 380 s ahead, beyond T until 80 s have passed
  Aircraft parked_a{"P1", 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e9, true};
  Aircraft parked_b{"P2", 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 1e9, true};
  const std::vector<Case> cases = {
      {"1,000 ft apart and level: separated", head_on(36000.0), 0},
      {"999 ft apart: within S_v", head_on(35999.0), 1},
      {"passing 6 NM abeam: never within 5 NM", head_on(35000.0, 6.0), 0},
      {"passing 4.9 NM abeam", head_on(35000.0, 4.9), 1},
      {"climbing through the other's level", {head_on()[0], climber}, 1},
      {"the loss beyond the look-ahead at first", {head_on()[0], far}, 1},
      {"no filters: two parked aircraft alert", {parked_a, parked_b}, 1},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    EXPECT_EQ(state_based_alerts(fly(c.aircraft, 240.0)).size(), c.alerts);
  }
  const std::vector<AlertSpan> late = state_based_alerts(fly({head_on()[0], far}, 240.0));
  ASSERT_EQ(late.size(), 1u);
  EXPECT_NEAR(late[0].opened_t, kT0 + 80.0, 1.0);
}

TEST(StateBased, AnAircraftThatFallsSilentEndsItsAlertAfterTheTimeout) {
  std::vector<Aircraft> pair = head_on();
  pair[1].last_s = 20.0;
  const std::vector<AlertSpan> alerts = state_based_alerts(fly(pair, 120.0));
  ASSERT_EQ(alerts.size(), 1u);
  ASSERT_TRUE(alerts[0].ended_t);
  EXPECT_NEAR(*alerts[0].ended_t, kT0 + 20.0 + StateBasedConfig{}.timeout_s, 1.0);
}

TEST(StateBased, IsDeterministic) {
  const std::vector<TrackReport> records = fly(head_on(35500.0, 2.0), 240.0);
  const std::vector<AlertSpan> first = state_based_alerts(records);
  const std::vector<AlertSpan> second = state_based_alerts(records);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].id, second[i].id);
    EXPECT_EQ(first[i].opened_t, second[i].opened_t);
  }
}

}  // namespace
}  // namespace kew::replay
