// (c) flip: one triangulation kept across periods; every position updated in place at
// the period's start, every edge checked (exact incircle) and repaired by Lawson flips
// (a full rebuild when a face folded over).

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "baseline.hpp"
#include "kew/triangulation/delaunay.hpp"

namespace kew::bench::peers {

namespace {

class FlipRepair {
 public:
  void rebuild(const World& world, double t0, PeriodResult& out) {
    using kew::triangulation::kNoVertex;
    using kew::triangulation::Trajectory;
    if (vertex_of_.size() < world.live.size()) vertex_of_.resize(world.live.size(), kNoVertex);
    for (std::vector<Slot>& extra : same_point_) extra.clear();
    // Tracks gone since the last period leave first, at the positions the structure holds.
    bool broken = false;
    for (Slot s = 0; s < vertex_of_.size(); ++s) {
      const auto v = vertex_of_[s];
      if (v == kNoVertex || world.live[s]) continue;
      if (dt_.is_attached(v)) {
        const kew::triangulation::DetachResult detached = dt_.detach(v);
        broken = broken || !detached.hole_triangulated;
        // Left out by the rebuild that took: they go back in below, with the new tracks.
        for (const kew::triangulation::Eviction& e : detached.evicted) {
          vertex_of_[slot_of_vertex_[e.vertex]] = kNoVertex;
          dt_.destroy_vertex(e.vertex);
        }
      }
      dt_.destroy_vertex(v);
      vertex_of_[s] = kNoVertex;
    }
    // Every remaining vertex jumps to its track's position at t0 (velocity zero keeps it
    // there exactly while the period is probed).
    for (Slot s = 0; s < vertex_of_.size(); ++s)
      if (vertex_of_[s] != kNoVertex) dt_.set_trajectory(vertex_of_[s], Trajectory{world.state[s].at(t0).position, {}, t0});
    dt_.set_time(t0);
    // Check: a folded face (a point moved across an edge) cannot be repaired by flips.
    const kew::triangulation::Tds& tds = dt_.tds();
    seeds_.clear();
    for (kew::triangulation::FaceIndex f = 0; f < tds.face_capacity() && !broken; ++f) {
      if (!tds.face(f).alive) continue;
      if (!dt_.is_positive(f)) broken = true;
      for (int i = 0; i < 3; ++i) seeds_.emplace_back(f, i);
    }
    if (!broken) {
      stuck_.clear();
      out.flips += dt_.make_locally_delaunay(seeds_, &stuck_);
      broken = !stuck_.empty();
    }
    if (broken) {
      ++out.fallbacks;
      for (const auto& [vertex, same] : dt_.rebuild()) forget_duplicate(vertex, same);
    }
    // New tracks are inserted into the repaired triangulation.
    for (Slot s = 0; s < world.live.size(); ++s) {
      if (!world.live[s] || vertex_of_[s] != kNoVertex) continue;
      const auto v = dt_.create_vertex(Trajectory{world.state[s].at(t0).position, {}, t0});
      vertex_of_[s] = v;
      grow_slot_map(v);
      slot_of_vertex_[v] = s;
      kew::triangulation::VertexIndex same = kNoVertex;
      if (dt_.attach(v, &same, valid_hint()) == kew::triangulation::AttachResult::Duplicate) forget_duplicate(v, same);
      else hint_ = tds.vertex_face(v);
    }
  }

  template <class F>
  void for_each_candidate(const World& world, Slot slot, Point2 centre, double radius, F&& f) {
    using kew::triangulation::kInfiniteVertex;
    if (dt_.size() == 0) return;
    const kew::triangulation::Tds& tds = dt_.tds();
    const bool own = slot < vertex_of_.size() && world.indexed[slot] && vertex_of_[slot] != kew::triangulation::kNoVertex;
    const auto start = own ? vertex_of_[slot] : nearest_vertex(centre);
    const double r2 = radius * radius;
    if (squared_distance(dt_.position(start), centre) > r2) return;
    if (seen_.size() < tds.vertex_capacity()) seen_.resize(tds.vertex_capacity(), 0);
    if (++round_ == 0) round_ = 1;
    frontier_.assign(1, start);
    seen_[start] = round_;
    for (std::size_t next = 0; next < frontier_.size(); ++next) {
      const auto v = frontier_[next];
      f(slot_of_vertex_[v]);
      for (const Slot s : same_point_[v]) f(s);
      if (!tds.is_attached(v)) continue;  // fewer than two points: no faces
      tds.for_each_adjacent_vertex(v, [&](kew::triangulation::VertexIndex w) {
        if (w == kInfiniteVertex || seen_[w] == round_) return;
        seen_[w] = round_;
        if (squared_distance(dt_.position(w), centre) <= r2) frontier_.push_back(w);
      });
    }
  }

  std::uint64_t audit() const { return dt_.audit().violations(); }

 private:
  // Greedy walk to the vertex nearest `p`: from any vertex some neighbour is closer to p
  // unless the vertex is the nearest (Delaunay).
  kew::triangulation::VertexIndex nearest_vertex(Point2 p) const {
    const kew::triangulation::Tds& tds = dt_.tds();
    const kew::triangulation::Face& face = tds.face(dt_.locate(p, valid_hint()));
    auto best = face.vertex[0] != kew::triangulation::kInfiniteVertex ? face.vertex[0] : face.vertex[1];
    double best_d2 = squared_distance(dt_.position(best), p);
    for (auto current = kew::triangulation::kNoVertex; current != best;) {
      current = best;
      tds.for_each_adjacent_vertex(current, [&](kew::triangulation::VertexIndex w) {
        if (w == kew::triangulation::kInfiniteVertex) return;
        const double d2 = squared_distance(dt_.position(w), p);
        if (d2 < best_d2) {
          best_d2 = d2;
          best = w;
        }
      });
    }
    return best;
  }
  kew::triangulation::FaceIndex valid_hint() const {
    const kew::triangulation::Tds& tds = dt_.tds();
    return hint_ < tds.face_capacity() && tds.face(hint_).alive ? hint_ : kew::triangulation::kNoFace;
  }
  void grow_slot_map(kew::triangulation::VertexIndex v) {
    if (v >= slot_of_vertex_.size()) {
      slot_of_vertex_.resize(v + 1, kNone);
      same_point_.resize(v + 1);
    }
  }
  // A track at exactly another's position rides along with that vertex this period.
  void forget_duplicate(kew::triangulation::VertexIndex vertex, kew::triangulation::VertexIndex same) {
    const Slot s = slot_of_vertex_[vertex];
    grow_slot_map(same);
    same_point_[same].push_back(s);
    dt_.destroy_vertex(vertex);
    vertex_of_[s] = kew::triangulation::kNoVertex;
  }

  kew::triangulation::DelaunayTriangulation dt_;
  std::vector<kew::triangulation::VertexIndex> vertex_of_;  // by slot
  std::vector<Slot> slot_of_vertex_;
  std::vector<std::vector<Slot>> same_point_;  // by vertex: tracks at exactly its point
  std::vector<std::pair<kew::triangulation::FaceIndex, int>> seeds_, stuck_;
  std::vector<kew::triangulation::VertexIndex> frontier_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t round_ = 0;
  kew::triangulation::FaceIndex hint_ = kew::triangulation::kNoFace;
};

}  // namespace

std::unique_ptr<Method> make_flip_repair() {
  return std::make_unique<Baseline<FlipRepair>>(
      "flip", "positions updated in place, every edge checked (exact incircle), Lawson flips", 1);
}

}  // namespace kew::bench::peers
