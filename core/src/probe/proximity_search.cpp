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
  // Sized once for every point id, so first_visit() never grows it inside the loop.
  const std::size_t ids = kdt.triangulation().tds().vertex_capacity();
  if (visited_round_.size() < ids) visited_round_.resize(ids, 0);
  frontier_.clear();
  first_visit(center);
  frontier_.push_back(center);
  const auto visit = [&](PointId w) {
    if (!first_visit(w)) return;
    const geometry::Vector2 d = kdt.position_now(w) - c;
    if (geometry::dot(d, d) > reach2) return;
    frontier_.push_back(w);
    out.push_back(w);
  };
  for (std::size_t next = 0; next < frontier_.size(); ++next) for_each_neighbor(kdt, frontier_[next], visit);
}

template <class F>
void ProximitySearch::for_each_neighbor(const kinetic::KineticDelaunay& kdt, PointId id, F&& f) {
  // The same neighbours as kdt.for_each_neighbor(), twins included, walked straight off
  // the triangulation's faces: that one copies them into a vector and sorts it (to drop a
  // flat chain's repeated end), which the profile showed as a sixth of the probe. Repeats
  // and order do not matter here: first_visit() drops repeats and the search reaches the
  // same set in any order.
  const PointId vertex = kdt.host_of(id);
  const triangulation::Tds& tds = kdt.triangulation().tds();
  if (!tds.is_attached(vertex)) {  // fewer than two points: no faces yet
    kdt.for_each_neighbor(id, f);
    return;
  }
  if (vertex != id) f(vertex);
  tds.for_each_adjacent_vertex(vertex, [&](PointId w) {
    if (w == triangulation::kInfiniteVertex) return;
    f(w);
    for (const PointId twin : kdt.twins_of(w)) f(twin);
  });
  for (const PointId twin : kdt.twins_of(vertex))
    if (twin != id) f(twin);
}

void ProximitySearch::neighbours(const kinetic::KineticDelaunay& kdt, PointId center, std::vector<PointId>& out) {
  kdt.for_each_neighbor(center, [&](PointId w) {
    if (w != center) out.push_back(w);
  });
}

}  // namespace kew::probe
