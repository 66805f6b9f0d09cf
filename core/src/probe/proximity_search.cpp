#include "kew/probe/proximity_search.hpp"

#include <algorithm>
#include <cstring>

namespace kew::probe {

const char* to_string(ProbeMode mode) {
  switch (mode) {
    case ProbeMode::Edges: return "edges";
    case ProbeMode::Brute: return "brute";
    case ProbeMode::Exact: break;
  }
  return "exact";
}

bool parse_probe_mode(const char* text, ProbeMode& out) {
  for (ProbeMode m : {ProbeMode::Exact, ProbeMode::Edges, ProbeMode::Brute}) {
    if (std::strcmp(text, to_string(m)) == 0) {
      out = m;
      return true;
    }
  }
  return false;
}

bool ProximitySearch::first_visit(PointId p) {
  if (p >= visited_round_.size()) visited_round_.resize(p + 1, 0);
  if (visited_round_[p] == round_) return false;
  visited_round_[p] = round_;
  return true;
}

void ProximitySearch::within(const kinetic::KineticDelaunay& kdt, PointId center, double radius_m,
                             std::vector<PointId>& out) {
  if (++round_ == 0) {  // wrapped: forget every mark
    std::fill(visited_round_.begin(), visited_round_.end(), 0);
    round_ = 1;
  }
  // Twins sit within their release distance of their host; widening the disk by twice
  // that keeps the greedy-routing argument valid for hosts of twins inside the disk.
  const double reach = radius_m + 2.0 * kdt.config().twin_release_distance_m;
  const double reach2 = reach * reach;
  const geometry::Point2 c = kdt.position_now(center);
  frontier_.clear();
  first_visit(center);
  frontier_.push_back(center);
  for (std::size_t next = 0; next < frontier_.size(); ++next) {
    kdt.for_each_neighbor(frontier_[next], [&](PointId w) {
      if (!first_visit(w)) return;
      const geometry::Vector2 d = kdt.position_now(w) - c;
      if (geometry::dot(d, d) > reach2) return;
      frontier_.push_back(w);
      out.push_back(w);
    });
  }
}

void ProximitySearch::neighbours(const kinetic::KineticDelaunay& kdt, PointId center, std::vector<PointId>& out) {
  kdt.for_each_neighbor(center, [&](PointId w) {
    if (w != center) out.push_back(w);
  });
}

}  // namespace kew::probe
