#pragma once
// The test oracle: a static Delaunay triangulation computed by CGAL from scratch.

#include <cstdint>
#include <utility>
#include <vector>

#include "kew/geometry/vector2.hpp"

namespace kew::testing {

/// Finite Delaunay edges of the given points as (smaller id, larger id) pairs, sorted.
/// Ids are the caller's; points must be pairwise distinct.
std::vector<std::pair<std::uint32_t, std::uint32_t>> cgal_delaunay_edges(
    const std::vector<std::pair<std::uint32_t, geometry::Point2>>& points);

/// True when no four points are cocircular and no three collinear (exact), i.e. the
/// Delaunay triangulation is unique and an edge-set comparison is meaningful.
bool in_general_position(const std::vector<geometry::Point2>& points);

}  // namespace kew::testing
