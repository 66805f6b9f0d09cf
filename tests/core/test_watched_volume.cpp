// What the area proximity warning knows of a volume besides its shape (design §4.11):
// its weekly schedule, read as AIP schedules are written, and the traffic it concerns.
#include <gtest/gtest.h>

#include "kew/volume/watched_volume.hpp"

namespace kew::volume {
namespace {

// 2024-05-06 was a Monday; its midnight, UTC.
constexpr double kMonday = 1714953600.0;
constexpr double kHour = 3600.0;
constexpr double kDay = 86400.0;

WeeklySchedule parse(std::vector<std::string> entries) {
  std::string error;
  const auto schedule = WeeklySchedule::parse(entries, error);
  EXPECT_TRUE(schedule) << error;
  return schedule.value_or(WeeklySchedule());
}

TEST(WeeklySchedule, WithoutWindowsAlwaysActive) {
  const WeeklySchedule always;
  EXPECT_TRUE(always.always());
  EXPECT_TRUE(always.active_at(kMonday + 3 * kHour));
}

TEST(WeeklySchedule, WorkingDaysAndHours) {
  const WeeklySchedule s = parse({"Mon-Fri 0600-1800"});
  struct Case {
    double t;
    bool active;
  };
  for (const Case c : {Case{kMonday + 5.99 * kHour, false}, Case{kMonday + 6 * kHour, true},
                       Case{kMonday + 17.99 * kHour, true}, Case{kMonday + 18 * kHour, false},
                       Case{kMonday + 4 * kDay + 12 * kHour, true},   // Friday
                       Case{kMonday + 5 * kDay + 12 * kHour, false},  // Saturday
                       Case{kMonday - kDay + 12 * kHour, false}})     // Sunday before
    EXPECT_EQ(s.active_at(c.t), c.active) << (c.t - kMonday) / kHour << " h after Monday 00:00";
}

TEST(WeeklySchedule, OvernightListsAndWrappingRanges) {
  const WeeklySchedule night = parse({"Sat,Sun 22:00-02:00"});
  EXPECT_TRUE(night.active_at(kMonday - 2 * kHour));        // Sunday 22:00
  EXPECT_TRUE(night.active_at(kMonday + 1.5 * kHour));      // Monday 01:30, Sunday's night
  EXPECT_FALSE(night.active_at(kMonday + 2 * kHour));       // Monday 02:00
  EXPECT_FALSE(night.active_at(kMonday + 22.5 * kHour));    // Monday night
  const WeeklySchedule weekend = parse({"Sat-Mon 0000-2400"});
  EXPECT_TRUE(weekend.active_at(kMonday + 23.9 * kHour));
  EXPECT_FALSE(weekend.active_at(kMonday + kDay + kHour));  // Tuesday
  EXPECT_TRUE(parse({"daily 1200-1300"}).active_at(kMonday + 3 * kDay + 12.5 * kHour));
}

TEST(WeeklySchedule, RefusesWhatItCannotRead) {
  for (const char* entry : {"Mon-Fri", "Moon 0600-1800", "Mon 0600", "Mon 06-18", "Mon 2500-0100", "Mon 0660-0700",
                            "Mon 2400-0100", "0600-1800"}) {
    std::string error;
    EXPECT_FALSE(WeeklySchedule::parse({entry}, error)) << entry;
    EXPECT_NE(error.find(entry), std::string::npos) << error;
  }
}

TEST(TrafficFilter, EveryoneOrTheListed) {
  TrafficFilter filter;
  EXPECT_TRUE(filter.concerns("3c6444", "DLH4AB", std::nullopt));
  filter.callsigns = {"DLH*"};
  filter.addresses = {"a1b2c3"};
  filter.squawks = {07000};
  EXPECT_TRUE(filter.concerns("3c6444", "dlh4ab", std::nullopt));
  EXPECT_TRUE(filter.concerns("A1B2C3", "", std::nullopt));
  EXPECT_TRUE(filter.concerns("000001", "N1", std::uint16_t{07000}));
  EXPECT_FALSE(filter.concerns("000001", "N1", std::uint16_t{01200}));
  EXPECT_FALSE(filter.concerns("000001", "", std::nullopt));
}

}  // namespace
}  // namespace kew::volume
