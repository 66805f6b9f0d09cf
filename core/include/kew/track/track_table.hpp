#pragma once
// The table of live tracks (design §4.3): identity by source + id, per-track record
// ordering, plausibility of every record with counted reasons, velocity derived from the
// last two positions when a record has none, on-ground exclusion, and the timeout that
// drops silent tracks. It turns accepted records into plane kinematics; it never talks
// to the kinetic engine (the Pipeline does).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kew/geo/projection.hpp"
#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/track/track_index.hpp"
#include "kew/track/refusal.hpp"
#include "kew/track/track_report.hpp"
#include "kew/track/vertical_intent.hpp"
#include "kew/util/chunked_vector.hpp"
#include "kew/util/indexed_heap.hpp"
#include "kew/util/rejections.hpp"

namespace kew::track {

using TrackSlot = std::uint32_t;
inline constexpr TrackSlot kNoTrack = ~TrackSlot{0};

struct TrackTableConfig {
  double track_timeout_s = 30.0;          ///< drop a track this long after its last record (s, > 0)
  /// A reported ground speed above this is dropped from its record (counted in
  /// fields_dropped, the record kept); a velocity derived from positions above it is
  /// discarded and derived afresh from this record on (kt, > 0).
  double max_ground_speed_kt = 1200.0;
  double max_vertical_rate_fpm = 20000.0; ///< a reported |vertical rate| above this is dropped (ft/min)
  double min_altitude_ft = -2000.0;       ///< altitude range accepted (ft)
  double max_altitude_ft = 100000.0;
  bool exclude_on_ground = true;          ///< on-ground targets are not tracked (design §4.3)
  std::size_t max_tracks = 200000;        ///< bound on live + pending tracks (security)
  std::size_t max_id_bytes = 64;          ///< longer ids or sources are rejected
  /// Records older than the pipeline clock by more than this are rejected as too late
  /// (s, ≥ 0); later ones are extrapolated to the clock with their own velocity.
  double max_lateness_s = 10.0;
  /// A record more than this ahead of the pipeline clock (s, ≥ 0) does not move it at
  /// once: it is held until kTimeJumpConfirm records confirm the jump, and refused
  /// ("future_time") when a later record would have been too late after it (design
  /// §4.1). At most max_lateness_s, one record can never make the others too late.
  double max_time_jump_s = 10.0;
  /// Velocity is derived from the previous position only when it is at most this old (s).
  double max_derivation_gap_s = 60.0;
  /// When a selected altitude stops the vertical prediction (design §4.4).
  IntentConfig intent;
};

/// A rate of turn is derived from track angles at least this far apart in time (s) ...
inline constexpr double kTurnRateBaseline_s = 3.0;
/// ... and at most this far (s): older angles say nothing of the present turn.
inline constexpr double kTurnRateMaxBaseline_s = 20.0;

/// Records held ahead of the clock, none contradicted, that show the data really jumped
/// (TimeGuard): the first and two more.
inline constexpr std::size_t kTimeJumpConfirm = 3;

/// One aircraft as the table knows it. Reported values are kept in canonical units for
/// alerts and TRACK objects; kinematics are in the plane, SI units.
struct Track {
  std::string source;
  std::string id;
  std::string callsign;
  std::optional<std::uint16_t> mode3a;
  std::optional<std::uint32_t> address;  ///< 24-bit ICAO address, once a record gave one
  bool coasting = false;     ///< the last record was extrapolated by its source
  std::uint16_t number = 0;  ///< 16-bit system track number for CAT004 and Modbus, ≠ 0
  bool has_velocity = false;  ///< false until a velocity was reported or derived
  /// The vertical rate was reported or derived from altitudes (or kept from such a
  /// record): false when vr_fpm is 0 only because nothing said otherwise.
  bool vertical_rate_known = false;
  /// The vertical rate was derived from the last two altitudes, which differed by
  /// altitude_step_ft (ft, ≥ 0): one 25 ft step between two records is the altitude's
  /// quantum, not a climb (the level-pair rule, design §4.5).
  bool vertical_rate_derived = false;
  double altitude_step_ft = 0.0;
  /// Altitude of the last record less the one before (ft, signed; 0 without one within
  /// the derivation gap), and whether it and the change before it were both non-zero and
  /// one way: a steady climb or descent, which one 25 ft step per record can also be.
  double altitude_change_ft = 0.0;
  bool altitude_moving_one_way = false;
  bool in_use = false;
  /// Records accepted since the track began, or since its last velocity reset
  /// (saturates): a track seen once may be a tracker's duplicate (design §4.5).
  std::uint32_t records = 0;

