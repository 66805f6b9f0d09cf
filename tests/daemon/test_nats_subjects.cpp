// The subjects kewd publishes alerts to (docs/nats.md, design §5.9): a conflict to
// <alerts_subject>.<zone> of the zone that owns its pair, an area proximity warning to
// <alerts_subject>.apw.<zone> of the zone holding its aircraft.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "kew/config/nats_subject.hpp"
#include "nats_output.hpp"

namespace kew::daemon {
namespace {

AlertEvent conflict() {
  AlertEvent e;
  e.kind = AlertKind::Stca;
  e.a.id = "3c6444";
  e.a.lat_deg = 48.35;
  e.a.lon_deg = 11.78;
  e.b.id = "a1b2c3";
  e.b.lat_deg = 48.40;
  e.b.lon_deg = 11.70;
  return e;
}

/// Aircraft a and a volume; b empty, at (0, 0) as every empty party is.
AlertEvent area_warning() {
  AlertEvent e = conflict();
  e.kind = AlertKind::Apw;
  e.b = {};
  e.volume = "EDR-114";
  e.volume_kind = "restricted";
  return e;
}

TEST(NatsSubjects, SingleZoneMode) {
  EXPECT_EQ(alert_subject_tail(conflict(), std::nullopt), "single");
  EXPECT_EQ(alert_subject_tail(area_warning(), std::nullopt), "apw.single");
}

TEST(NatsSubjects, AnAreaWarningGoesToTheZoneOfItsAircraft) {
  const std::optional<zone::ZoneTiling> tiling(std::in_place, 50'000.0);
  const std::string munich = config::nats_subject_token(tiling->name(tiling->home({48.35, 11.78})));
  EXPECT_EQ(munich, "N49_5E013_3");
  EXPECT_EQ(alert_subject_tail(conflict(), tiling), munich);
  // Not the owner of a and the empty b's (0, 0): that is a zone in Africa.
  EXPECT_EQ(alert_subject_tail(area_warning(), tiling), "apw." + munich);
  const AlertEvent far = area_warning();
  EXPECT_NE(config::nats_subject_token(tiling->name(tiling->owner({far.a.lat_deg, far.a.lon_deg}, {0.0, 0.0}))),
            munich);
}

}  // namespace
}  // namespace kew::daemon
