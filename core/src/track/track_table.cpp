#include "kew/track/track_table.hpp"

#include <cmath>
#include <algorithm>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include "kew/util/units.hpp"

namespace kew::track {

namespace {
/// The largest |track angle rate| kept (deg/s): a rate-one turn is 3 deg/s, and no
/// aircraft the tables carry turns ten times as fast (design §4.3).
constexpr double kMaxTrackAngleRateDps = 30.0;

Refusal projection_refusal(geo::ProjectionError e) {
  switch (e) {
    case geo::ProjectionError::NotFinite: return Refusal::PositionNotFinite;
    case geo::ProjectionError::LatitudeRange: return Refusal::LatitudeOutOfRange;
    case geo::ProjectionError::LongitudeRange: return Refusal::LongitudeOutOfRange;
    case geo::ProjectionError::OutsideCoverage: return Refusal::OutsideCoverage;
    case geo::ProjectionError::None: break;
  }
  return Refusal::None;
}

std::uint16_t track_number_of(TrackSlot slot) { return static_cast<std::uint16_t>(slot % 65535u + 1u); }
}  // namespace

TrackTable::TrackTable(const TrackTableConfig& config) : config_(config) {}

Refusal TrackTable::plausibility_problem(const TrackReport& r) const {
  if (r.id.empty()) return Refusal::EmptyId;
  if (r.id.size() > config_.max_id_bytes || r.source.size() > config_.max_id_bytes) return Refusal::IdTooLong;
  if (!std::isfinite(r.t)) return Refusal::TimeNotFinite;
  if (!std::isfinite(r.lat_deg) || !std::isfinite(r.lon_deg)) return Refusal::PositionNotFinite;
  if (std::abs(r.lat_deg) > 90.0) return Refusal::LatitudeOutOfRange;
  if (std::abs(r.lon_deg) > 180.0) return Refusal::LongitudeOutOfRange;
  if (std::isnan(r.alt_ft)) return Refusal::AltitudeMissing;
  if (!std::isfinite(r.alt_ft)) return Refusal::AltitudeNotFinite;
  if (r.alt_ft < config_.min_altitude_ft || r.alt_ft > config_.max_altitude_ft) return Refusal::AltitudeOutOfRange;
  if (r.on_ground && config_.exclude_on_ground) return Refusal::OnGround;
  return Refusal::None;
}

unsigned TrackTable::implausible_optional_fields(const TrackReport& r) const {
  unsigned bits = 0;
  if (r.gs_kt && !(*r.gs_kt >= 0.0 && *r.gs_kt <= config_.max_ground_speed_kt)) bits |= kGroundSpeed;
  if (r.trk_deg && !(*r.trk_deg >= 0.0 && *r.trk_deg < 360.0)) bits |= kTrackAngle;
  if (r.vr_fpm && !(std::abs(*r.vr_fpm) <= config_.max_vertical_rate_fpm)) bits |= kVerticalRate;
  if (r.sel_ft && !(*r.sel_ft >= config_.min_altitude_ft && *r.sel_ft <= config_.max_altitude_ft))
    bits |= kSelectedAltitude;
  if (r.tar_dps && !(std::abs(*r.tar_dps) <= kMaxTrackAngleRateDps)) bits |= kTrackAngleRate;
  return bits;
}

void TrackTable::drop_optional_fields(TrackReport& r, unsigned bits) {
  // NaN fails every range test of implausible_optional_fields: it is told apart here.
  if (bits & kGroundSpeed) {
    const double v = *r.gs_kt;
    dropped_fields_.reject(!std::isfinite(v) ? "speed_not_finite" : v < 0.0 ? "speed_negative" : "speed_too_high",
                           fmt::format("{}: ground speed {} kt dropped", r.id, v));
    r.gs_kt.reset();
  }
  const auto drop = [&](unsigned bit, std::optional<double>& field, std::string_view out_of_range,
                        std::string_view not_finite, std::string_view what, std::string_view unit) {
    if ((bits & bit) == 0) return;
    dropped_fields_.reject(std::isfinite(*field) ? out_of_range : not_finite,
                           fmt::format("{}: {} {} {} dropped", r.id, what, *field, unit));
    field.reset();
  };
  drop(kTrackAngle, r.trk_deg, "track_angle_out_of_range", "track_angle_not_finite", "track angle", "deg");
  drop(kVerticalRate, r.vr_fpm, "vertical_rate_too_high", "vertical_rate_not_finite", "vertical rate", "ft/min");
  drop(kSelectedAltitude, r.sel_ft, "selected_altitude_out_of_range", "selected_altitude_not_finite",
       "selected altitude", "ft");
  drop(kTrackAngleRate, r.tar_dps, "track_angle_rate_too_high", "track_angle_rate_not_finite",
       "track angle rate", "deg/s");
}

AdmitResult TrackTable::admit(const TrackReport& r, double now, const geo::Projection& projection,
                               std::uint32_t plane_key, const ProjectedPosition* projected) {
  AdmitResult result;
  const auto reject = [&](Refusal reason) {
    rejections_.reject(kRefusalNames.name(reason), r.id);
    result.refusal = reason;
    return result;
  };
  if (const Refusal reason = plausibility_problem(r); reason != Refusal::None) return reject(reason);
  if (const unsigned bad_fields = implausible_optional_fields(r); bad_fields != 0) {
    // Rare: only a record with a field to drop pays for the copy.
    TrackReport cleaned = r;
    drop_optional_fields(cleaned, bad_fields);
    return admit(cleaned, now, projection, plane_key, projected);
  }
  if (r.t < now - config_.max_lateness_s) return reject(Refusal::TooLate);

  const TrackSlot existing = find(r.source, r.id);
  if (existing != kNoTrack) {
    const Track& previous = tracks_[existing];
    if (r.t < previous.t) return reject(Refusal::OutOfOrder);
    if (r.t == previous.t) return reject(Refusal::DuplicateTime);
  } else if (in_use_ >= config_.max_tracks) {
    return reject(Refusal::TrackLimit);
  }

  geo::ProjectionError error = projected ? projected->error : geo::ProjectionError::None;
  const geo::PlanePosition plane = projected ? projected->at : projection.project({r.lat_deg, r.lon_deg}, error);
  if (error != geo::ProjectionError::None) return reject(projection_refusal(error));

  const Track* previous = existing != kNoTrack ? &tracks_[existing] : nullptr;
  const double gap = previous ? r.t - previous->t : 0.0;
  const bool can_derive = previous && gap <= config_.max_derivation_gap_s;

  // Horizontal velocity: reported, derived from the previous position, or kept.
  bool has_velocity = false;
  bool derived = false;
  geometry::Vector2 velocity{};
  if (r.gs_kt && r.trk_deg) {
    velocity = projection.velocity_to_plane(plane, *r.gs_kt * units::kMpsPerKnot, *r.trk_deg);
    has_velocity = true;
  } else if (can_derive) {
    // The previous position in this record's plane: a track that crossed into another
    // zone was admitted in that zone's plane.
    geometry::Point2 before = previous->kinematics.position;
    if (previous->plane != plane_key) {
      geo::ProjectionError ignored = geo::ProjectionError::None;
      before = projection.project({previous->lat_deg, previous->lon_deg}, ignored).p;
    }
    velocity = (1.0 / gap) * (plane.p - before);
    has_velocity = true;
    derived = true;
    if (geometry::norm(velocity) / plane.scale > config_.max_ground_speed_kt * units::kMpsPerKnot) {
      // A jump no aircraft can fly: the previous position is not this aircraft's (a
      // reused track number, a bad fix). Start the velocity afresh from this record.
      has_velocity = false;
      derived = false;
      result.velocity_reset = true;
    }
  } else if (previous && previous->has_velocity) {
    velocity = previous->plane == plane_key
                   ? previous->kinematics.velocity
                   : projection.velocity_to_plane(plane, previous->gs_kt * units::kMpsPerKnot, previous->trk_deg);
    has_velocity = true;
  }

  double vertical_rate_mps = 0.0;
  bool vertical_rate_known = false;
  bool vertical_rate_derived = false;
  double altitude_step_ft = 0.0;
  // Successive altitude changes one way are a climb or descent, however small each step.
  const double altitude_change_ft = can_derive ? r.alt_ft - previous->alt_ft : 0.0;
  const bool altitude_moving_one_way =
      can_derive && altitude_change_ft != 0.0 && previous->altitude_change_ft * altitude_change_ft > 0.0;
  if (r.vr_fpm) {
    vertical_rate_mps = *r.vr_fpm * units::kMpsPerFpm;
    vertical_rate_known = true;
  } else if (can_derive) {
    vertical_rate_mps = (r.alt_ft - previous->alt_ft) * units::kMetresPerFoot / gap;
    vertical_rate_known = vertical_rate_derived = true;
    altitude_step_ft = std::abs(r.alt_ft - previous->alt_ft);
    if (std::abs(vertical_rate_mps) > config_.max_vertical_rate_fpm * units::kMpsPerFpm) {
      vertical_rate_mps = 0.0;
      vertical_rate_known = vertical_rate_derived = false;
    }
  } else if (previous) {
    vertical_rate_mps = previous->kinematics.vertical_rate_mps;
    vertical_rate_known = previous->vertical_rate_known;
    vertical_rate_derived = previous->vertical_rate_derived;
    altitude_step_ft = previous->altitude_step_ft;
  }

  TrackSlot slot = existing;
  if (slot == kNoTrack) {
    slot = allocate(r);
    result.new_track = true;
  }
  Track& track = tracks_[slot];
  track.t = r.t;
  track.records = result.velocity_reset ? 1 : std::min(track.records + 1, std::numeric_limits<std::uint32_t>::max() - 1);
  track.lat_deg = r.lat_deg;
  track.lon_deg = r.lon_deg;
  track.alt_ft = r.alt_ft;
  if (result.velocity_reset) {
    // The previous position was another aircraft's (a reused track number): so were its
    // attributes, and one aircraft's address on another would make them "one aircraft".
    track.callsign.clear();
    track.mode3a.reset();
    track.address.reset();
    track.intent = IntentState{};
    track.has_turn_reference = false;
  }
  if (!r.callsign.empty()) track.callsign = r.callsign;
  if (r.mode3a) track.mode3a = r.mode3a;
  if (r.address) track.address = r.address;
  track.coasting = r.coasting;
  track.plane_scale = plane.scale;
  track.plane = plane_key;
  track.kinematics.position = plane.p;
  track.kinematics.velocity = velocity;
  track.kinematics.altitude_m = r.alt_ft * units::kMetresPerFoot;
  track.kinematics.vertical_rate_mps = vertical_rate_mps;
  track.has_velocity = has_velocity;
  track.vertical_rate_known = vertical_rate_known;
  track.vertical_rate_derived = vertical_rate_derived;
  track.altitude_step_ft = altitude_step_ft;
  track.altitude_change_ft = altitude_change_ft;
  track.altitude_moving_one_way = altitude_moving_one_way;
  track.vr_fpm = vertical_rate_mps / units::kMpsPerFpm;
  if (r.gs_kt && r.trk_deg) {
    track.gs_kt = *r.gs_kt;
    track.trk_deg = *r.trk_deg;
  } else if (has_velocity) {
    double speed = 0.0;
    projection.velocity_from_plane(plane, velocity, speed, track.trk_deg);
    track.gs_kt = speed / units::kMpsPerKnot;
  }
  track.level_off_ft = update_intent(track.intent, config_.intent, r.t, r.sel_ft, r.sel_src, r.alt_ft, track.vr_fpm);
  track.kinematics.level_off_m =
      track.level_off_ft ? *track.level_off_ft * units::kMetresPerFoot : std::numeric_limits<double>::quiet_NaN();
  update_turn_rate(track, r, has_velocity);
  if (derived) ++velocities_derived_;
  if (result.velocity_reset) ++velocity_resets_;
  deadlines_.set(slot, r.t + config_.track_timeout_s);

  result.slot = slot;
  result.admission = has_velocity ? Admission::Accepted : Admission::AwaitingVelocity;
  return result;
}

void TrackTable::update_turn_rate(Track& track, const TrackReport& r, bool has_velocity) {
  if (r.tar_dps) {
    track.turn_rate_dps = r.tar_dps;
    return;
  }
  if (!has_velocity) {
    track.turn_rate_dps.reset();
    track.has_turn_reference = false;
    return;
  }
  const double baseline = r.t - track.turn_reference_t;
  if (track.has_turn_reference && baseline > kTurnRateMaxBaseline_s) {
    track.turn_rate_dps.reset();
    track.has_turn_reference = false;
  }
  if (!track.has_turn_reference) {
    track.turn_reference_t = r.t;
    track.turn_reference_trk_deg = track.trk_deg;
    track.has_turn_reference = true;
    return;
  }
  if (baseline < kTurnRateBaseline_s) return;  // keep the last rate
  double turned = std::fmod(track.trk_deg - track.turn_reference_trk_deg, 360.0);
  if (turned > 180.0) turned -= 360.0;
  if (turned < -180.0) turned += 360.0;
  track.turn_rate_dps = turned / baseline;
  track.turn_reference_t = r.t;
  track.turn_reference_trk_deg = track.trk_deg;
}

static_assert(TrackIndex::kAbsent == kNoTrack, "find() hands the index's 'absent' on as kNoTrack");

TrackSlot TrackTable::find(std::string_view source, std::string_view id) const {
  return index_.find(TrackIndex::hash(source, id),
                     [&](TrackSlot slot) { return tracks_[slot].id == id && tracks_[slot].source == source; });
}

TrackSlot TrackTable::allocate(const TrackReport& r) {
  TrackSlot slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    slot = static_cast<TrackSlot>(tracks_.size());
    tracks_.emplace_back();
  }
  Track& track = tracks_[slot];
  track = Track{};
  track.source = r.source;
  track.id = r.id;
  track.number = track_number_of(slot);
  track.in_use = true;
  index_.insert(TrackIndex::hash(r.source, r.id), slot);
  ++in_use_;
  if (in_use_ > max_in_use_) max_in_use_ = in_use_;
  return slot;
}

void TrackTable::drop(TrackSlot slot) {
  Track& track = tracks_[slot];
  if (!track.in_use) return;
  index_.erase(TrackIndex::hash(track.source, track.id), slot);
  deadlines_.erase(slot);
  track = Track{};
  free_slots_.push_back(slot);
  --in_use_;
}

}  // namespace kew::track