  double t = 0.0;            ///< data time of the last accepted record (UTC s)
  double lat_deg = 0.0, lon_deg = 0.0, alt_ft = 0.0;
  double gs_kt = 0.0, trk_deg = 0.0, vr_fpm = 0.0;  ///< as reported, or derived

  /// Point scale k of the projection at the position (plane length / ellipsoid
  /// length, ≥ 1): separations measured in the plane are divided by it.
  double plane_scale = 1.0;
  /// Vertical intent: the selection and what the track did about it.
  IntentState intent;
  /// Altitude (ft) at which the vertical prediction levels off, as of the last record;
  /// empty: linear (update_intent).
  std::optional<double> level_off_ft;
  /// Rate of turn (deg/s, positive right): reported, or derived from two track angles
  /// kTurnRateBaseline_s to kTurnRateMaxBaseline_s apart; empty when unknown.
  std::optional<double> turn_rate_dps;
  double turn_reference_t = 0.0;          ///< the older track angle of the derivation
  double turn_reference_trk_deg = 0.0;
  bool has_turn_reference = false;
  probe::Kinematics kinematics;             ///< plane kinematics at t, in plane `plane`
  /// Which plane `kinematics` and `plane_scale` are in: the key of the zone whose
  /// projection admit() was given (design §4.9; 0 in single mode).
  std::uint32_t plane = 0;
  /// The track is in the kinetic engines of the zones that hold it (it has a velocity);
  /// the Pipeline sets it.
  bool in_engine = false;

  /// Plane kinematics extrapolated to time `at` (UTC s), probe::extrapolated.
  probe::Kinematics at(double at_t) const { return probe::extrapolated(kinematics, at_t - t); }
};

/// A record's position projected in a plane, and the projection's verdict on it.
struct ProjectedPosition {
  geo::PlanePosition at;
  geo::ProjectionError error = geo::ProjectionError::None;
};

/// What admit() decided about a record.
enum class Admission : std::uint8_t {
  Rejected,        ///< counted in the table's Rejections; the table is unchanged
  AwaitingVelocity,///< position stored, but no velocity yet: not in the engine
  Accepted,        ///< the track has kinematics at the record's time
};

struct AdmitResult {
  Admission admission = Admission::Rejected;
  TrackSlot slot = kNoTrack;
  bool new_track = false;       ///< the record opened a new track
  bool velocity_reset = false;  ///< derived speed was implausible: velocity forgotten
  Refusal refusal = Refusal::None;  ///< the reason counted, when the record was rejected
};

class TrackTable {
 public:
  explicit TrackTable(const TrackTableConfig& config = {});

  /// Checks a record and, when it passes, applies it to its track. `now` is the pipeline
  /// clock (UTC s): records older than now − max_lateness_s are refused. On refusal the
  /// reason is counted in rejections() and nothing else changes. An implausible optional
  /// field (speed, track angle, vertical rate, selected altitude, track angle rate) costs
  /// only that field (design §4.3): it is dropped, counted in dropped_fields(), and the
  /// record judged without it. `plane` names the projection (Track::plane): a previous
  /// position or velocity in another plane is carried over through its geodetic
  /// position and ground velocity.
  /// `projected`: the record's position already projected in `projection` by the caller
  /// (null: admit() projects it), so that a record is projected once.
  AdmitResult admit(const TrackReport& report, double now, const geo::Projection& projection,
                    std::uint32_t plane = 0, const ProjectedPosition* projected = nullptr);

