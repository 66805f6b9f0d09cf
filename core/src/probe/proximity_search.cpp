#include "kew/probe/proximity_search.hpp"

#include <algorithm>
#include <limits>

#include "kew/util/gentle_growth.hpp"

namespace kew::probe {

double ProximitySearch::begin_search(const kinetic::KineticDelaunay& kdt, double radius_m) {
  if (round_ >= std::numeric_limits<std::uint32_t>::max() - 2) {  // about to wrap: forget every mark
    std::fill(visited_round_.begin(), visited_round_.end(), 0);
    std::fill(face_round_.begin(), face_round_.end(), 0);
    round_ = 0;
  }
  round_ += 2;  // a vertex mark of round_ means "seen, out of reach", round_ + 1 "in reach"
  // Sized once for every id, so the marks never grow inside the loops.
  const triangulation::Tds& tds = kdt.triangulation().tds();
  util::grow_to(visited_round_, tds.vertex_capacity(), std::uint32_t{0});
  util::grow_to(face_round_, tds.face_capacity(), std::uint32_t{0});
  // Twins sit within their release distance of their host; widening the disk by twice
  // that keeps the greedy-routing argument valid for hosts of twins inside the disk.
  const double reach = radius_m + 2.0 * kdt.config().twin_release_distance_m;
  return reach * reach;
}

void ProximitySearch::within(const kinetic::KineticDelaunay& kdt, PointId center, double radius_m,
                             std::vector<PointId>& out) {
  const double reach2 = begin_search(kdt, radius_m);
  search_from(kdt, center, center, kdt.position_now(center), reach2, out);  // its own point is nearest
}

void ProximitySearch::within_around(const kinetic::KineticDelaunay& kdt, PointId center, geometry::Point2 target,
                                    double radius_m, std::vector<PointId>& out) {
  const double reach2 = begin_search(kdt, radius_m);
  // From any vertex in the disk a greedy walk towards `target` stays in the disk and ends
  // at the vertex nearest it, so the vertices in the disk are joined to one another
  // within it: the search may spread from any of them. The predicted position is
  // usually within the search radius of the track's own (|v|·T < R), so the walk is
  // needed only when it is not.
  const geometry::Vector2 d = kdt.position_now(center) - target;
  const PointId start = geometry::dot(d, d) <= reach2 ? center : nearest_to(kdt, center, target);
  search_from(kdt, start, center, target, reach2, out);
}

void ProximitySearch::search_from(const kinetic::KineticDelaunay& kdt, PointId start, PointId center,
                                  geometry::Point2 c, double reach2, std::vector<PointId>& out) {
  const PointId vertex = kdt.host_of(start);
  if (!kdt.triangulation().tds().is_attached(vertex) || kdt.triangulation().is_flat())
    within_by_vertices(kdt, start, center, c, reach2, out);
  else
    within_by_faces(kdt, vertex, center, c, reach2, out);
}

PointId ProximitySearch::nearest_to(const kinetic::KineticDelaunay& kdt, PointId from, geometry::Point2 c) {
  // Distances fall strictly at each step, so the walk ends; where it ends no neighbour is
  // closer, which on a Delaunay triangulation makes it the nearest point (ties: one of them).
  PointId best = from;
  geometry::Vector2 d = kdt.position_now(best) - c;
  double best2 = geometry::dot(d, d);
  for (bool moved = true; moved;) {
    moved = false;
    PointId next = best;
    for_each_neighbor(kdt, best, [&](PointId w) {
      const geometry::Vector2 e = kdt.position_now(w) - c;
      const double e2 = geometry::dot(e, e);
      if (e2 < best2) {
        best2 = e2;
        next = w;
      }
    });
    if (next != best) {
      best = next;
      moved = true;
    }
  }
  return best;
}

bool ProximitySearch::first_group_in_reach(const kinetic::KineticDelaunay& kdt, PointId vertex, PointId center,
                                           geometry::Point2 c, double reach2, std::vector<PointId>& out) {
  bool any = false;
  const auto consider = [&](PointId p) {
    const geometry::Vector2 d = kdt.position_now(p) - c;
    if (geometry::dot(d, d) > reach2) return;
    any = true;
    if (p != center) out.push_back(p);
  };
  consider(vertex);
  for (const PointId twin : kdt.twins_of(vertex)) consider(twin);
  visited_round_[vertex] = any ? round_ + 1 : round_;
  return any;
}

void ProximitySearch::within_by_faces(const kinetic::KineticDelaunay& kdt, PointId start, PointId center,
                                      geometry::Point2 c, double reach2, std::vector<PointId>& out) {
  // Faces, not vertex rings: walking the ring of every vertex in the disk reads each face
  // three times, and those reads (cache misses on a triangulation of thousands of
  // points) were half the probe's time. A face is opened when one of its vertices (or a
  // twin of one) is in reach, so every face around a vertex in reach is opened and every
  // neighbour of one is seen: the same points as the breadth-first search over vertices.
  const triangulation::Tds& tds = kdt.triangulation().tds();
  const FaceIndex first = tds.vertex_face(start);
  face_frontier_.clear();
  face_round_[first] = round_;
  face_frontier_.push_back(first);
  for (std::size_t next = 0; next < face_frontier_.size(); ++next) {
    // The search is bound by memory latency, not arithmetic: ask for the vertices of a
    // face a few places ahead in the queue (its record was requested when it was queued).
    if (next + 2 < face_frontier_.size()) {
      for (const PointId v : tds.face(face_frontier_[next + 2]).vertex)
        if (v != triangulation::kInfiniteVertex) {
          __builtin_prefetch(&kdt.triangulation().trajectory(v));
          __builtin_prefetch(&visited_round_[v]);
        }
    }
    const triangulation::Face& face = tds.face(face_frontier_[next]);
    bool open = false;
    for (const PointId v : face.vertex)
      if (v != triangulation::kInfiniteVertex && group_in_reach(kdt, v, center, c, reach2, out)) open = true;
    if (!open) continue;
    for (const FaceIndex g : face.neighbor) {
      if (g == triangulation::kNoFace || face_round_[g] == round_) continue;
      face_round_[g] = round_;
      __builtin_prefetch(&tds.face(g));
      face_frontier_.push_back(g);
    }
  }
}

void ProximitySearch::within_by_vertices(const kinetic::KineticDelaunay& kdt, PointId start, PointId center,
                                         geometry::Point2 c, double reach2, std::vector<PointId>& out) {
  frontier_.clear();
  // The center is walked through when in reach (a path may pass it), never returned.
  const auto visit = [&](PointId w) {
    if (!first_visit(w)) return;
    const geometry::Vector2 d = kdt.position_now(w) - c;
    if (geometry::dot(d, d) > reach2) return;
    frontier_.push_back(w);
    if (w != center) out.push_back(w);
  };
  visit(start);
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
