// Notifications (design §5.10): what each alert event is to a notifier, the outbox that
// loses nothing across a restart and sends nothing twice, the bodies of each template.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <simdjson.h>

#include "delivery_progress.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "message_template.hpp"
#include "notify_filter.hpp"
#include "outbox.hpp"
#include "kew/util/wildcard.hpp"

namespace kew::daemon {
namespace {

AlertEvent event(std::uint64_t seq, std::string id, AlertState state, Severity severity) {
  AlertEvent e;
  e.seq = seq;
  e.id = std::move(id);
  e.number = 7;
  e.state = state;
  e.severity = severity;
  e.end_reason = state == AlertState::End ? AlertEndReason::Cleared : AlertEndReason::None;
  e.t = 1'700'000'100.0;
  e.opened_t = 1'700'000'000.0;
  e.a = {"3c6444", "adsb", "DLH4AB", 1, 48.1, 11.5, 5000, 250, 90, 0};
  e.b = {"a1b2c3", "adsb", "", 2, 48.11, 11.52, 5300, 140, 270, -500};
  e.t_los_s = severity == Severity::Loss ? 0.0 : 45.0;
  e.t_cpa_s = 60;
  e.cpa_h_m = 740.8;
  e.cpa_v_ft = 100;
  e.sep_h_m = 5556;
  e.sep_v_ft = 300;
  e.region = "EDDM";
  return e;
}

/// An area proximity warning (design §4.11): DLH4AB and volume EDR-114, b empty, no
/// pair figures, no region.
AlertEvent area_event(std::uint64_t seq, std::string id, AlertState state, Severity severity) {
  AlertEvent e = event(seq, std::move(id), state, severity);
  e.kind = AlertKind::Apw;
  e.b = {};
  e.t_los_s = severity == Severity::Loss ? 0.0 : 40.0;
  e.t_cpa_s = e.cpa_h_m = e.cpa_v_ft = e.sep_h_m = e.sep_v_ft = 0.0;
  e.region.clear();
  e.volume = "EDR-114";
  e.volume_kind = "restricted";
  return e;
}

std::string line_of(const AlertEvent& e) {
  std::string out;
  protocol::append_alert_json(out, e, e.seq);
  return out;
}

NotifyConfig config(NotifyTemplate format) {
  NotifyConfig c;
  c.name = "t";
  c.url = "http://127.0.0.1/";
  c.format = format;
  c.states = {NotifyState::New, NotifyState::Escalated, NotifyState::Updated, NotifyState::Ended};
  return c;
}

TEST(Wildcard, MatchesWithoutCase) {
  struct Case {
    const char* pattern;
    const char* text;
    bool match;
  };
  for (const Case& c : std::initializer_list<Case>{{"DLH*", "DLH4AB", true},
                                                  {"dlh*", "DLH4AB", true},
                                                  {"DLH*", "BAW12", false},
                                                  {"N9?7LP", "N907LP", true},
                                                  {"N9?7LP", "N97LP", false},
                                                  {"*7LP", "N907LP", true},
                                                  {"*", "", true},
                                                  {"a*b*c", "aXbYbc", true},
                                                  {"a*b*c", "aXbYb", false},
                                                  {"3c6444", "3C6444", true}})
    EXPECT_EQ(util::matches_wildcard(c.pattern, c.text), c.match) << c.pattern << " ~ " << c.text;
}

TEST(NotifyFilter, FollowsEachAlertsSeverity) {
  NotifyConfig c = config(NotifyTemplate::Json);
  c.min_severity = Severity::Warning;
  NotifyFilter filter(c);
  // Opened below the threshold: nothing; reaching it is an escalation.
  EXPECT_EQ(filter.classify(event(1, "x", AlertState::New, Severity::Caution)), std::nullopt);
  EXPECT_EQ(filter.classify(event(2, "x", AlertState::Update, Severity::Warning)), NotifyState::Escalated);
  EXPECT_EQ(filter.classify(event(3, "x", AlertState::Update, Severity::Warning)), NotifyState::Updated);
  EXPECT_EQ(filter.classify(event(4, "x", AlertState::Update, Severity::Loss)), NotifyState::Escalated);
  // Down and up again to a severity it had: no new escalation.
  EXPECT_EQ(filter.classify(event(5, "x", AlertState::Update, Severity::Warning)), NotifyState::Updated);
  EXPECT_EQ(filter.classify(event(6, "x", AlertState::Update, Severity::Loss)), NotifyState::Updated);
  EXPECT_EQ(filter.classify(event(7, "x", AlertState::End, Severity::Loss)), NotifyState::Ended);
  // An alert never announced ends unheard.
  EXPECT_EQ(filter.classify(event(8, "y", AlertState::New, Severity::Caution)), std::nullopt);
  EXPECT_EQ(filter.classify(event(9, "y", AlertState::End, Severity::Caution)), std::nullopt);
  // One not seen open in this run (a restart) is ended when it would have been told.
  EXPECT_EQ(filter.classify(event(10, "z", AlertState::End, Severity::Warning)), NotifyState::Ended);
  EXPECT_EQ(filter.classify(event(11, "w", AlertState::New, Severity::Loss)), NotifyState::New);
}

TEST(NotifyFilter, StatesRegionsCallsignsAndAddresses) {
  NotifyConfig c = config(NotifyTemplate::Ntfy);
  c.states = {NotifyState::Escalated, NotifyState::Ended};
  NotifyFilter filter(c);
  // New not wanted; the first update at the same severity is not an escalation.
  EXPECT_EQ(filter.classify(event(1, "x", AlertState::New, Severity::Warning)), std::nullopt);
  EXPECT_EQ(filter.classify(event(2, "x", AlertState::Update, Severity::Warning)), std::nullopt);
  EXPECT_EQ(filter.classify(event(3, "x", AlertState::Update, Severity::Loss)), NotifyState::Escalated);
  EXPECT_EQ(filter.classify(event(4, "x", AlertState::End, Severity::Loss)), NotifyState::Ended);

  NotifyConfig regional = config(NotifyTemplate::Json);
  regional.regions = {"EDDF"};
  EXPECT_EQ(NotifyFilter(regional).classify(event(1, "x", AlertState::New, Severity::Loss)), std::nullopt);
  regional.regions = {"EDDM"};
  EXPECT_EQ(NotifyFilter(regional).classify(event(1, "x", AlertState::New, Severity::Loss)), NotifyState::New);

  NotifyConfig parties = config(NotifyTemplate::Json);
  parties.callsigns = {"BAW*"};
  EXPECT_EQ(NotifyFilter(parties).classify(event(1, "x", AlertState::New, Severity::Loss)), std::nullopt);
  parties.callsigns = {"dlh*"};
  EXPECT_EQ(NotifyFilter(parties).classify(event(1, "x", AlertState::New, Severity::Loss)), NotifyState::New);
  parties.callsigns.clear();
  parties.addresses = {"A1B2C3"};  // party b, which has no callsign
  EXPECT_EQ(NotifyFilter(parties).classify(event(1, "x", AlertState::New, Severity::Loss)), NotifyState::New);
}

TEST(NotifyFilter, KindsAndVolumes) {
  const AlertEvent conflict = event(1, "x", AlertState::New, Severity::Warning);
  const AlertEvent area = area_event(1, "v", AlertState::New, Severity::Warning);
  NotifyConfig c = config(NotifyTemplate::Json);
  EXPECT_EQ(NotifyFilter(c).classify(area), NotifyState::New) << "both kinds by default";
  c.kinds = {AlertKind::Stca};
  EXPECT_EQ(NotifyFilter(c).classify(area), std::nullopt);
  EXPECT_EQ(NotifyFilter(c).classify(conflict), NotifyState::New);
  c.kinds = {AlertKind::Apw};
  EXPECT_EQ(NotifyFilter(c).classify(conflict), std::nullopt);
  EXPECT_EQ(NotifyFilter(c).classify(area), NotifyState::New);

  // A person's own watch circle: its alerts and nothing else.
  NotifyConfig mine = config(NotifyTemplate::Ntfy);
  mine.volumes = {"edr-1*"};
  EXPECT_EQ(NotifyFilter(mine).classify(area), NotifyState::New);
  EXPECT_EQ(NotifyFilter(mine).classify(conflict), std::nullopt);
  AlertEvent elsewhere = area;
  elsewhere.volume = "EDP-7";
  EXPECT_EQ(NotifyFilter(mine).classify(elsewhere), std::nullopt);
  // Volumes, callsigns and addresses admit alike: any one match passes.
  mine.callsigns = {"DLH*"};
  EXPECT_EQ(NotifyFilter(mine).classify(elsewhere), NotifyState::New);
  EXPECT_EQ(NotifyFilter(mine).classify(conflict), NotifyState::New);

  // Regions judge pairs; an area warning has none and is not held back by them.
  NotifyConfig regional = config(NotifyTemplate::Json);
  regional.regions = {"EDDF"};
  EXPECT_EQ(NotifyFilter(regional).classify(conflict), std::nullopt);
  EXPECT_EQ(NotifyFilter(regional).classify(area), NotifyState::New);

  // The empty b of an area warning is nobody: a pattern matching any address matches a.
  NotifyConfig anyone = config(NotifyTemplate::Json);
  anyone.addresses = {"*"};
  AlertEvent unnamed = area;
  unnamed.a.id = "";
  EXPECT_EQ(NotifyFilter(anyone).classify(unnamed), std::nullopt);
}

TEST(DeliveryProgress, RoundTripsAndMerges) {
  DeliveryProgress p{10, {12, 15}};
  EXPECT_TRUE(p.covers(9));
  EXPECT_TRUE(p.covers(12));
  EXPECT_FALSE(p.covers(11));
  const auto back = DeliveryProgress::from_json(p.to_json());
  ASSERT_TRUE(back);
  EXPECT_EQ(back->through, 10u);
  EXPECT_EQ(back->also, (std::vector<std::uint64_t>{12, 15}));
  p.merge({11, {13}});
  EXPECT_EQ(p.through, 13u);
  EXPECT_EQ(p.also, std::vector<std::uint64_t>{15});
  EXPECT_FALSE(DeliveryProgress::from_json("{\"through\":\"x\"}"));
  EXPECT_FALSE(DeliveryProgress::from_json("not json"));
}

class OutboxFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("kew-outbox-" + std::to_string(::getpid()) + "-" +
                                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path() const { return (dir_ / "notify-t.outbox").string(); }
  static void add(Outbox& box, const AlertEvent& e, NotifyState state, double now = 0.0) {
    ASSERT_TRUE(box.add(e, state, line_of(e), now));
  }
  /// Delivers everything due at `now`, returning the first seq of each message.
  static std::vector<std::vector<std::uint64_t>> deliver_all(Outbox& box, double now, bool in_order) {
    std::vector<std::vector<std::uint64_t>> sent;
    double wake = 0;
    while (OutboxEntry* entry = box.next_due(now, wake, in_order)) {
      sent.push_back(entry->seqs);
      box.delivered(entry->seqs.front(), now);
    }
    return sent;
  }
  std::filesystem::path dir_;
};

TEST_F(OutboxFile, EveryEventInOrderAndNeverTwice) {
  Outbox box(path(), 100, 0.0);
  EXPECT_EQ(box.load(0.0), "");
  for (std::uint64_t seq = 1; seq <= 5; ++seq) add(box, event(seq, "x", AlertState::Update, Severity::Warning), NotifyState::Updated);
  EXPECT_FALSE(box.add(event(3, "x", AlertState::Update, Severity::Warning), NotifyState::Updated, "", 0.0));
  double wake = 0;
  OutboxEntry* first = box.next_due(0.0, wake, true);
  ASSERT_NE(first, nullptr);
  first->in_flight = true;
  EXPECT_EQ(box.next_due(0.0, wake, true), nullptr) << "in order: nothing passes the message in flight";
  box.returned(1);
  const auto sent = deliver_all(box, 0.0, true);
  ASSERT_EQ(sent.size(), 5u);
  for (std::uint64_t i = 0; i < 5; ++i) EXPECT_EQ(sent[i], std::vector<std::uint64_t>{i + 1});
  EXPECT_EQ(box.waiting_events(), 0u);
  EXPECT_EQ(box.progress().through, 5u);
}

TEST_F(OutboxFile, ARestartDeliversWhatWaitedAndNothingDelivered) {
  {
    Outbox box(path(), 100, 0.0);
    box.load(0.0);
    for (std::uint64_t seq = 1; seq <= 4; ++seq) add(box, event(seq, "x", AlertState::Update, Severity::Warning), NotifyState::Updated);
    double wake = 0;
    box.delivered(box.next_due(0.0, wake, true)->seqs.front(), 0.0);  // seq 1
    box.delivered(box.next_due(0.0, wake, true)->seqs.front(), 0.0);  // seq 2
    // No sync, no close: as after SIGKILL (the kernel has what was written).
  }
  {
    // A torn last line, as a crash in the middle of a write leaves.
    std::ofstream torn(path(), std::ios::app);
    torn << "E new {\"class\":\"ALE";
  }
  Outbox again(path(), 100, 0.0);
  const std::string said = again.load(0.0);
  EXPECT_NE(said.find("2 events waiting"), std::string::npos) << said;
  EXPECT_NE(said.find("1 unreadable"), std::string::npos) << said;
  EXPECT_FALSE(again.add(event(2, "x", AlertState::Update, Severity::Warning), NotifyState::Updated, "", 0.0));
  add(again, event(5, "x", AlertState::End, Severity::Warning), NotifyState::Ended);
  const auto sent = deliver_all(again, 0.0, true);
  EXPECT_EQ(sent, (std::vector<std::vector<std::uint64_t>>{{3}, {4}, {5}}));
  // The json body is the line as the stream wrote it, through the file.
  Outbox third(path(), 100, 0.0);
  third.load(0.0);
  EXPECT_EQ(third.waiting_events(), 0u);
  EXPECT_FALSE(third.add(event(5, "x", AlertState::End, Severity::Warning), NotifyState::Ended, "", 0.0));
}

TEST_F(OutboxFile, KeepsTheStreamsLineByteForByte) {
  const AlertEvent e = event(1, "x", AlertState::New, Severity::Loss);
  {
    Outbox box(path(), 100, 0.0);
    box.load(0.0);
    add(box, e, NotifyState::New);
  }
  Outbox again(path(), 100, 0.0);
  again.load(0.0);
  double wake = 0;
  OutboxEntry* entry = again.next_due(0.0, wake, true);
  ASSERT_NE(entry, nullptr);
  EXPECT_EQ(entry->lines.back(), line_of(e));
  EXPECT_EQ(render_message(config(NotifyTemplate::Json), *entry, "").body, line_of(e));
}

TEST_F(OutboxFile, AFullOutboxDropsTheOldestAndCountsIt) {
  Outbox box(path(), 3, 0.0);
  box.load(0.0);
  for (std::uint64_t seq = 1; seq <= 5; ++seq) add(box, event(seq, "x", AlertState::Update, Severity::Warning), NotifyState::Updated);
  EXPECT_EQ(box.waiting_events(), 3u);
  EXPECT_EQ(box.dropped(), 2u);
  EXPECT_EQ(box.take_new_drops(), 2u);
  EXPECT_EQ(box.take_new_drops(), 0u);
  EXPECT_EQ(deliver_all(box, 0.0, true), (std::vector<std::vector<std::uint64_t>>{{3}, {4}, {5}}));
}

TEST_F(OutboxFile, CoalescesAnAlertsBurstForPeople) {
  Outbox box(path(), 100, 30.0);
  box.load(0.0);
  add(box, event(1, "x", AlertState::New, Severity::Caution), NotifyState::New, 0.0);
  add(box, event(2, "y", AlertState::New, Severity::Warning), NotifyState::New, 0.0);
  add(box, event(3, "x", AlertState::Update, Severity::Warning), NotifyState::Escalated, 0.0);
  // Waiting together: one message for x's two events, in x's place in line.
  auto sent = deliver_all(box, 1.0, false);
  EXPECT_EQ(sent, (std::vector<std::vector<std::uint64_t>>{{1, 3}, {2}}));
  // After a message, the alert's next events wait coalesce_s and go as one.
  add(box, event(4, "x", AlertState::Update, Severity::Loss), NotifyState::Escalated, 2.0);
  add(box, event(5, "x", AlertState::End, Severity::Loss), NotifyState::Ended, 3.0);
  add(box, event(6, "z", AlertState::New, Severity::Loss), NotifyState::New, 3.0);
  double wake = 0;
  sent = deliver_all(box, 10.0, false);
  EXPECT_EQ(sent, (std::vector<std::vector<std::uint64_t>>{{6}}));
  EXPECT_EQ(box.next_due(10.0, wake, false), nullptr);
  EXPECT_DOUBLE_EQ(wake, 31.0);
  // Delivered above the first waiting event: the progress says so.
  const DeliveryProgress progress = box.progress();
  EXPECT_EQ(progress.through, 3u);
  EXPECT_EQ(progress.also, std::vector<std::uint64_t>{6});
  sent = deliver_all(box, 31.0, false);
  EXPECT_EQ(sent, (std::vector<std::vector<std::uint64_t>>{{4, 5}}));
  EXPECT_EQ(box.progress().through, 6u);
}

TEST_F(OutboxFile, ForgetsWhatTheOtherInstanceDelivered) {
  Outbox box(path(), 100, 0.0);
  box.load(0.0);
  for (std::uint64_t seq = 1; seq <= 6; ++seq) add(box, event(seq, "x", AlertState::Update, Severity::Warning), NotifyState::Updated);
  box.forget({3, {5}});
  EXPECT_EQ(box.waiting_events(), 2u);
  EXPECT_FALSE(box.add(event(5, "x", AlertState::Update, Severity::Warning), NotifyState::Updated, "", 0.0));
  EXPECT_EQ(deliver_all(box, 0.0, true), (std::vector<std::vector<std::uint64_t>>{{4}, {6}}));
  Outbox again(path(), 100, 0.0);
  again.load(0.0);
  EXPECT_EQ(again.waiting_events(), 0u);
}

TEST(MessageTemplate, NtfyTextAndHeaders) {
  OutboxEntry entry;
  const AlertEvent e = event(9, "abc", AlertState::New, Severity::Warning);
  entry.seqs = {9};
  entry.states = {NotifyState::New};
  entry.lines = {line_of(e)};
  entry.latest = e;
  entry.highest = e.severity;
  const NotifyMessage m = render_message(config(NotifyTemplate::Ntfy), entry, "tk_secret");
  EXPECT_NE(m.body.find("Loss of separation predicted in 45 s; 3.0 NM / 300 ft apart now."), std::string::npos) << m.body;
  EXPECT_NE(m.body.find("Closest in 1 min: 0.4 NM / 100 ft."), std::string::npos) << m.body;
  EXPECT_NE(m.body.find("DLH4AB (3c6444) 5000 ft"), std::string::npos) << m.body;
  EXPECT_NE(m.body.find("a1b2c3 5300 ft, 140 kt, track 270."), std::string::npos) << m.body;
  EXPECT_NE(m.body.find("region EDDM"), std::string::npos) << m.body;
  const auto has = [&](const std::string& header) {
    return std::find(m.headers.begin(), m.headers.end(), header) != m.headers.end();
  };
  EXPECT_TRUE(has("Title: kew: WARNING DLH4AB / a1b2c3"));
  EXPECT_TRUE(has("Priority: 4"));
  EXPECT_TRUE(has("Tags: warning"));
  EXPECT_TRUE(has("Authorization: Bearer tk_secret"));
  EXPECT_TRUE(has("Kew-Seq: 9"));
  EXPECT_TRUE(has("Kew-Alert: abc"));
}

TEST(MessageTemplate, ChatBodiesAreJsonWithTheText) {
  OutboxEntry entry;
  const AlertEvent opened = event(1, "abc", AlertState::New, Severity::Caution);
  const AlertEvent ended = event(4, "abc", AlertState::End, Severity::Loss);
  entry.seqs = {1, 4};
  entry.states = {NotifyState::New, NotifyState::Ended};
  entry.lines = {line_of(opened), line_of(ended)};
  entry.latest = ended;
  entry.highest = Severity::Loss;
  struct Case {
    NotifyTemplate format;
    const char* member;
  };
  for (const Case c : {Case{NotifyTemplate::Gotify, "message"}, Case{NotifyTemplate::Slack, "text"},
                       Case{NotifyTemplate::Mattermost, "text"}, Case{NotifyTemplate::Discord, "content"}}) {
    const NotifyMessage m = render_message(config(c.format), entry, c.format == NotifyTemplate::Gotify ? "gk" : "");
    simdjson::dom::parser parser;
    simdjson::dom::element doc;
    ASSERT_EQ(parser.parse(m.body).get(doc), simdjson::SUCCESS) << m.body;
    std::string_view text;
    ASSERT_EQ(doc[c.member].get(text), simdjson::SUCCESS) << m.body;
    EXPECT_NE(text.find("ended"), std::string_view::npos) << text;
    EXPECT_NE(text.find("Alert ended (cleared) after 1 min 40 s; highest severity loss."), std::string_view::npos)
        << text;
    EXPECT_NE(text.find("Events: new, ended."), std::string_view::npos) << text;
    if (c.format == NotifyTemplate::Gotify) {
      std::int64_t priority = 0;
      EXPECT_EQ(doc["priority"].get(priority), simdjson::SUCCESS);
      EXPECT_EQ(priority, 2);
      EXPECT_NE(std::find(m.headers.begin(), m.headers.end(), "X-Gotify-Key: gk"), m.headers.end());
    }
  }
}

OutboxEntry entry_of(std::initializer_list<std::pair<AlertEvent, NotifyState>> events) {
  OutboxEntry entry;
  for (const auto& [e, state] : events) {
    entry.seqs.push_back(e.seq);
    entry.states.push_back(state);
    entry.lines.push_back(line_of(e));
    entry.latest = e;
    entry.highest = std::max(entry.highest, e.severity);
  }
  return entry;
}

TEST(MessageTemplate, AreaWarningsInWords) {
  const OutboxEntry ahead = entry_of({{area_event(3, "v", AlertState::New, Severity::Warning), NotifyState::New}});
  EXPECT_EQ(message_title("kew", ahead), "kew: WARNING DLH4AB → EDR-114 (restricted)");
  const std::string text = message_text(ahead);
  EXPECT_EQ(text,
            "Enters restricted area EDR-114 in 40 s.\n"
            "DLH4AB (3c6444) 5000 ft, 250 kt, track 090.\n"
            "Alert 7 opened 22:13:20Z.");

  const OutboxEntry inside = entry_of({{area_event(3, "v", AlertState::New, Severity::Warning), NotifyState::New},
                                       {area_event(4, "v", AlertState::Update, Severity::Loss), NotifyState::Escalated}});
  EXPECT_EQ(message_title("kew", inside), "kew: LOSS DLH4AB → EDR-114 (restricted)");
  EXPECT_EQ(message_text(inside).rfind("Inside restricted area EDR-114 now.\n", 0), 0u) << message_text(inside);

  const OutboxEntry ended = entry_of({{area_event(5, "v", AlertState::End, Severity::Loss), NotifyState::Ended}});
  EXPECT_EQ(message_title("kew", ended), "kew: ended DLH4AB → EDR-114 (restricted)");
  EXPECT_EQ(message_text(ended).rfind("Area warning ended (cleared) after 1 min 40 s; highest severity loss.\n", 0), 0u)
      << message_text(ended);

  for (const OutboxEntry* entry : {&ahead, &inside, &ended}) {
    const std::string all = message_title("kew", *entry) + "\n" + message_text(*entry);
    for (const char* absent : {" / ", "Closest", "apart", "region", "\n (", "\n 0 ft"})
      EXPECT_EQ(all.find(absent), std::string::npos) << absent << " in\n" << all;
  }
}

TEST(MessageTemplate, EveryTemplateCarriesAnAreaWarning) {
  const AlertEvent e = area_event(3, "v", AlertState::New, Severity::Warning);
  const OutboxEntry entry = entry_of({{e, NotifyState::New}});
  const NotifyMessage json = render_message(config(NotifyTemplate::Json), entry, "");
  EXPECT_EQ(json.body, line_of(e));
  EXPECT_NE(json.body.find("\"kind\":\"apw\""), std::string::npos) << json.body;

  const NotifyMessage ntfy = render_message(config(NotifyTemplate::Ntfy), entry, "");
  EXPECT_EQ(ntfy.body, message_text(entry));
  EXPECT_NE(std::find(ntfy.headers.begin(), ntfy.headers.end(), "Title: kew: WARNING DLH4AB → EDR-114 (restricted)"),
            ntfy.headers.end());
  struct Case {
    NotifyTemplate format;
    const char* member;
  };
  for (const Case c : {Case{NotifyTemplate::Gotify, "message"}, Case{NotifyTemplate::Slack, "text"},
                       Case{NotifyTemplate::Mattermost, "text"}, Case{NotifyTemplate::Discord, "content"}}) {
    const NotifyMessage m = render_message(config(c.format), entry, "");
    simdjson::dom::parser parser;
    simdjson::dom::element doc;
    ASSERT_EQ(parser.parse(m.body).get(doc), simdjson::SUCCESS) << m.body;
    std::string_view text;
    ASSERT_EQ(doc[c.member].get(text), simdjson::SUCCESS) << m.body;
    EXPECT_NE(text.find("Enters restricted area EDR-114 in 40 s."), std::string_view::npos) << text;
    std::string_view title = text;
    if (c.format == NotifyTemplate::Gotify) {
      ASSERT_EQ(doc["title"].get(title), simdjson::SUCCESS) << m.body;
    }
    EXPECT_NE(title.find("WARNING DLH4AB → EDR-114 (restricted)"), std::string_view::npos) << m.body;
  }
}

}  // namespace
}  // namespace kew::daemon
