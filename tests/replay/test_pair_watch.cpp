// The pair watch (design §4.10): what it notes, in words, about a watched pair at each
// update, the first stage that holds it back, and that watching changes no alert.
#include "kew/replay/pair_watch.hpp"
#include "kew/pipeline/pipeline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "scripted_flight.hpp"

namespace kew {
namespace {

using replay::PairNote;
using replay::PairWatch;
using test_support::Flight;
using test_support::head_on;
using test_support::kT0;

struct Watched {
  std::vector<PairNote> notes;
  std::vector<AlertEvent> events;
};

/// Flies `flights` (records every 4 s for `seconds`) through a pipeline watching A x B.
Watched watch_pair(const std::vector<Flight>& flights, double seconds = 60.0, PipelineConfig config = {}) {
  PairWatch watch;
  watch.watch("test", "A", "test", "B", kT0, kT0 + seconds);
  Pipeline pipeline(config);
  pipeline.set_pair_observer(&watch);
  Watched out;
  pipeline.set_alert_sink([&](const AlertEvent& e) { out.events.push_back(e); });
  for (double t = kT0; t <= kT0 + seconds; t += 4.0)
    for (const Flight& f : flights) pipeline.process(f.at(t));
  out.notes = watch.pair(0).notes;
  return out;
}

std::vector<PairStage> stages(const std::vector<PairNote>& notes) {
  std::vector<PairStage> out;
  for (const PairNote& n : notes)
    if (out.empty() || out.back() != n.stage) out.push_back(n.stage);
  return out;
}


TEST(PairWatch, NotesAPairFromItsFirstRecordsToItsAlert) {
  const Watched w = watch_pair(head_on());
  // A's first record finds no B; then the pair is in conflict, held while either track
  // has one record only (first_records: no addresses), confirmed at its second look, and
  // alerts.
  EXPECT_EQ(stages(w.notes), (std::vector<PairStage>{PairStage::NoTrack, PairStage::Excluded,
                                                     PairStage::ConfirmPending, PairStage::Alerting}));
  EXPECT_EQ(w.notes.front().subject, "test:B");
  EXPECT_NE(w.notes.front().detail.find("no record of it yet"), std::string::npos) << w.notes.front().detail;
  const auto alerting = std::find_if(w.notes.begin(), w.notes.end(),
                                     [](const PairNote& n) { return n.stage == PairStage::Alerting; });
  ASSERT_NE(alerting, w.notes.end());
  ASSERT_FALSE(w.events.empty());
  EXPECT_EQ(alerting->t, w.events.front().t);
  EXPECT_NE(alerting->detail.find("t_los"), std::string::npos) << alerting->detail;
}

TEST(PairWatch, NotesADivergingPairClearWithItsFigures) {
  std::vector<Flight> pair = head_on();
  pair[0].trk_deg = 270.0;  // A turns its back on B
  pair[1].trk_deg = 90.0;
  const Watched w = watch_pair(pair);
  ASSERT_FALSE(w.notes.empty());
  EXPECT_EQ(w.notes.back().stage, PairStage::ProbeClear);
  EXPECT_NE(w.notes.back().detail.find("no horizontal loss"), std::string::npos) << w.notes.back().detail;
  EXPECT_TRUE(w.events.empty());
}

TEST(PairWatch, NotesTheRuleThatKeepsAConflictFromAlerting) {
  // Below the lower limit: A's altitude is the evidence.
  Watched low = watch_pair(head_on(1000.0, 1000.0));
  ASSERT_FALSE(low.notes.empty());
  EXPECT_EQ(low.notes.back().stage, PairStage::Excluded);
  EXPECT_NE(low.notes.back().detail.find("below_lower_limit"), std::string::npos) << low.notes.back().detail;
  EXPECT_NE(low.notes.back().detail.find("1000 ft"), std::string::npos) << low.notes.back().detail;

  // One address on both tracks: one aircraft, whatever the geometry.
  std::vector<Flight> twins = head_on();
  for (Flight& f : twins) f.edit = [](TrackReport& r) { r.address = 0x3C6586; };
  const Watched same = watch_pair(twins);
  EXPECT_EQ(same.notes.back().stage, PairStage::SameAddress);
  EXPECT_NE(same.notes.back().detail.find("3C6586"), std::string::npos) << same.notes.back().detail;
  EXPECT_TRUE(same.events.empty());
}

TEST(PairWatch, ChangesNoAlert) {
  std::vector<AlertEvent> unwatched;
  Pipeline pipeline;
  pipeline.set_alert_sink([&](const AlertEvent& e) { unwatched.push_back(e); });
  const std::vector<Flight> flights = head_on();
  for (double t = kT0; t <= kT0 + 60.0; t += 4.0)
    for (const Flight& f : flights) pipeline.process(f.at(t));
  const Watched watched = watch_pair(flights);
  ASSERT_EQ(watched.events.size(), unwatched.size());
  for (std::size_t i = 0; i < unwatched.size(); ++i) {
    EXPECT_EQ(watched.events[i].id, unwatched[i].id);
    EXPECT_EQ(watched.events[i].t, unwatched[i].t);
  }
}

TEST(PairWatch, NeedsOneRecordPerBatch) {
  PairWatch watch;
  PipelineConfig config;
  config.batch_records = 512;
  Pipeline batched(config);
  EXPECT_THROW(batched.set_pair_observer(&watch), std::invalid_argument);
  Pipeline single;
  EXPECT_NO_THROW(single.set_pair_observer(&watch));
}

}  // namespace
}  // namespace kew
