// Alert lifecycle (design §4.7): confirm, update, clear, drop; ids and sequence.
#include "kew/alert/alert_manager.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace kew::alert {
namespace {

struct Figures {
  double t_los = 90.0, cpa_h = 1000.0, cpa_v = 0.0;
  Severity severity = Severity::Caution;
};

void expect_same_party(const AlertParty& x, const AlertParty& y) {
  EXPECT_EQ(x.source, y.source);
  EXPECT_EQ(x.id, y.id);
  EXPECT_EQ(x.callsign, y.callsign);
  EXPECT_EQ(x.track_number, y.track_number);
  EXPECT_EQ(x.lat_deg, y.lat_deg);
}

// Same alert and figures; state, time, sequence and end reason may differ.
void expect_same_alert(const AlertEvent& x, const AlertEvent& y) {
  EXPECT_EQ(x.id, y.id);
  EXPECT_EQ(x.number, y.number);
  EXPECT_EQ(x.opened_t, y.opened_t);
  EXPECT_EQ(x.severity, y.severity);
  EXPECT_EQ(x.t_los_s, y.t_los_s);
  EXPECT_EQ(x.cpa_h_m, y.cpa_h_m);
  expect_same_party(x.a, y.a);
  expect_same_party(x.b, y.b);
}

class Lifecycle : public ::testing::Test {
 protected:
  // Evaluates pair {p, q} at t with the given outcome.
  void evaluate(Slot p, Slot q, double t, bool conflict, const Figures& f = {}) {
    Evaluation e{conflict, conflict ? f.severity : Severity::None, f.t_los, f.cpa_h, f.cpa_v};
    manager.evaluate(
        p, q, e, t,
        [&](AlertEvent& event) {
          event.severity = f.severity;
          // Parties ordered by (source, id) as the contract says: by name, not by slot.
          const Slot a = name_of(p) < name_of(q) ? p : q, b = a == p ? q : p;
          event.a.source = event.b.source = "s";
          event.a.id = name_of(a);
          event.a.callsign = "CS" + name_of(a);
          event.a.track_number = static_cast<std::uint16_t>(a);
          event.a.lat_deg = 50.0 + a;
          event.b.id = name_of(b);
          event.b.callsign = "CS" + name_of(b);
          event.b.track_number = static_cast<std::uint16_t>(b);
          event.b.lat_deg = 50.0 + b;
          event.t_los_s = f.t_los;
          event.cpa_h_m = f.cpa_h;
          event.cpa_v_ft = f.cpa_v;
        },
        events);
  }

  // Names that do not sort like the slots, so the lower slot is sometimes party b.
  static std::string name_of(Slot slot) { return "T" + std::to_string(slot * 7 % 10) + std::to_string(slot); }
  std::vector<std::string> names_ = [] {
    std::vector<std::string> v;
    for (Slot s = 0; s < 16; ++s) v.push_back(name_of(s));
    return v;
  }();
  // confirm = clear = 2, the values these cases were worked out for (the default clear is 4).
  static AlertConfig two_and_two() {
    AlertConfig c;
    c.confirm = 2;
    c.clear = 2;
    return c;
  }
  AlertManager manager{two_and_two(), [this](Slot slot) { return PartyName{"s", names_.at(slot)}; }};
  std::vector<AlertEvent> events;
};

TEST_F(Lifecycle, OpensOnlyAfterConfirmConsecutiveConflicts) {
  evaluate(1, 2, 100.0, true);
  EXPECT_TRUE(events.empty());
  evaluate(1, 2, 104.0, false);  // the streak is broken
  evaluate(1, 2, 108.0, true);
  EXPECT_TRUE(events.empty());
  evaluate(2, 1, 112.0, true, {85.0});  // same pair, either order
  ASSERT_EQ(events.size(), 1u);
  const AlertEvent& opened = events[0];
  EXPECT_EQ(opened.state, AlertState::New);
  EXPECT_EQ(opened.seq, 1u);
  EXPECT_EQ(opened.number, 1u);
  EXPECT_EQ(opened.t, 112.0);
  EXPECT_EQ(opened.opened_t, 112.0);
  EXPECT_EQ(opened.id, make_alert_id(opened.a, opened.b, 112.0));
  EXPECT_EQ(opened.id.size(), 16u);
  EXPECT_EQ(manager.active_count(), 1u);
  EXPECT_EQ(manager.counters().opened, 1u);
}

TEST_F(Lifecycle, EvaluationsAtOneDataTimeCountOnce) {
  // jade-cat062-ff 14:46:02Z: both tracks of a CAT062 frame carry the frame's time, so
  // their two records gave two conflicting evaluations at one instant and confirm = 2
  // opened an alert on a single picture (of a track its source ended in that frame).
  evaluate(1, 2, 100.0, true);
  evaluate(2, 1, 100.0, true);
  EXPECT_TRUE(events.empty()) << "one picture is not a confirmation";
  evaluate(1, 2, 105.0, true);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].opened_t, 105.0);
  // Clearing counts instants too: two clear evaluations at 110 are one.
  evaluate(1, 2, 110.0, false);
  evaluate(2, 1, 110.0, false);
  EXPECT_EQ(events.size(), 1u);
  evaluate(1, 2, 115.0, false);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[1].state, AlertState::End);
  EXPECT_EQ(events[1].t, 115.0);
}

