// Hot standby's judgement (design §5.9): an instance is in step with the active when it
// has computed every event the alert stream held when it began following it, each equal
// to the active's; the active's acknowledgements apply where they happened; the pair's
// origin is read back exactly as written, and anything else is refused.
#include "standby_sync.hpp"

#include <gtest/gtest.h>

#include "pair_checkpoint.hpp"
#include "pair_origin.hpp"

namespace kew::daemon {
namespace {

AlertEvent event(std::uint64_t seq, const std::string& id, AlertState state, std::uint16_t number,
                 Severity severity = Severity::Warning) {
  AlertEvent e;
  e.seq = seq;
  e.id = id;
  e.state = state;
  e.number = number;
  e.severity = severity;
  if (state == AlertState::End) e.end_reason = AlertEndReason::Cleared;
  return e;
}

TEST(StandbySync, AnInstanceBehindTheActiveIsInStepOnceItHasComputedWhatTheStreamHeld) {
  StandbySync sync(100);
  sync.active_alert(event(101, "a1", AlertState::New, 7));
  sync.active_alert(event(102, "a2", AlertState::New, 8));
  sync.stream_read_up_to(102);
  EXPECT_EQ(sync.state(), StandbySync::State::Syncing);
  sync.own_alert(event(101, "a1", AlertState::New, 7));
  EXPECT_EQ(sync.state(), StandbySync::State::Syncing);  // seq 102 still to compute
  sync.own_alert(event(102, "a2", AlertState::New, 8));
  EXPECT_TRUE(sync.in_step());
  // Later events on both sides, in either order, keep it in step.
  sync.own_alert(event(103, "a1", AlertState::End, 7));
  sync.active_alert(event(103, "a1", AlertState::End, 7));
  sync.active_alert(event(104, "a3", AlertState::New, 9));
  sync.own_alert(event(104, "a3", AlertState::New, 9));
  EXPECT_TRUE(sync.in_step());
  EXPECT_TRUE(sync.departure().empty());
}

TEST(StandbySync, AnEmptyStreamAfterTheOriginIsInStepAtOnce) {
  StandbySync sync(40);
  sync.stream_read_up_to(40);
  EXPECT_TRUE(sync.in_step());
}

TEST(StandbySync, AnyDifferenceOfIdNumberStateSeverityOrReasonIsADeparture) {
  const auto departs = [](AlertEvent mine, bool own_first) {
    StandbySync sync(0);
    const AlertEvent theirs = event(1, "x", AlertState::New, 1);
    mine.seq = 1;
    if (own_first) {
      sync.own_alert(mine);
      sync.active_alert(theirs);
    } else {
      sync.active_alert(theirs);
      sync.own_alert(mine);
    }
    sync.stream_read_up_to(1);
    return sync.state() == StandbySync::State::OutOfStep;
  };
  for (bool own_first : {false, true}) {
    EXPECT_FALSE(departs(event(1, "x", AlertState::New, 1), own_first));
    EXPECT_TRUE(departs(event(1, "y", AlertState::New, 1), own_first));
    EXPECT_TRUE(departs(event(1, "x", AlertState::New, 2), own_first));
    EXPECT_TRUE(departs(event(1, "x", AlertState::Update, 1), own_first));
    EXPECT_TRUE(departs(event(1, "x", AlertState::New, 1, Severity::Loss), own_first));
  }
  // The figures and the acknowledged flag are not the numbering's concern.
  AlertEvent figures = event(1, "x", AlertState::New, 1);
  figures.t_los_s = 12.5;
  figures.acknowledged = true;
  EXPECT_FALSE(departs(figures, false));
}

TEST(StandbySync, OutOfStepStaysSoAndSaysWhere) {
  StandbySync sync(0);
  sync.stream_read_up_to(0);
  ASSERT_TRUE(sync.in_step());
  sync.active_alert(event(1, "x", AlertState::New, 1));
  sync.own_alert(event(1, "x", AlertState::New, 2));
  EXPECT_EQ(sync.state(), StandbySync::State::OutOfStep);
  EXPECT_EQ(sync.departure(), "the active sent seq 1 x #1 new warning, this instance computed seq 1 x #2 new warning");
  sync.active_alert(event(2, "y", AlertState::New, 3));
  sync.own_alert(event(2, "y", AlertState::New, 3));
  EXPECT_EQ(sync.state(), StandbySync::State::OutOfStep);
}

TEST(StandbySync, AnAcknowledgementIsDueOnceThisInstanceHasComputedTheEventItFollowed) {
  StandbySync sync(10);
  sync.active_alert(event(11, "x", AlertState::New, 1));
  sync.active_acknowledgement(11, {"x"});
  sync.active_alert(event(12, "x", AlertState::Update, 1));
  sync.active_acknowledgement(12, {"x"});
  EXPECT_TRUE(sync.due_acknowledgements().empty());  // this instance is at seq 10
  sync.own_alert(event(11, "x", AlertState::New, 1));
  const auto due = sync.due_acknowledgements();
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(due[0], std::vector<std::string>{"x"});
  EXPECT_TRUE(sync.due_acknowledgements().empty());  // taken out
  sync.own_alert(event(12, "x", AlertState::Update, 1));
  EXPECT_EQ(sync.due_acknowledgements().size(), 1u);
  // One that comes after this instance computed its event is due at once.
  sync.active_acknowledgement(12, {"x"});
  EXPECT_EQ(sync.due_acknowledgements().size(), 1u);
}

TEST(StandbySync, TheActivesOpenAlertsAreItsEventsWithoutAnEndInOpeningOrder) {
  StandbySync sync(0);
  sync.active_alert(event(1, "b", AlertState::New, 1));
  sync.active_alert(event(2, "a", AlertState::New, 2));
  sync.active_alert(event(3, "c", AlertState::New, 3));
  sync.active_alert(event(4, "a", AlertState::End, 2));
  sync.active_alert(event(5, "b", AlertState::Update, 1, Severity::Loss));
  sync.active_alert(event(5, "b", AlertState::End, 1));  // read again: ignored
  const std::vector<AlertEvent> open = sync.open_on_active();
  ASSERT_EQ(open.size(), 2u);
  EXPECT_EQ(open[0].id, "c");  // the last event of each, by seq
  EXPECT_EQ(open[1].id, "b");
  EXPECT_EQ(open[1].severity, Severity::Loss);
}

TEST(PairOrigin, ReadsBackWhatItWritesAndRefusesAnythingElse) {
  PairOrigin origin;
  origin.feed_seq = 1234;
  origin.alerts_seq = 56;
  origin.last_seq = 789;
  origin.next_number = 65535;
  origin.created_by = "kew-a \"north\"";
  origin.created_unix_s = 1733000000.125;
  const std::string text = to_json(origin);
  EXPECT_EQ(text, R"({"feed_seq":1234,"alerts_seq":56,"last_seq":789,"next_number":65535,)"
                  R"("created_by":"kew-a \"north\"","created_t":1733000000.125})");
  EXPECT_EQ(pair_origin_from_json(text), origin);
  for (const char* bad : {"", "{}", "[1]", "not json", R"({"feed_seq":0,"alerts_seq":1,"last_seq":0,"next_number":1,"created_by":"a","created_t":0})",
                          R"({"feed_seq":1,"alerts_seq":1,"last_seq":0,"next_number":70000,"created_by":"a","created_t":0})",
                          R"({"feed_seq":1,"alerts_seq":1,"last_seq":-1,"next_number":1,"created_by":"a","created_t":0})",
                          R"({"feed_seq":1,"alerts_seq":1,"last_seq":0,"next_number":1,"created_by":7,"created_t":0})"})
    EXPECT_FALSE(pair_origin_from_json(bad)) << bad;
}

TEST(PairCheckpoint, ReadsBackWhatItWritesAndRefusesAnythingElse) {
  PairCheckpoint checkpoint;
  checkpoint.origin_feed_seq = 3;
  checkpoint.origin_created_unix_s = 1733000000.125;
  checkpoint.feed_seq = 90210;
  checkpoint.alerts_seq = 4711;
  checkpoint.last_seq = 815;
  checkpoint.written_by = "kew-a \"north\"";
  checkpoint.written_unix_s = 1733000300.5;
  checkpoint.pipeline = std::string("\0state\n\xff bytes\n", 15);
  const std::string bytes = to_bytes(checkpoint);
  std::string why;
  EXPECT_EQ(pair_checkpoint_from_bytes(bytes, why), checkpoint) << why;
  // Every truncation, an altered byte of the state, a header without a field, and a
  // feed message before the pair's origin are refused, each saying why.
  for (std::size_t cut = 0; cut < bytes.size(); ++cut) {
    why.clear();
    EXPECT_FALSE(pair_checkpoint_from_bytes(std::string_view(bytes).substr(0, cut), why)) << cut;
    EXPECT_FALSE(why.empty()) << cut;
  }
  std::string altered = bytes;
  altered.back() ^= 1;
  EXPECT_FALSE(pair_checkpoint_from_bytes(altered, why));
  EXPECT_NE(why.find("CRC-32"), std::string::npos) << why;
  std::string no_field = bytes;
  no_field.replace(no_field.find("\"last_seq\""), 10, "\"lost_seq\"");
  EXPECT_FALSE(pair_checkpoint_from_bytes(no_field, why));
  PairCheckpoint before_origin = checkpoint;
  before_origin.feed_seq = 2;
  EXPECT_FALSE(pair_checkpoint_from_bytes(to_bytes(before_origin), why));
}

TEST(StandbySync, ACheckpointsOpenAlertsAreTheActivesToEndInAnUnsyncedTakeover) {
  StandbySync sync(100);
  AlertEvent open_at_checkpoint;
  open_at_checkpoint.id = "a1";
  open_at_checkpoint.seq = 98;
  open_at_checkpoint.state = AlertState::Update;
  sync.seed_open({open_at_checkpoint});
  AlertEvent ended = open_at_checkpoint;
  ended.id = "a2";
  ended.seq = 101;
  ended.state = AlertState::New;
  sync.active_alert(ended);
  const std::vector<AlertEvent> open = sync.open_on_active();
  ASSERT_EQ(open.size(), 2u);
  EXPECT_EQ(open[0].id, "a1");
  EXPECT_EQ(open[1].id, "a2");
}

}  // namespace
}  // namespace kew::daemon
