#include "delaunay_oracle.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>

namespace kew::testing {
namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Dt = CGAL::Delaunay_triangulation_2<Kernel, Tds>;
}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> cgal_delaunay_edges(
    const std::vector<std::pair<std::uint32_t, geometry::Point2>>& points) {
  std::vector<std::pair<Kernel::Point_2, std::uint32_t>> input;
  input.reserve(points.size());
  for (const auto& [id, p] : points) input.emplace_back(Kernel::Point_2(p.x, p.y), id);
  Dt dt(input.begin(), input.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const auto f = e->first;
    const int i = e->second;
    const std::uint32_t a = f->vertex(Dt::cw(i))->info();
    const std::uint32_t b = f->vertex(Dt::ccw(i))->info();
    edges.emplace_back(std::min(a, b), std::max(a, b));
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

bool in_general_position(const std::vector<geometry::Point2>& points) {
  // Checked through CGAL's own triangulation: any cocircular quadruple of a Delaunay
  // edge or collinear triple on a face is what makes the triangulation ambiguous.
  std::vector<Kernel::Point_2> input;
  for (const auto& p : points) input.emplace_back(p.x, p.y);
  Dt dt(input.begin(), input.end());
  if (dt.dimension() < 2) return false;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const auto f = e->first;
    const int i = e->second;
    const auto g = f->neighbor(i);
    if (dt.is_infinite(f) || dt.is_infinite(g)) {
      // Collinear hull triples make the hull edges ambiguous for the comparison.
      continue;
    }
    const auto& d = g->vertex(g->index(f))->point();
    if (CGAL::side_of_oriented_circle(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point(), d) ==
        CGAL::ON_ORIENTED_BOUNDARY)
      return false;
  }
  // Collinear hull vertices.
  auto c = dt.incident_vertices(dt.infinite_vertex());
  const auto done = c;
  do {
    auto prev = c;
    auto cur = std::next(prev);
    auto next = std::next(cur);
    if (CGAL::orientation(prev->point(), cur->point(), next->point()) == CGAL::COLLINEAR) return false;
    ++c;
  } while (c != done);
  return true;
}

}  // namespace kew::testing
