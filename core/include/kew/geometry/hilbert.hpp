#pragma once
// Hilbert-curve order of planar points, for memory order (design §8.3):
// points close along the curve are close in the plane, so structures numbered in this
// order keep neighbours in nearby memory.

#include <cstdint>
#include <vector>

#include "kew/geometry/vector2.hpp"

namespace kew::geometry {

/// The distance along the Hilbert curve of order `order` (a 2^order × 2^order grid,
/// order in [1, 31]) of cell (x, y), x and y in [0, 2^order): 0 at cell (0, 0), then
/// (0, 1), (1, 1), (1, 0) at order 1, each cell 4-adjacent to the cell before it, the
/// last at (2^order − 1, 0). Arguments outside those ranges give an unspecified index.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, int order);

/// The indices of `points` sorted along a Hilbert curve of order 16 laid over their
/// bounding box (ties, and non-finite points, which go last, in index order).
std::vector<std::uint32_t> hilbert_order(const std::vector<Point2>& points);

}  // namespace kew::geometry
