#pragma once
// A volume as the area proximity warning watches it (design §4.11): its area and band,
// what kind of airspace it is, when it is active, which traffic it concerns, how far
// ahead it looks and how early it warns; or a circle that follows one aircraft.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kew/util/name_table.hpp"
#include "kew/volume/volume.hpp"

namespace kew::volume {

enum class VolumeKind : std::uint8_t { Restricted, Danger, Prohibited, Watch };
inline constexpr util::NameTable<VolumeKind, 4> kVolumeKindNames({{
    {VolumeKind::Restricted, "restricted"},
    {VolumeKind::Danger, "danger"},
    {VolumeKind::Prohibited, "prohibited"},
    {VolumeKind::Watch, "watch"},
}});

/// One weekly window of activity, UTC: on the days of `days` (bit 0 Monday … bit 6
/// Sunday) from `start_min` to `end_min` (minutes after midnight, 0–1440); an end at or
/// before the start runs past midnight into the next day.
struct WeeklyWindow {
  std::uint8_t days = 0x7f;
  int start_min = 0;
  int end_min = 1440;
};

/// When a volume is active: always (no window), or within any of its windows.
class WeeklySchedule {
 public:
  /// Always active.
  WeeklySchedule() = default;
  /// Windows written as AIP schedules are, one per entry: "Mon-Fri 0600-1800",
  /// "Sat,Sun 08:00-12:00", "daily 2200-0600" (days: Mon … Sun, ranges and lists;
  /// "daily"; times HHMM or HH:MM, UTC, 2400 allowed as an end). nullopt, with `error`
  /// naming the entry and what is wrong, when one cannot be read.
  static std::optional<WeeklySchedule> parse(const std::vector<std::string>& entries, std::string& error);

  /// Active at `utc_s` (Unix seconds, UTC).
  bool active_at(double utc_s) const;
  bool always() const { return windows_.empty(); }
  const std::vector<WeeklyWindow>& windows() const { return windows_; }

 private:
  std::vector<WeeklyWindow> windows_;
};

/// Which traffic a volume concerns: every aircraft (all lists empty), or those whose
/// callsign matches one of `callsigns`, whose track id (ICAO address) matches one of
/// `addresses` (patterns: '*', '?', no case) or whose Mode 3/A code is one of `squawks`.
struct TrafficFilter {
  std::vector<std::string> callsigns;
  std::vector<std::string> addresses;
  std::vector<std::uint16_t> squawks;

  bool everyone() const { return callsigns.empty() && addresses.empty() && squawks.empty(); }
  /// `squawk` nullopt when unknown.
  bool concerns(std::string_view id, std::string_view callsign, std::optional<std::uint16_t> squawk) const;
};

struct WatchedVolume {
  std::string name;  ///< unique; named in every alert about it
  VolumeKind kind = VolumeKind::Watch;
  /// The area and band of a fixed volume; absent for one that follows an aircraft.
  std::optional<Volume> area;
  /// A volume that follows an aircraft: the track whose id or callsign matches this
  /// (no case) is its centre while it is seen; "" for a fixed volume.
  std::string follow;
  double follow_radius_m = 0.0;  ///< the followed circle's radius (m, > 0)
  /// The followed circle's band, relative to the followed aircraft's altitude (ft):
  /// [alt + floor_ft, alt + ceiling_ft].
  VerticalBand follow_band;
  WeeklySchedule schedule;
  TrafficFilter traffic;
  double lookahead_s = 120.0;  ///< how far ahead paths are followed (s, > 0)
  double warning_s = 60.0;     ///< an entry within this is alerted (s, 0 < warning ≤ look-ahead)
};

}  // namespace kew::volume
