// (b) cgal: a static Delaunay triangulation rebuilt by CGAL every period (spatial sort,
// then insertion with a hint; Epick), searched breadth-first from a vertex in the disk.

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/spatial_sort.h>

#include <cstdint>
#include <memory>
#include <numeric>
#include <vector>

#include "baseline.hpp"
#include "cgal_types.hpp"

namespace kew::bench::peers {

namespace {

struct VertexInfo {
  Slot first = kNone;      // a track at this point; others at exactly the same point chain on
  std::uint32_t seen = 0;  // BFS round that visited the vertex
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<VertexInfo, cgal::Kernel>;
using Structure = CGAL::Triangulation_data_structure_2<VertexBase>;
using Triangulation = CGAL::Delaunay_triangulation_2<cgal::Kernel, Structure>;

class CgalRebuild {
 public:
  void rebuild(const World& world, double t0, PeriodResult&) {
    dt_.clear();
    points_.clear();
    slots_.clear();
    for (Slot s = 0; s < world.live.size(); ++s) {
      if (!world.live[s]) continue;
      const Point2 p = world.state[s].at(t0).position;
      points_.emplace_back(p.x, p.y);
      slots_.push_back(s);
    }
    order_.resize(points_.size());
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    CGAL::spatial_sort(order_.begin(), order_.end(), cgal::SortTraits(CGAL::make_property_map(points_)));
    vertex_of_.assign(world.live.size(), {});
    same_point_next_.assign(world.live.size(), kNone);
    Triangulation::Face_handle hint;
    for (const std::size_t i : order_) {
      const auto v = dt_.insert(points_[i], hint);
      hint = v->face();
      const Slot s = slots_[i];
      same_point_next_[s] = v->info().first;  // kNone unless a duplicate
      v->info().first = s;
      vertex_of_[s] = v;
    }
  }

  template <class F>
  void for_each_candidate(const World& world, Slot slot, Point2 centre, double radius, F&& f) {
    if (dt_.number_of_vertices() == 0) return;
    const cgal::CgalPoint c(centre.x, centre.y);
    // Any vertex in the disk will do as a start (see ProximitySearch): the track's own,
    // or the nearest to the centre for a track that is not in the index.
    const auto start = slot < vertex_of_.size() && world.indexed[slot] ? vertex_of_[slot] : dt_.nearest_vertex(c);
    const double r2 = radius * radius;
    if (CGAL::squared_distance(start->point(), c) > r2) return;
    if (++round_ == 0) round_ = 1;  // a wrapped mark could only add candidates
    frontier_.assign(1, start);
    start->info().seen = round_;
    for (std::size_t next = 0; next < frontier_.size(); ++next) {
      const auto v = frontier_[next];
      for (Slot s = v->info().first; s != kNone; s = same_point_next_[s]) f(s);
      if (dt_.dimension() < 2) {  // all collinear: CGAL gives no faces, try every vertex
        for (auto it = dt_.finite_vertices_begin(); it != dt_.finite_vertices_end(); ++it)
          if (it->info().seen != round_) {
            it->info().seen = round_;
            frontier_.push_back(it);
          }
        continue;
      }
      auto around = dt_.incident_vertices(v);
      const auto done = around;
      do {
        if (dt_.is_infinite(around) || around->info().seen == round_) continue;
        around->info().seen = round_;
        if (CGAL::squared_distance(around->point(), c) <= r2) frontier_.push_back(around);
      } while (++around != done);
    }
  }

  std::uint64_t audit() const { return dt_.is_valid() ? 0 : 1; }

 private:
  Triangulation dt_;
  std::vector<cgal::CgalPoint> points_;
  std::vector<Slot> slots_;
  std::vector<std::size_t> order_;
  std::vector<Triangulation::Vertex_handle> vertex_of_;
  std::vector<Slot> same_point_next_;
  std::vector<Triangulation::Vertex_handle> frontier_;
  std::uint32_t round_ = 0;
};

}  // namespace

std::unique_ptr<Method> make_cgal_rebuild() {
  return std::make_unique<Baseline<CgalRebuild>>(
      "cgal", "CGAL Delaunay_triangulation_2 (Epick) rebuilt per period, spatial sort + BFS", 1);
}

}  // namespace kew::bench::peers
