#include "pair_judge.hpp"

#include <algorithm>

namespace kew::pipeline {

PairJudge::PairJudge(const PipelineConfig& config)
    : regions_(config.regions), no_regions_(config.regions.empty()), turn_enabled_(config.turn.enabled) {
  defaults_.minima = config.minima;
  defaults_.warning_s = config.alerts.warning_s;
  defaults_.confirm = config.alerts.confirm;
  defaults_.clear = config.alerts.clear;
  largest_horizontal_m_ = defaults_.minima.horizontal_m;
  largest_lookahead_s_ = defaults_.minima.lookahead_s;
  // Each region's parameters resolved against the defaults once.
  for (const region::Region& r : regions_.regions()) {
    PairParameters p = defaults_;
    const region::RegionParameters& set = r.parameters;
    p.minima.horizontal_m = set.horizontal_m.value_or(p.minima.horizontal_m);
    p.minima.vertical_m = set.vertical_m.value_or(p.minima.vertical_m);
    p.minima.lookahead_s = set.lookahead_s.value_or(p.minima.lookahead_s);
    p.warning_s = set.warning_s.value_or(p.warning_s);
    p.confirm = set.confirm.value_or(p.confirm);
    p.clear = set.clear.value_or(p.clear);
    p.region = &r.name;
    p.inhibited = r.inhibit;
    largest_horizontal_m_ = std::max(largest_horizontal_m_, p.minima.horizontal_m);
    largest_lookahead_s_ = std::max(largest_lookahead_s_, p.minima.lookahead_s);
    by_region_.push_back(p);
  }
}

PairParameters PairJudge::parameters(std::size_t ra, std::size_t rb) const {
  const PairParameters& a = ra == region::RegionMap::kNone ? defaults_ : by_region_[ra];
  const PairParameters& b = rb == region::RegionMap::kNone ? defaults_ : by_region_[rb];
  if (&a == &b) return a;
  // Different regions: the stricter of each parameter (design §4.8).
  PairParameters p = a;
  p.minima.horizontal_m = std::max(a.minima.horizontal_m, b.minima.horizontal_m);
  p.minima.vertical_m = std::max(a.minima.vertical_m, b.minima.vertical_m);
  p.minima.lookahead_s = std::max(a.minima.lookahead_s, b.minima.lookahead_s);
  p.warning_s = std::max(a.warning_s, b.warning_s);
  p.confirm = std::min(a.confirm, b.confirm);
  p.clear = std::max(a.clear, b.clear);
  p.region = a.region ? a.region : b.region;
  if (a.region && b.region) p.region = *a.region < *b.region ? a.region : b.region;
  p.inhibited = a.inhibited || b.inhibited;
  return p;
}

PairKinematics PairJudge::pair(const zone::ProbeState& self, const probe::Kinematics& k_self,
                               const zone::ProbeState& other, double now) const {
  PairKinematics pair;
  pair.scale = geo::Projection::pair_scale(self.scale, other.scale);
  pair.parameters = parameters(self.region, other.region);
  pair.minima = pair.parameters.minima;
  pair.minima.horizontal_m *= pair.scale;
  // The lower slot goes first so that a pair's figures do not depend on which of its
  // two tracks was updated.
  const bool self_first = self.slot < other.slot;
  const probe::Kinematics k_other = other.at(now);
  pair.p = self_first ? self.slot : other.slot;
  pair.q = self_first ? other.slot : self.slot;
  pair.kp = self_first ? k_self : k_other;
  pair.kq = self_first ? k_other : k_self;
  return pair;
}

}  // namespace kew::pipeline
