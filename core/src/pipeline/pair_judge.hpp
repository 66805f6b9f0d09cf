#pragma once
// How a pair of tracks is judged, in one place for the zones and the alert stage: the
// parameters of the regions the aircraft are in (design §4.8), the pair's minima in a
// plane, its kinematics in the order the probe takes them, and the conflict test.

#include <cstddef>
#include <string>
#include <vector>

#include "kew/pipeline/pipeline_config.hpp"
#include "kew/probe/cpa.hpp"
#include "kew/region/region_map.hpp"
#include "kew/zone/zone.hpp"

namespace kew::pipeline {

/// The parameters that judge a pair whose aircraft are in two regions.
struct PairParameters {
  probe::SeparationMinima minima;  ///< S_h in metres on the ellipsoid (not yet scaled)
  double warning_s = 0.0;
  int confirm = 0, clear = 0;
  const std::string* region = nullptr;  ///< the judging region's name; null: the defaults
  bool inhibited = false;               ///< either aircraft in an inhibition volume
};

/// A pair as the probe evaluates it: lower slot first, minima scaled for the pair.
struct PairKinematics {
  track::TrackSlot p = track::kNoTrack, q = track::kNoTrack;
  probe::Kinematics kp, kq;
  probe::SeparationMinima minima;  ///< S_h scaled by the pair's point scale
  double scale = 1.0;              ///< the pair's projection scale
  PairParameters parameters;
};

class PairJudge {
 public:
  explicit PairJudge(const PipelineConfig& config);

  /// The parameters of a pair in regions `ra` and `rb` (region::RegionMap indices, kNone
  /// for none): a region's own, or between two regions the stricter of each.
  PairParameters parameters(std::size_t ra, std::size_t rb) const;
  /// The minima of a pair whose members are `a` and `b` in one plane, S_h scaled by
  /// their pair scale: the one computation of a pair's minima.
  probe::SeparationMinima minima(const zone::ProbeState& a, const zone::ProbeState& b) const {
    probe::SeparationMinima m = no_regions_ ? defaults_.minima : parameters(a.region, b.region).minima;
    m.horizontal_m *= geo::Projection::pair_scale(a.scale, b.scale);
    return m;
  }
  /// The pair (self, other) at data time `now` (UTC s) in their common plane, `k_self`
  /// being self.at(now) (the caller has it).
  PairKinematics pair(const zone::ProbeState& self, const probe::Kinematics& k_self, const zone::ProbeState& other,
                      double now) const;
  /// The conflict test of one ordered pair: linear (with vertical intent), then, when
  /// the turn hypothesis is on and either aircraft turns, along the arcs.
  bool in_conflict(const probe::Kinematics& kp, const probe::Kinematics& kq,
                   const probe::SeparationMinima& minima) const {
    if (probe::in_conflict(kp, kq, minima)) return true;
    return turn_enabled_ && (kp.turn_rate_rps != 0.0 || kq.turn_rate_rps != 0.0) &&
           probe::in_turn_conflict(kp, kq, minima);
  }

  const region::RegionMap& regions() const { return regions_; }
  /// The largest S_h (m) and T (s) of the defaults and every region: the search's reach.
  double largest_horizontal_m() const { return largest_horizontal_m_; }
  double largest_lookahead_s() const { return largest_lookahead_s_; }

 private:
  region::RegionMap regions_;
  bool no_regions_ = true;
  bool turn_enabled_ = false;
  PairParameters defaults_;
  std::vector<PairParameters> by_region_;  // by region index
  double largest_horizontal_m_ = 0.0;
  double largest_lookahead_s_ = 0.0;
};

}  // namespace kew::pipeline
