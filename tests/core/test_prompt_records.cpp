// PipelineConfig::prompt_records (design §3.3): after each flush() the first records are
// judged one by one, their events delivered from process() itself; the records after
// them wait for the batch.
#include "kew/pipeline/pipeline.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kew {
namespace {

constexpr double kT0 = 1714400000.0;
constexpr double kGs_kt = 400.0;
constexpr double kMetresPerDegree = 111195.0;  // of latitude, near enough for the test

// A flies north and B south at FL200 on the meridian 8° E, 40 km apart at kT0, closing
// at 800 kt: a loss within the look-ahead from the first update with a velocity.
TrackReport report(const std::string& id, double t) {
  const double closed_m = (t - kT0) * kGs_kt * 1852.0 / 3600.0;
  const double north_m = id == "A" ? -20000.0 + closed_m : 20000.0 - closed_m;
  TrackReport r;
  r.t = t;
  r.id = id;
  r.source = "prompt";
  r.lat_deg = 50.0 + north_m / kMetresPerDegree;
  r.lon_deg = 8.0;
  r.alt_ft = 20000.0;
  r.gs_kt = kGs_kt;
  r.trk_deg = id == "A" ? 0.0 : 180.0;
  r.vr_fpm = 0.0;
  return r;
}

struct Delivery {
  std::vector<std::size_t> events_after_process;  // events delivered so far, after each process()
  std::vector<bool> waiting_after_process;        // batch_waiting() after each process()
  std::vector<std::size_t> events_after_flush;    // after each read's flush()
};

// Reads of two records (A then B, one update period), each read flushed.
Delivery run(std::size_t prompt_records) {
  PipelineConfig config;
  config.batch_records = 512;
  config.prompt_records = prompt_records;
  Pipeline pipeline(config);
  Delivery out;
  std::size_t events = 0;
  pipeline.set_alert_sink([&](const AlertEvent&) { ++events; });
  for (int period = 0; period < 6; ++period) {
    for (const char* id : {"A", "B"}) {
      pipeline.process(report(id, kT0 + 4.0 * period));
      out.events_after_process.push_back(events);
      out.waiting_after_process.push_back(pipeline.batch_waiting());
    }
    pipeline.flush();
    out.events_after_flush.push_back(events);
  }
  return out;
}

TEST(PromptRecords, TheFirstRecordsAfterAFlushDeliverTheirEventsFromProcess) {
  const Delivery batched = run(0);
  const Delivery both = run(2);
  const Delivery first = run(1);
  ASSERT_GT(batched.events_after_flush.back(), 0u) << "the pair must alert";
  EXPECT_EQ(both.events_after_flush, batched.events_after_flush);
  EXPECT_EQ(first.events_after_flush, batched.events_after_flush);
  for (std::size_t i = 0; i < batched.waiting_after_process.size(); ++i) {
    SCOPED_TRACE("record " + std::to_string(i));
    const std::size_t read = i / 2;
    const std::size_t before_read = read == 0 ? 0 : batched.events_after_flush[read - 1];
    // Without prompt records every event waits for the read's flush.
    EXPECT_TRUE(batched.waiting_after_process[i]);
    EXPECT_EQ(batched.events_after_process[i], before_read);
    // With both records prompt, nothing waits: the read's events are out before its flush.
    EXPECT_FALSE(both.waiting_after_process[i]);
    if (i % 2 == 1) {
      EXPECT_EQ(both.events_after_process[i], both.events_after_flush[read]);
    }
    // With one, B (the second of each read) waits for the flush.
    EXPECT_EQ(first.waiting_after_process[i], i % 2 == 1);
  }
}

}  // namespace
}  // namespace kew
