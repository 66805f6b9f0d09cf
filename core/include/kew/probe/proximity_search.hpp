#pragma once
// Candidate search for the conflict probe (design §2.1): the kinetic Delaunay
// triangulation used as an exact proximity index.
//
// Every point within distance r of a point x is reached by a breadth-first search over
// Delaunay edges that starts at the vertex nearest to x and never leaves the disk of
// radius r around x: greedy routing toward x succeeds on a Delaunay triangulation (from
// any vertex but the nearest, some neighbour is strictly closer to x), so each point in
// the disk is joined to the nearest vertex by a path that stays in the disk, and the
// same greedy walk finds the nearest vertex (design §2.1).

#include <cstdint>
#include <string_view>
#include <vector>

#include "kew/kinetic/kinetic_delaunay.hpp"
#include "kew/util/name_table.hpp"

namespace kew::probe {

using kinetic::PointId;

enum class ProbeMode : std::uint8_t {
  Exact,  ///< BFS within R_i (complete; the default)
  Edges,  ///< Delaunay neighbours only (the thesis; misses stacked conflicts)
  Brute,  ///< every live track (the oracle)
};

/// The names of `probe = ...` and `--probe`.
inline constexpr util::NameTable<ProbeMode, 3> kProbeModeNames({{
    {ProbeMode::Exact, "exact"},
    {ProbeMode::Edges, "edges"},
    {ProbeMode::Brute, "brute"},
}});
constexpr std::string_view to_string(ProbeMode mode) { return kProbeModeNames.name(mode); }

class ProximitySearch {
 public:
  /// Appends to `out` (not cleared) every point other than `center` whose model position
  /// at kdt.now() is within `radius_m` of center's, plus possibly a few points slightly
  /// farther (twins within their release distance of the disk). Order unspecified.
  void within(const kinetic::KineticDelaunay& kdt, PointId center, double radius_m, std::vector<PointId>& out);

  /// The same for a disk around any point `target` of the plane (m), which need not hold
  /// `center`: every point other than `center` whose model position at kdt.now() is
  /// within `radius_m` of `target`, plus possibly twins slightly farther. The search spreads
  /// from center's vertex when it lies in the disk, otherwise from the vertex nearest
  /// `target`, reached by a greedy walk.
  void within_around(const kinetic::KineticDelaunay& kdt, PointId center, geometry::Point2 target, double radius_m,
                     std::vector<PointId>& out);

  /// Appends the Delaunay neighbours of `center` (twins counted) — the thesis' candidates.
  void neighbours(const kinetic::KineticDelaunay& kdt, PointId center, std::vector<PointId>& out);

 private:
  using FaceIndex = triangulation::FaceIndex;
  /// New marks for one search; the reach (radius widened for twins, squared).
  double begin_search(const kinetic::KineticDelaunay& kdt, double radius_m);
  /// The search from `start`, the point nearest c (c's own point for within()), over
  /// faces or vertex rings as below; `center` is never returned.
  void search_from(const kinetic::KineticDelaunay& kdt, PointId start, PointId center, geometry::Point2 c,
                   double reach2, std::vector<PointId>& out);
  /// Over faces (a triangulation with a finite face), from start's vertex ...
  void within_by_faces(const kinetic::KineticDelaunay& kdt, PointId start, PointId center, geometry::Point2 c,
                       double reach2, std::vector<PointId>& out);
  /// ... or over vertex rings (flat or tiny triangulations, which have no finite face).
  void within_by_vertices(const kinetic::KineticDelaunay& kdt, PointId start, PointId center, geometry::Point2 c,
                          double reach2, std::vector<PointId>& out);
  /// The greedy walk: from `from`, to ever closer neighbours of c until none is closer.
  static PointId nearest_to(const kinetic::KineticDelaunay& kdt, PointId from, geometry::Point2 c);
  /// Whether a triangulation vertex or one of its twins is within reach of c, each
  /// decided once per search; the first time, appends those in reach (center excepted).
  /// Inline: a vertex is met from each of its ~6 faces and decided at the first.
  bool group_in_reach(const kinetic::KineticDelaunay& kdt, PointId vertex, PointId center, geometry::Point2 c,
                      double reach2, std::vector<PointId>& out) {
    const std::uint32_t mark = visited_round_[vertex];
    if (mark == round_ + 1) return true;
    if (mark == round_) return false;
    return first_group_in_reach(kdt, vertex, center, c, reach2, out);
  }
  /// group_in_reach() the first time the search meets `vertex`: decides and marks it.
  bool first_group_in_reach(const kinetic::KineticDelaunay& kdt, PointId vertex, PointId center,
                            geometry::Point2 c, double reach2, std::vector<PointId>& out);
  /// Marks p visited in this search (vertex search); false when it already was.
  bool first_visit(PointId p) {
    if (visited_round_[p] == round_) return false;
    visited_round_[p] = round_;
    return true;
  }
  /// kdt.for_each_neighbor(id, f) without its copy and sort; may call f twice for one
  /// point (a flat chain's end).
  template <class F>
  static void for_each_neighbor(const kinetic::KineticDelaunay& kdt, PointId id, F&& f);

  std::vector<std::uint32_t> visited_round_;  // by point id
  std::vector<std::uint32_t> face_round_;     // by face index
  std::uint32_t round_ = 0;                   // even; see within()
  std::vector<PointId> frontier_;
  std::vector<FaceIndex> face_frontier_;
};

}  // namespace kew::probe
