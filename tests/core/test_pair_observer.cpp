// The pair observer (design §4.10): the facts the pipeline reports about watched tracks
// and pairs (refused and applied records, the stage that holds a pair back with its
// enums and figures), and that it reports nothing about other tracks.
#include "kew/pipeline/pair_observer.hpp"
#include "kew/pipeline/pipeline.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scripted_flight.hpp"

namespace kew {
namespace {

using test_support::Flight;
using test_support::head_on;
using test_support::kT0;

/// What an observer was told about one pair judgement: the facts it copies, since the
/// observation's pointers are valid during the call only.
struct Judged {
  double t = 0.0;
  std::string updated, partner;
  PairStage stage = PairStage::NoTrack;
  bool figures = false;
  double t_los_s = 0.0;
  int confirm = 0;
  std::string p, q;
  eligibility::PairVerdict verdict;
  std::string excluded;
  double limit = 0.0;
};

/// Watches the pair "test:A" x "test:B" at all times and keeps what it is told.
class Recorder final : public PairObserver {
 public:
  bool watches(std::string_view source, std::string_view id) const override {
    return source == source_ && (id == a_ || id == b_);
  }
  std::vector<alert::PartyName> partners(std::string_view source, std::string_view id, double) const override {
    if (!watches(source, id)) return {};
    return {{source_, id == a_ ? b_ : a_}};
  }
  void record(const TrackReport& report, const RecordOutcome& outcome) override {
    records.push_back({report.id, outcome});
  }
  void pair_judged(const PairObservation& o) override {
    Judged j;
    j.t = o.t;
    j.updated = o.updated.id;
    j.partner = o.partner.id;
    j.stage = o.stage;
    j.figures = o.figures.has_value();
    if (o.figures) j.t_los_s = o.figures->t_los_s;
    j.confirm = o.confirm;
    if (o.p) j.p = o.p->id;
    if (o.q) j.q = o.q->id;
    j.verdict = o.verdict;
    if (o.excluded) j.excluded = o.excluded->id;
    j.limit = o.limit.low;
    judged.push_back(j);
  }

  struct Record {
    std::string id;
    RecordOutcome outcome;
  };
  std::vector<Record> records;
  std::vector<Judged> judged;

 private:
  std::string source_ = "test", a_ = "A", b_ = "B";
};

TEST(PairObserver, SeesARefusedRecordsRefusal) {
  Recorder recorder;
  Pipeline pipeline;
  pipeline.set_pair_observer(&recorder);
  const Flight a = head_on()[0];
  const Flight c{"C"};  // not watched
  ASSERT_TRUE(pipeline.process(a.at(kT0)).applied());
  TrackReport off_the_map = a.at(kT0 + 4.0);
  off_the_map.lat_deg = 95.0;  // refused on its own, before the track stage takes it
  EXPECT_EQ(pipeline.process(off_the_map).refusal, track::Refusal::LatitudeOutOfRange);
  EXPECT_EQ(pipeline.process(a.at(kT0)).refusal, track::Refusal::DuplicateTime);  // refused by the track table
  EXPECT_TRUE(pipeline.process(c.at(kT0)).applied());
  EXPECT_EQ(pipeline.process(c.at(kT0)).refusal, track::Refusal::DuplicateTime);

  ASSERT_EQ(recorder.records.size(), 3u);  // nothing of C
  EXPECT_EQ(recorder.records[0].id, "A");
  EXPECT_EQ(recorder.records[0].outcome.kind, RecordOutcome::Kind::Accepted);
  EXPECT_EQ(recorder.records[1].outcome.kind, RecordOutcome::Kind::Refused);
  EXPECT_EQ(recorder.records[1].outcome.refusal, track::Refusal::LatitudeOutOfRange);
  EXPECT_EQ(recorder.records[2].outcome.kind, RecordOutcome::Kind::Refused);
  EXPECT_EQ(recorder.records[2].outcome.refusal, track::Refusal::DuplicateTime);
}

TEST(PairObserver, SeesThePairsStagesWithTheirFacts) {
  Recorder recorder;
  Pipeline pipeline;
  pipeline.set_pair_observer(&recorder);
  std::vector<AlertEvent> events;
  pipeline.set_alert_sink([&](const AlertEvent& e) { events.push_back(e); });
  for (double t = kT0; t <= kT0 + 60.0; t += 4.0)
    for (const Flight& f : head_on()) pipeline.process(f.at(t));
  ASSERT_FALSE(events.empty());
  ASSERT_FALSE(recorder.judged.empty());

  // A's first record finds no track of B.
  const Judged& first = recorder.judged.front();
  EXPECT_EQ(first.stage, PairStage::NoTrack);
  EXPECT_EQ(first.updated, "A");
  EXPECT_EQ(first.partner, "B");
  EXPECT_FALSE(first.figures);
  // Then in conflict, held by the first-records exclusion with its limit, confirmed, and
  // alerting at the first event's time, with the conflict test's figures.
  const auto find = [&](PairStage stage) {
    for (const Judged& j : recorder.judged)
      if (j.stage == stage) return &j;
    return static_cast<const Judged*>(nullptr);
  };
  const Judged* excluded = find(PairStage::Excluded);
  ASSERT_NE(excluded, nullptr);
  EXPECT_EQ(excluded->verdict.rule, eligibility::PairRule::Excluded);
  EXPECT_EQ(excluded->verdict.exclusion, eligibility::Exclusion::FirstRecords);
  EXPECT_FALSE(excluded->excluded.empty());
  EXPECT_EQ(excluded->limit, PipelineConfig().eligibility.min_records);
  ASSERT_NE(find(PairStage::ConfirmPending), nullptr);
  const Judged* alerting = find(PairStage::Alerting);
  ASSERT_NE(alerting, nullptr);
  EXPECT_EQ(alerting->t, events.front().t);
  EXPECT_TRUE(alerting->figures);
  EXPECT_GT(alerting->t_los_s, 0.0);
  EXPECT_EQ(alerting->confirm, PipelineConfig().alerts.confirm);
  EXPECT_EQ(alerting->verdict.rule, eligibility::PairRule::None);
  EXPECT_EQ(alerting->p + alerting->q, "AB");  // the lower slot, A's, first
}

}  // namespace
}  // namespace kew
