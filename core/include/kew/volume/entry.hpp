#pragma once
// When does an aircraft on its predicted path enter a volume (the geometric core of an
// area proximity warning)?
//
// Motion model. At time 0 the aircraft is at `start` (WGS84 degrees) and `alt_ft`. It
// moves along the geodesic leaving `start` with the true track `track_deg` at the ground
// speed `gs_kt`: its position at t seconds is GeographicLib's Geodesic::Direct from
// `start`, azimuth `track_deg`, distance gs·t (gs in m/s = gs_kt·1852/3600). Its altitude
// is alt_ft + vr_fpm·t/60, or, with a selected altitude it climbs or descends towards
// (kew's level-off hypothesis, design §4.4), alt_ft + vr_fpm·min(t, t_stop)/60 with
// t_stop = 60·(sel_ft − alt_ft)/vr_fpm > 0; a selection it is level at or moving away
// from is ignored. The look-ahead is [0, T], T = `horizon_s`.
//
// Entry. The aircraft is inside at t when its position is in the area (holes excluded,
// boundary inside) and floor_ft ≤ altitude ≤ ceiling_ft. entry() returns the earliest such
// t in [0, T]. Horizontally, a polygon's crossings are found in the gnomonic plane of the
// volume (path and edges straight lines, their intersection points) and refined on the
// ellipsoid (a gnomonic projection centred on the path, where the path is exactly
// straight, until the crossing moves less than 1 µm), then turned into times by their
// distance along the path over the speed. Every crossing time, and the time the path
// passes each nearby vertex, splits [0, T]; each piece is classified by testing its
// midpoint, so a path through a vertex or along an edge needs no counting rule. A circle's
// crossings are the roots of (geodesic distance from the centre) − radius, bracketed
// around the distance's minimum along the path and bisected to 0.1 mm. Vertically the
// altitude is monotone, so the band is one interval, intersected with the horizontal ones.
//
// Degenerate cases. Zero speed or T = 0: the position is constant, inside or not for the
// whole look-ahead. Path through a vertex: the vertex's own passage time is a split point,
// and both edges' crossings land on it. Path along an edge: the passage times of the
// edge's vertices are split points and the stretch between them is on the boundary, so
// inside. Tangent touch (a path grazing a circle, a vertex touched from outside, an
// altitude levelling off exactly at the floor): the touch counts as entering at that
// instant (an inside interval of length 0), within kBoundaryTolerance_m horizontally.

#include <optional>
#include <vector>

#include "kew/util/name_table.hpp"
#include "kew/volume/volume.hpp"

namespace kew::volume {

struct Motion {
  LatLon start;                  ///< position at t = 0 (degrees)
  double alt_ft = 0.0;           ///< altitude at t = 0 (ft), finite
  double track_deg = 0.0;        ///< true track (degrees clockwise from north), finite
  double gs_kt = 0.0;            ///< ground speed (kt) in [0, kMaxGroundSpeed_kt]
  double vr_fpm = 0.0;           ///< vertical rate (ft/min, + climbing), finite
  std::optional<double> sel_ft;  ///< selected altitude (ft) where a climb or descent levels off
};

/// Fastest ground speed (kt) and longest look-ahead (s): the path is at most 1,000 NM
/// (16.7° of arc), which keeps the part of it near a volume inside its gnomonic plane.
inline constexpr double kMaxGroundSpeed_kt = 1000.0;
inline constexpr double kMaxHorizon_s = 3600.0;

/// Why entry() refused a motion.
enum class MotionError {
  None,
  NotFinite,       ///< a field (or the horizon) is NaN or infinite
  LatitudeRange,   ///< |lat| > 90
  LongitudeRange,  ///< lon outside [-180, 180]
  SpeedRange,      ///< gs_kt outside [0, kMaxGroundSpeed_kt]
  HorizonRange,    ///< horizon_s outside [0, kMaxHorizon_s]
};

inline constexpr util::NameTable<MotionError, 6> kMotionErrorNames({{
    {MotionError::None, "none"},
    {MotionError::NotFinite, "not_finite"},
    {MotionError::LatitudeRange, "latitude_range"},
    {MotionError::LongitudeRange, "longitude_range"},
    {MotionError::SpeedRange, "speed_range"},
    {MotionError::HorizonRange, "horizon_range"},
}});

/// A closed interval of time (s), begin_s ≤ end_s; a point when they are equal.
struct Interval {
  double begin_s = 0.0;
  double end_s = 0.0;
};

struct Entry {
  MotionError error = MotionError::None;  ///< the rest is empty unless None
  bool inside_now = false;                ///< inside at t = from_s (0): a violation
  std::optional<double> entry_s;          ///< earliest t in [from_s, T] inside (s)
  /// End of the inside interval that starts at entry_s (s), when it ends before T.
  std::optional<double> exit_s;
};

/// MotionError::None, or why `motion` with look-ahead `horizon_s` (s) cannot be used.
MotionError validate(const Motion& motion, double horizon_s);

/// Ground speed of `motion` in m/s.
double ground_speed_mps(const Motion& motion);

/// Position at t (s, any finite value; negative is before the start).
LatLon position_at(const Motion& motion, double t_s);

/// Time (s, > 0) at which the climb or descent levels off at sel_ft, or none.
std::optional<double> level_off_s(const Motion& motion);

/// Altitude (ft) at t ≥ 0 (s).
double altitude_at(const Motion& motion, double t_s);

/// The times in [0, T] when floor_ft ≤ altitude ≤ ceiling_ft: one interval or none (the
/// altitude is monotone). `motion` and `horizon_s` valid.
std::optional<Interval> vertical_interval(const Motion& motion, VerticalBand band, double horizon_s);

/// False only when the path of `motion` over `length_m` (m) cannot come within the
/// area: a conservative test on a sphere, a few trigonometric calls. `motion` valid.
bool within_reach(const Volume& volume, const Motion& motion, double length_m);
/// The times in [0, T] when the position is in the area, as sorted disjoint closed
/// intervals. `motion` and `horizon_s` valid (validate()).
std::vector<Interval> horizontal_intervals(const Volume& volume, const Motion& motion, double horizon_s);

/// The earliest time in [from_s, horizon_s] (s) at which `motion` is inside `volume`,
/// whether that is at from_s ("now": a record judged from_s after its own time), and when
/// it leaves again. An invalid motion, or from_s outside [0, horizon_s]
/// (HorizonRange), is returned as its error.
Entry entry(const Volume& volume, const Motion& motion, double horizon_s, double from_s = 0.0);

}  // namespace kew::volume
