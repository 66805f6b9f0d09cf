#pragma once
// One zone's engine (design §4.9): its plane, the kinetic Delaunay triangulation of its
// members (the tracks within its margin), the candidate search over it, and what the
// probe reads of each member in this plane. The track table stays one, in the Pipeline;
// a zone knows its members by slot, and maps each to its engine point itself. One caller
// at a time; different zones may be worked on by different threads (design §3.3).

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "kew/geo/projection.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/probe/proximity_search.hpp"
#include "kew/region/region_map.hpp"
#include "kew/util/indexed_heap.hpp"
#include "kew/zone/zone_tiling.hpp"

namespace kew::zone {

using TrackSlot = std::uint32_t;  // track::TrackSlot
inline constexpr TrackSlot kNoSlot = ~TrackSlot{0};

/// What the probe reads of one member, in the zone's plane, by engine point (so that
/// renumbering the points orders it too), packed for the candidate loop: the probe reads
/// a hundred of these, scattered, per update. Two cache lines.
struct alignas(64) ProbeState {
  probe::Kinematics kinematics;  ///< in this zone's plane at time t
  double t = 0.0;                ///< data time of the track's last record (UTC s)
  double scale = 1.0;            ///< this plane's point scale at the position
  double level_off_until_t = 0.0;  ///< the selected altitude's age limit (UTC s)
  double lat_deg = 0.0, lon_deg = 0.0;  ///< the last reported position (owner of a pair)
  std::size_t region = region::RegionMap::kNone;
  TrackSlot slot = kNoSlot;       ///< the track it belongs to
  probe::Kinematics at(double at_t) const {
    probe::Kinematics k = kinematics;
    if (at_t > level_off_until_t) k.level_off_m = std::numeric_limits<double>::quiet_NaN();
    return probe::extrapolated(k, at_t - t);
  }
};
static_assert(sizeof(ProbeState) == 128, "two cache lines");

/// Work done in one zone, for statistics and /metrics.
struct ZoneStatistics {
  std::uint64_t updates = 0;  ///< member updates applied (insert or move)
  std::uint64_t probes = 0;   ///< candidate searches run
  double busy_s = 0.0;        ///< wall time spent on its updates and probes (s)
};

class Zone {
 public:
  /// `engine_now`: the kinetic engine's start time (engine seconds, design §4.1).
  Zone(ZoneKey key, std::string name, const geo::Projection& projection, const kinetic::KineticConfig& config,
       double engine_now);

  ZoneKey key() const { return key_; }
  const std::string& name() const { return name_; }
  const geo::Projection& projection() const { return projection_; }

  /// Inserts slot's track at `now_k` (this plane, at engine time t) when it is not a
  /// member, else moves its point (velocity-only or reinsertion, as the engine decides);
  /// returns the point. The caller then fills state(point).
  kinetic::PointId place(TrackSlot slot, double engine_t, const probe::Kinematics& now_k);
  /// Removes a member at engine time t (nothing when it is not one).
  void remove(TrackSlot slot, double engine_t);
  /// The member's point, kNoPoint when the track is not a member.
  kinetic::PointId point_of(TrackSlot slot) const {
    const auto it = point_of_slot_.find(slot);
    return it == point_of_slot_.end() ? kinetic::kNoPoint : it->second;
  }
  /// Executes kinetic events up to engine time t.
  void advance(double engine_t) { engine_->advance(engine_t); }

  ProbeState& state(kinetic::PointId point) { return states_[point]; }
  const ProbeState& state(kinetic::PointId point) const { return states_[point]; }
  std::vector<ProbeState>& states() { return states_; }
  /// The member's slot, kNoSlot for a free point.
  TrackSlot slot_of(kinetic::PointId point) const { return slot_of_point_[point]; }
  kinetic::PointId point_end() const { return static_cast<kinetic::PointId>(slot_of_point_.size()); }
  std::size_t members() const { return engine_->size(); }
  /// The largest plane speed of a member (m/s), 0 without members.
  double fastest_mps() const { return speeds_.empty() ? 0.0 : speeds_.top_key(); }

  kinetic::KineticDelaunay& engine() { return *engine_; }
  const kinetic::KineticDelaunay& engine() const { return *engine_; }
  probe::ProximitySearch& search() { return search_; }

  /// Rebuilds the engine at engine time t (data time `at`) with the members inserted
  /// along a Hilbert curve, each at its last report extrapolated to `at`, and moves
  /// their probe states with them (design §8.3.1).
  void renumber(double engine_t, double at);

  ZoneStatistics& statistics() { return statistics_; }
  const ZoneStatistics& statistics() const { return statistics_; }
  /// Kinetic counters summed over every engine this zone had (renumbering rebuilds it).
  const kinetic::KineticStatistics& kinetic_statistics() const { return engine_->statistics(); }

 private:
  ZoneKey key_;
  std::string name_;
  geo::Projection projection_;
  kinetic::KineticConfig config_;
  // Optional only so that renumbering can build a fresh engine.
  std::optional<kinetic::KineticDelaunay> engine_;
  probe::ProximitySearch search_;
  util::IndexedHeap<std::greater<double>> speeds_;  // plane speed of every member, by point
  std::vector<ProbeState> states_;                  // by point
  std::vector<TrackSlot> slot_of_point_;            // kNoSlot: a free point
  std::unordered_map<TrackSlot, kinetic::PointId> point_of_slot_;
  ZoneStatistics statistics_;
};

}  // namespace kew::zone