TEST_F(Lifecycle, LateRecordsJudgedAtTheClockAreLooksOfTheirOwnTimes) {
  // Records 8 and 4 s late are extrapolated to the clock (116) and judged there: two
  // observations, two looks; one record's two evaluations stay one.
  Evaluation e{true, Severity::Caution, 90.0, 1000.0, 0.0};
  const auto look = [&](double observed_t) {
    e.observed_t = observed_t;
    manager.evaluate(1, 2, e, 116.0, [](AlertEvent& event) { event.a.id = "x", event.b.id = "y"; }, events);
  };
  look(108.0);
  look(108.0);
  EXPECT_TRUE(events.empty());
  look(112.0);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].t, 116.0);
}

TEST_F(Lifecycle, ResumeContinuesSeqAndNumberFromTheGivenValues) {
  // kewd after a restart (design §4.7): the last run's numbering goes on.
  manager.resume(41, 65535);
  EXPECT_EQ(manager.last_seq(), 41u);
  evaluate(1, 2, 100.0, true);
  evaluate(1, 2, 104.0, true);
  evaluate(3, 4, 100.0, true);
  evaluate(3, 4, 104.0, true);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].seq, 42u);
  EXPECT_EQ(events[0].number, 65535u);
  EXPECT_EQ(events[1].seq, 43u);
  EXPECT_EQ(events[1].number, 1u);  // cycles, never 0
  EXPECT_EQ(manager.next_number(), 2u);
  manager.resume(7, 0);  // 0 is no alert number: read as 1
  EXPECT_EQ(manager.next_number(), 1u);
}

TEST_F(Lifecycle, UpdatesOnlyWhenSeverityOrFiguresChange) {
  evaluate(1, 2, 100.0, true, {90.0});
  evaluate(1, 2, 104.0, true, {86.0});  // opens
  ASSERT_EQ(events.size(), 1u);
  evaluate(1, 2, 108.0, true, {82.5});  // t_los aged as expected: no update
  EXPECT_EQ(events.size(), 1u);
  evaluate(1, 2, 112.0, true, {70.0});  // 8 s earlier than the aged figure: update
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[1].state, AlertState::Update);
  EXPECT_EQ(events[1].id, events[0].id);
  EXPECT_EQ(events[1].seq, 2u);
  evaluate(1, 2, 113.0, true, {69.0, 1000.0 + 200.0});  // CPA moved by 200 m ≥ 0.1 NM
  ASSERT_EQ(events.size(), 3u);
  evaluate(1, 2, 114.0, true, {55.0, 1200.0, 0.0, Severity::Warning});
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[3].severity, Severity::Warning);
  evaluate(1, 2, 115.0, true, {54.0, 1200.0, 150.0, Severity::Warning});  // CPA vertical moved 150 ft
  EXPECT_EQ(events.size(), 5u);
}

TEST_F(Lifecycle, EndsAfterClearConsecutiveClearEvaluations) {
  evaluate(1, 2, 100.0, true, {90.0});
  evaluate(1, 2, 104.0, true, {86.0});
  evaluate(1, 2, 108.0, false);
  evaluate(1, 2, 112.0, true, {78.0});  // resets the clear streak; figures as predicted
  evaluate(1, 2, 116.0, false);
  EXPECT_EQ(events.size(), 1u);
  evaluate(1, 2, 120.0, false);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[1].state, AlertState::End);
  EXPECT_EQ(events[1].end_reason, AlertEndReason::Cleared);
  EXPECT_EQ(events[1].t, 120.0);
  EXPECT_EQ(events[1].id, events[0].id);
  EXPECT_EQ(manager.active_count(), 0u);
  // The pair is forgotten: a new conflict must be confirmed again and gets a new id.
  evaluate(1, 2, 124.0, true);
  EXPECT_EQ(events.size(), 2u);
  evaluate(1, 2, 128.0, true);
  ASSERT_EQ(events.size(), 3u);
  EXPECT_NE(events[2].id, events[0].id);
  EXPECT_EQ(events[2].number, 2u);
}