  /// Forgets a track (its slot may be reused by a later track).
  void drop(TrackSlot slot);

  /// Drops every track whose last record is older than now − track_timeout_s, oldest
  /// first, calling on_drop(slot, track) before each is forgotten.
  template <class F>
  void expire(double now, F&& on_drop) {
    while (!deadlines_.empty() && deadlines_.top_key() < now) {
      const TrackSlot slot = deadlines_.top_handle();
      on_drop(slot, tracks_[slot]);
      drop(slot);
    }
  }

  const Track& operator[](TrackSlot slot) const { return tracks_[slot]; }
  Track& operator[](TrackSlot slot) { return tracks_[slot]; }
  /// Tracks in use (live or awaiting velocity).
  std::size_t size() const { return in_use_; }
  std::size_t max_size() const { return max_in_use_; }
  /// One past the highest slot ever used: iterate [0, slot_end()) and test in_use.
  TrackSlot slot_end() const { return static_cast<TrackSlot>(tracks_.size()); }
  TrackSlot find(std::string_view source, std::string_view id) const;

  /// The reason a record is implausible on its own (time, position, altitude, on
  /// ground...), or an empty view when it is plausible. Optional fields are not judged
  /// here (admit() drops implausible ones). No state is read or changed. None: plausible.
  Refusal plausibility_problem(const TrackReport& r) const;

  const TrackTableConfig& config() const { return config_; }
  Rejections& rejections() { return rejections_; }
  const Rejections& rejections() const { return rejections_; }
  /// Optional fields dropped from accepted records, by reason ("vertical_rate_too_high"...).
  Rejections& dropped_fields() { return dropped_fields_; }
  const Rejections& dropped_fields() const { return dropped_fields_; }
  std::uint64_t velocity_resets() const { return velocity_resets_; }
  std::uint64_t velocities_derived() const { return velocities_derived_; }

  /// The table's whole state, for a checkpoint (design §5.9): every slot's track, the
  /// free slots in the order they are reused, the deadlines and the counters. restore()
  /// into a table of the same configuration admits, expires and numbers exactly as this
  /// one would. Throws util::CheckpointError when it cannot be read; the table is then
  /// left empty.
  void save(util::CheckpointWriter& out) const;
  void restore(util::CheckpointReader& in);
  /// One track's fields as save() writes them (in_use aside), for the copies of tracks
  /// other owners keep (the alert stage's view). read_track throws util::CheckpointError.
  static void write_track(util::CheckpointWriter& out, const Track& track);
  static void read_track(util::CheckpointReader& in, Track& track);

 private:
  TrackSlot allocate(const TrackReport& r);
  /// The rate of turn after record `r` (Track::turn_rate_dps); track.trk_deg is r's.
  static void update_turn_rate(Track& track, const TrackReport& r, bool has_velocity);
  /// Bits of the optional fields of `r` that are implausible.
  enum OptionalField : unsigned {
    kGroundSpeed = 1,
    kTrackAngle = 2,
    kVerticalRate = 4,
    kSelectedAltitude = 8,  ///< outside [min_altitude_ft, max_altitude_ft]
    kTrackAngleRate = 16,   ///< |rate| above 30 deg/s
  };
  unsigned implausible_optional_fields(const TrackReport& r) const;
  /// Clears the fields of `bits` in `r` and counts each in dropped_fields().
  void drop_optional_fields(TrackReport& r, unsigned bits);

  TrackTableConfig config_;
  util::ChunkedVector<Track> tracks_;  // chunked: no doubling slack on ~200-byte records
  std::vector<TrackSlot> free_slots_;
  TrackIndex index_;  // (source, id) → slot, for slots in use
  util::IndexedHeap<std::less<double>> deadlines_;  // one per track in use: last t + timeout
  std::size_t in_use_ = 0;
  std::size_t max_in_use_ = 0;
  std::uint64_t velocity_resets_ = 0;
  std::uint64_t velocities_derived_ = 0;
  Rejections rejections_;
  Rejections dropped_fields_;
};

}  // namespace kew::track
