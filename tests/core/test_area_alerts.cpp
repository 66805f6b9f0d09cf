// Area proximity warnings in the alert manager (design §4.7, §4.11): a track and a
// volume under the lifecycle of a pair, sharing numbers and sequence with pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "kew/alert/alert_manager.hpp"

namespace kew::alert {
namespace {

class AreaAlerts : public ::testing::Test {
 protected:
  static AlertConfig two_and_two() {
    AlertConfig c;
    c.confirm = 2;
    c.clear = 2;
    return c;
  }
  static std::string name_of(Slot slot) { return "T" + std::to_string(slot); }
  static std::string volume_name(std::uint32_t volume) { return "V" + std::to_string(volume); }

  void area(Slot slot, std::uint32_t volume, double t, bool conflict, double t_entry = 30.0) {
    Evaluation e{conflict, conflict ? (t_entry == 0.0 ? Severity::Loss : Severity::Warning) : Severity::None, t_entry,
                 0.0, 0.0};
    manager.evaluate_area(
        slot, volume, e, t,
        [&](AlertEvent& event) {
          event.a.source = "s";
          event.a.id = name_of(slot);
          event.a.lat_deg = 50.0 + slot;
          event.t_los_s = t_entry;
          event.volume = volume_name(volume);
          event.volume_kind = "restricted";
        },
        events);
  }
  void pair(Slot p, Slot q, double t, bool conflict) {
    Evaluation e{conflict, conflict ? Severity::Caution : Severity::None, 90.0, 1000.0, 0.0};
    manager.evaluate(
        p, q, e, t,
        [&](AlertEvent& event) {
          event.a.source = event.b.source = "s";
          event.a.id = name_of(std::min(p, q));
          event.b.id = name_of(std::max(p, q));
        },
        events);
  }

  AlertManager manager{two_and_two(), [](Slot slot) {
                         static std::vector<std::string> names = [] {
                           std::vector<std::string> v;
                           for (Slot s = 0; s < 8; ++s) v.push_back(name_of(s));
                           return v;
                         }();
                         return PartyName{"s", names.at(slot)};
                       }};
  std::vector<AlertEvent> events;
};

TEST_F(AreaAlerts, OpenAfterConfirmAsApwWithTheVolumeAndNoSecondAircraft) {
  area(1, 3, 100.0, true);
  EXPECT_TRUE(events.empty());
  area(1, 3, 101.0, true);
  ASSERT_EQ(events.size(), 1u);
  const AlertEvent& e = events[0];
  EXPECT_EQ(e.kind, AlertKind::Apw);
  EXPECT_EQ(e.state, AlertState::New);
  EXPECT_EQ(e.volume, "V3");
  EXPECT_EQ(e.volume_kind, "restricted");
  EXPECT_EQ(e.a.id, "T1");
  EXPECT_TRUE(e.b.id.empty());
  EXPECT_TRUE(manager.is_area_active(1, 3));
  EXPECT_FALSE(manager.is_area_active(1, 2));
  EXPECT_EQ(manager.active_count(), 1u);
}

TEST_F(AreaAlerts, ShareNumbersAndSequenceWithPairsAndHaveIdsOfTheirOwn) {
  pair(1, 2, 100.0, true);
  area(1, 3, 100.0, true);
  area(1, 4, 100.0, true);
  pair(1, 2, 101.0, true);
  area(1, 3, 101.0, true);
  area(1, 4, 101.0, true);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].kind, AlertKind::Stca);
  EXPECT_EQ(events[1].kind, AlertKind::Apw);
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].seq, i + 1);
    EXPECT_EQ(events[i].number, i + 1);
  }
  EXPECT_NE(events[1].id, events[2].id);  // one aircraft, two volumes, one time
  EXPECT_EQ(events[1].id, format_alert_id(area_alert_id_hash(events[1].a, "V3", 101.0)));
}

TEST_F(AreaAlerts, EndAfterClearEvaluationsAndWhenTheTrackOrTheVolumeGoes) {
  for (const double t : {100.0, 101.0}) {
    area(1, 3, t, true);
    area(2, 3, t, true);
    area(2, 5, t, true);
    pair(1, 2, t, true);
  }
  ASSERT_EQ(events.size(), 4u);
  events.clear();
  area(1, 3, 102.0, false);
  area(1, 3, 103.0, false);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].end_reason, AlertEndReason::Cleared);
  EXPECT_EQ(events[0].kind, AlertKind::Apw);
  EXPECT_EQ(events[0].volume, "V3");
  events.clear();

  manager.drop_volume(5, 104.0, events);  // a followed aircraft's volume goes with it
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].volume, "V5");
  EXPECT_EQ(events[0].end_reason, AlertEndReason::TrackDropped);
  events.clear();

  manager.drop_track(2, 105.0, events);  // its pair first, then its volumes
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, AlertKind::Stca);
  EXPECT_EQ(events[1].kind, AlertKind::Apw);
  EXPECT_EQ(events[1].a.id, "T2");
  EXPECT_EQ(manager.active_count(), 0u);
  std::vector<std::uint32_t> volumes;
  manager.volumes_of(2, volumes);
  EXPECT_TRUE(volumes.empty());
}

TEST_F(AreaAlerts, VolumesOfATrackAreThoseBeingJudged) {
  area(1, 3, 100.0, true);  // pending
  area(1, 7, 100.0, true);
  std::vector<std::uint32_t> volumes;
  manager.volumes_of(1, volumes);
  std::sort(volumes.begin(), volumes.end());
  EXPECT_EQ(volumes, (std::vector<std::uint32_t>{3, 7}));
  std::vector<Slot> partners;
  manager.partners_of(1, partners);
  EXPECT_TRUE(partners.empty());  // a volume is never a partner track
}

TEST_F(AreaAlerts, ACheckpointContinuesAreaAlertsEventForEvent) {
  area(1, 3, 100.0, true);
  area(1, 3, 101.0, true);
  area(2, 3, 101.0, true);  // pending
  util::CheckpointWriter out;
  manager.save(out);
  AlertManager restored{two_and_two(), [](Slot slot) {
                          static const std::vector<std::string> names = {"T0", "T1", "T2", "T3"};
                          return PartyName{"s", names.at(slot)};
                        }};
  util::CheckpointReader in(out.bytes());
  restored.restore(in);
  ASSERT_EQ(restored.snapshot().size(), 1u);
  EXPECT_EQ(restored.snapshot()[0].kind, AlertKind::Apw);
  EXPECT_EQ(restored.snapshot()[0].volume, "V3");
  std::vector<AlertEvent> theirs;
  std::swap(theirs, events);
  for (AlertManager* m : {&manager, &restored}) {
    std::vector<AlertEvent>& into = m == &manager ? theirs : events;
    into.clear();
    m->evaluate_area(2, 3, Evaluation{true, Severity::Warning, 20.0, 0.0, 0.0}, 102.0,
                     [](AlertEvent& e) {
                       e.a.source = "s";
                       e.a.id = "T2";
                       e.volume = "V3";
                     },
                     into);
    m->drop_track(1, 103.0, into);
  }
  ASSERT_EQ(events.size(), theirs.size());
  ASSERT_EQ(events.size(), 2u);
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].id, theirs[i].id);
    EXPECT_EQ(events[i].seq, theirs[i].seq);
    EXPECT_EQ(events[i].number, theirs[i].number);
    EXPECT_EQ(events[i].volume, theirs[i].volume);
    EXPECT_EQ(events[i].state, theirs[i].state);
  }
}

}  // namespace
}  // namespace kew::alert