TEST_F(Lifecycle, DroppingATrackEndsItsAlertsInPartnerOrder) {
  for (Slot partner : {9u, 3u, 5u}) {
    evaluate(7, partner, 100.0, true);
    evaluate(7, partner, 104.0, true);
  }
  evaluate(3, 5, 104.0, true);  // pending only: no event, forgotten silently
  ASSERT_EQ(events.size(), 3u);
  std::vector<Slot> partners;
  manager.partners_of(7, partners);
  EXPECT_EQ(partners.size(), 3u);
  manager.drop_track(7, 110.0, events);
  ASSERT_EQ(events.size(), 6u);
  for (int i = 3; i < 6; ++i) {
    EXPECT_EQ(events[i].state, AlertState::End);
    EXPECT_EQ(events[i].end_reason, AlertEndReason::TrackDropped);
    EXPECT_EQ(events[i].t, 110.0);
  }
  // Partner order 3, 5, 9; each End event repeats its alert's last event (opened with
  // partners 9, 3, 5), parties named through the manager's PartyNames.
  const int opening_of_end[3] = {1, 2, 0};
  for (int i = 3; i < 6; ++i) {
    const AlertEvent& opened = events[static_cast<std::size_t>(opening_of_end[i - 3])];
    expect_same_alert(events[static_cast<std::size_t>(i)], opened);
  }
  EXPECT_EQ(events[3].a.id, name_of(3));  // "T13" < "T97"
  EXPECT_EQ(events[3].b.id, name_of(7));
  EXPECT_EQ(events[5].a.id, name_of(9));  // "T39"
  EXPECT_EQ(manager.active_count(), 0u);
  partners.clear();
  manager.partners_of(7, partners);
  EXPECT_TRUE(partners.empty());
}

TEST_F(Lifecycle, SnapshotAcknowledgeAndSeverity) {
  evaluate(1, 2, 100.0, true, {30.0, 500.0, 0.0, Severity::Warning});
  evaluate(1, 2, 104.0, true, {26.0, 500.0, 0.0, Severity::Warning});
  evaluate(3, 4, 100.0, true);
  evaluate(3, 4, 104.0, true);
  ASSERT_EQ(manager.snapshot().size(), 2u);
  EXPECT_EQ(manager.snapshot()[0].a.id, name_of(2));  // opening order; "T42" < "T71"
  expect_same_alert(manager.snapshot()[0], events[0]);
  EXPECT_EQ(manager.snapshot()[0].state, AlertState::New);  // its last event
  expect_same_alert(manager.snapshot()[1], events[1]);
  EXPECT_EQ(manager.highest_severity(), Severity::Warning);
  EXPECT_EQ(manager.unacknowledged_count(), 2u);
  const std::vector<std::string> acknowledged = manager.acknowledge_all();
  ASSERT_EQ(acknowledged.size(), 2u);
  EXPECT_EQ(acknowledged[0], manager.snapshot()[0].id);  // alert-number order
  EXPECT_EQ(acknowledged[1], manager.snapshot()[1].id);
  EXPECT_EQ(manager.unacknowledged_count(), 0u);
  EXPECT_TRUE(manager.acknowledge_all().empty());  // nothing new to acknowledge
  evaluate(3, 4, 108.0, true, {0.0, 500.0, 0.0, Severity::Loss});  // escalation re-arms
  EXPECT_EQ(manager.unacknowledged_count(), 1u);
  EXPECT_EQ(manager.acknowledge_all().size(), 1u);
  EXPECT_FALSE(events.back().acknowledged);
  EXPECT_EQ(manager.highest_severity(), Severity::Loss);
}

TEST(AlertIds, DependOnPairAndOpeningTimeOnly) {
  AlertParty a, b, c;
  a.source = b.source = c.source = "cat062/25.100";
  a.id = "4CA123";
  b.id = "3C6DD2";
  c.id = "4CA12";
  EXPECT_EQ(make_alert_id(a, b, 1714400000.25), make_alert_id(a, b, 1714400000.25));
  EXPECT_NE(make_alert_id(a, b, 1714400000.25), make_alert_id(a, b, 1714400004.25));
  EXPECT_NE(make_alert_id(a, b, 1714400000.25), make_alert_id(a, c, 1714400000.25));
  // The separator keeps ("4CA12", "3…") and ("4CA123", "…") apart.
  AlertParty b2 = b;
  b2.id = "3" + b.id;
  EXPECT_NE(make_alert_id(c, b2, 1.0), make_alert_id(a, b, 1.0));
}

TEST(Severities, ClassifiedByTimeToLoss) {
  const AlertManager m{AlertConfig{}, [](Slot) { return PartyName{}; }};
  EXPECT_EQ(m.classify(true, 0.0), Severity::Loss);
  EXPECT_EQ(m.classify(false, 60.0), Severity::Warning);
  EXPECT_EQ(m.classify(false, 60.5), Severity::Caution);
  EXPECT_EQ(kSeverityNames.parse("warning"), Severity::Warning);
  EXPECT_FALSE(kSeverityNames.parse("urgent"));
  EXPECT_EQ(kSeverityNames.list({Severity::None}), "caution, warning, loss");
}

}  // namespace
}  // namespace kew::alert
