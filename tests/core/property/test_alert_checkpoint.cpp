// A checkpoint of the alert manager (design §5.9): saved at any step of a random run and
// restored into a fresh manager, the run goes on event for event as it would have without
// it, and the restored manager's own checkpoint is the same bytes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kew/alert/alert_manager.hpp"

namespace kew::alert {
namespace {

constexpr Slot kSlots = 6;

enum class Kind { Evaluate, Drop, AcknowledgeAll, AcknowledgeOne, Forget };

struct Step {
  Kind kind = Kind::Evaluate;
  Slot p = 0, q = 1;
  double t = 0.0;
  Evaluation evaluation;
  double figure = 0.0;  // the parties' positions, moved by the step
  std::size_t pick = 0;  // which active alert an acknowledgement or a forget names
};

struct Figures {
  Severity severity = Severity::Caution;
  double t_los_s = 60.0, cpa_h_m = 1000.0, cpa_v_ft = 300.0;
  double t = 1.7e9;  // of the last evaluation
};

std::vector<Step> random_run(std::uint32_t seed, std::size_t steps) {
  std::mt19937 rng(seed);
  std::vector<Figures> figures(kSlots * kSlots);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Step> run;
  double t = 1.7e9;
  for (std::size_t i = 0; i < steps; ++i) {
    if (!run.empty() && run.back().kind == Kind::Evaluate && unit(rng) < 0.3) {
      run.push_back(run.back());  // the other party's record of the same scan: one look
      continue;
    }
    Step s;
    const double dt = std::floor(unit(rng) * 2.0);  // several evaluations often share a data time
    t += dt;
    s.t = t;
    const double roll = unit(rng);
    s.kind = roll < 0.03 ? Kind::Drop : roll < 0.05 ? Kind::AcknowledgeAll : roll < 0.07 ? Kind::AcknowledgeOne
             : roll < 0.08 ? Kind::Forget : Kind::Evaluate;
    s.p = static_cast<Slot>(unit(rng) * kSlots);
    s.q = static_cast<Slot>(unit(rng) * (kSlots - 1));
    if (s.q >= s.p) ++s.q;
    s.pick = static_cast<std::size_t>(unit(rng) * 8);
    s.figure = unit(rng);
    // Each pair's figures drift by less than the update thresholds most of the time, so
    // that whether an event is re-emitted rests on every figure the manager keeps.
    Figures& f = figures[s.p < s.q ? s.p * kSlots + s.q : s.q * kSlots + s.p];
    if (unit(rng) < 0.1) f.severity = static_cast<Severity>(1 + static_cast<int>(unit(rng) * 3));
    f.t_los_s = std::max(0.0, f.t_los_s - (t - f.t) + std::floor(unit(rng) * 5.0) - 2.0);
    if (f.t_los_s == 0.0 && unit(rng) < 0.2) f.t_los_s = 90.0;  // another encounter
    f.t = t;
    f.cpa_h_m = std::max(0.0, f.cpa_h_m + std::floor(unit(rng) * 161.0) - 80.0);
    f.cpa_v_ft = std::max(0.0, f.cpa_v_ft + std::floor(unit(rng) * 81.0) - 40.0);
    Evaluation& e = s.evaluation;
    e.in_conflict = unit(rng) < 0.6;
    e.severity = e.in_conflict ? f.severity : Severity::None;
    e.t_los_s = f.t_los_s;
    e.cpa_h_m = f.cpa_h_m;
    e.cpa_v_ft = f.cpa_v_ft;
    if (unit(rng) < 0.2) e.observed_t = t - std::floor(unit(rng) * 3.0);
    if (unit(rng) < 0.1) e.confirm = 1 + static_cast<int>(unit(rng) * 3);
    if (unit(rng) < 0.1) e.clear = 1 + static_cast<int>(unit(rng) * 4);
    run.push_back(s);
  }
  return run;
}

// Names that do not sort like the slots, so the lower slot is sometimes party b.
std::string name_of(Slot slot) { return "T" + std::to_string(slot * 7 % 10) + std::to_string(slot); }

AlertManager make_manager() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (Slot s = 0; s < kSlots; ++s) v.push_back(name_of(s));
    return v;
  }();
  AlertConfig config;
  config.confirm = 2;
  config.clear = 3;
  return AlertManager(config, [](Slot slot) { return PartyName{"s", names.at(slot)}; });
}

void apply(AlertManager& manager, const Step& s, std::vector<AlertEvent>& out, std::vector<std::string>& acks) {
  switch (s.kind) {
    case Kind::Drop:
      manager.drop_track(s.p, s.t, out);
      return;
    case Kind::AcknowledgeAll:
      for (std::string& id : manager.acknowledge_all()) acks.push_back(std::move(id));
      return;
    case Kind::AcknowledgeOne:
    case Kind::Forget: {
      const std::vector<AlertEvent> open = manager.snapshot();
      if (open.empty()) return;
      const std::string& id = open[s.pick % open.size()].id;
      if (s.kind == Kind::Forget) {
        acks.push_back("forgot " + id + (manager.forget(id) ? "" : " (no)"));
      } else {
        for (std::string& acked : manager.acknowledge(id)) acks.push_back(std::move(acked));
      }
      return;
    }
    case Kind::Evaluate:
      manager.evaluate(
          s.p, s.q, s.evaluation, s.t,
          [&](AlertEvent& event) {
            const Slot a = name_of(s.p) < name_of(s.q) ? s.p : s.q, b = a == s.p ? s.q : s.p;
            for (auto [party, slot] : {std::pair{&event.a, a}, std::pair{&event.b, b}}) {
              party->source = "s";
              party->id = name_of(slot);
              party->callsign = "CS" + std::to_string(slot);
              party->track_number = static_cast<std::uint16_t>(slot + 1);
              party->lat_deg = 47.0 + slot * 0.01 + s.figure * 0.001;
              party->lon_deg = 8.0 - slot * 0.01;
              party->alt_ft = 30000.0 + slot * 100.0 * s.figure;
              party->gs_kt = 420.0 + s.figure;
              party->trk_deg = 359.0 * s.figure;
              party->vr_fpm = -s.figure * 1000.0;
            }
            event.severity = s.evaluation.severity;
            event.t_los_s = s.evaluation.t_los_s;
            event.t_cpa_s = s.evaluation.t_los_s + 10.0;
            event.cpa_h_m = s.evaluation.cpa_h_m;
            event.cpa_v_ft = s.evaluation.cpa_v_ft;
            event.sep_h_m = s.evaluation.cpa_h_m + 1000.0 * s.figure;
            event.sep_v_ft = s.evaluation.cpa_v_ft + 100.0;
            event.hypothesis = s.figure < 0.5 ? Hypothesis::Linear : Hypothesis::Turn;
            event.region = s.figure < 0.3 ? "" : "TMA";
          },
          out);
      return;
  }
}

std::string describe(const AlertEvent& e) {
  const auto party = [](const AlertParty& p) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "%s/%s %s #%u %a %a %a %a %a %a", p.source.c_str(), p.id.c_str(),
                  p.callsign.c_str(), p.track_number, p.lat_deg, p.lon_deg, p.alt_ft, p.gs_kt, p.trk_deg, p.vr_fpm);
    return std::string(buffer);
  };
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%s n%u seq%llu %d %d %d t%a o%a los%a cpa%a %a %a sep%a %a h%d %s ack%d",
                e.id.c_str(), e.number, static_cast<unsigned long long>(e.seq), static_cast<int>(e.state),
                static_cast<int>(e.end_reason), static_cast<int>(e.severity), e.t, e.opened_t, e.t_los_s, e.t_cpa_s,
                e.cpa_h_m, e.cpa_v_ft, e.sep_h_m, e.sep_v_ft, static_cast<int>(e.hypothesis), e.region.c_str(),
                e.acknowledged ? 1 : 0);
  return std::string(buffer) + " | " + party(e.a) + " | " + party(e.b);
}

std::vector<std::string> described(const std::vector<AlertEvent>& events) {
  std::vector<std::string> out;
  for (const AlertEvent& e : events) out.push_back(describe(e));
  return out;
}

TEST(AlertCheckpoint, ARestoredManagerContinuesEventForEventAtAnyStep) {
  std::size_t alerts_open_at_checkpoints = 0;
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    const std::vector<Step> run = random_run(seed, 400);
    AlertManager whole = make_manager();
    std::vector<AlertEvent> expected;
    std::vector<std::string> expected_acks;
    for (const Step& s : run) apply(whole, s, expected, expected_acks);

    const std::size_t cut = (seed * 37) % run.size();
    AlertManager before = make_manager();
    std::vector<AlertEvent> events;
    std::vector<std::string> acks;
    for (std::size_t i = 0; i < cut; ++i) apply(before, run[i], events, acks);
    alerts_open_at_checkpoints += before.active_count();
    util::CheckpointWriter saved;
    before.save(saved);

    AlertManager after = make_manager();
    util::CheckpointReader reader(saved.bytes());
    after.restore(reader);
    ASSERT_TRUE(reader.at_end()) << "seed " << seed;
    util::CheckpointWriter again;
    after.save(again);
    ASSERT_EQ(again.bytes(), saved.bytes()) << "seed " << seed << ": restored, the same state";
    ASSERT_EQ(described(after.snapshot()), described(before.snapshot())) << "seed " << seed;

    for (std::size_t i = cut; i < run.size(); ++i) apply(after, run[i], events, acks);
    ASSERT_EQ(described(events), described(expected)) << "seed " << seed << ", checkpoint at step " << cut;
    ASSERT_EQ(acks, expected_acks) << "seed " << seed;
    EXPECT_EQ(after.counters().opened, whole.counters().opened);
    EXPECT_EQ(after.counters().ended, whole.counters().ended);
    EXPECT_EQ(after.next_number(), whole.next_number());
  }
  EXPECT_GT(alerts_open_at_checkpoints, 60u) << "the checkpoints must catch alerts open";
}

TEST(AlertCheckpoint, EveryTruncationIsRefusedAndLeavesTheManagerEmpty) {
  AlertManager manager = make_manager();
  std::vector<AlertEvent> events;
  std::vector<std::string> acks;
  for (const Step& s : random_run(7, 200)) apply(manager, s, events, acks);
  ASSERT_GT(manager.active_count(), 0u);
  util::CheckpointWriter saved;
  manager.save(saved);
  const std::string& bytes = saved.bytes();
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    AlertManager restored = make_manager();
    restored.resume(5, 9);
    util::CheckpointReader reader(std::string_view(bytes).substr(0, size));
    EXPECT_THROW(restored.restore(reader), util::CheckpointError) << "cut at " << size;
    EXPECT_EQ(restored.active_count(), 0u);
    EXPECT_EQ(restored.last_seq(), 0u);
    EXPECT_EQ(restored.next_number(), 1u);
  }
}

}  // namespace
}  // namespace kew::alert
