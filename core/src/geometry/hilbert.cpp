#include "kew/geometry/hilbert.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace kew::geometry {

std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y, int order) {
  const std::uint32_t side = std::uint32_t{1} << (order - 1) << 1;  // 2^order without 1 << 32
  std::uint64_t index = 0;
  for (std::uint32_t half = side >> 1; half > 0; half >>= 1) {
    const std::uint32_t right = (x & half) != 0 ? 1 : 0;
    const std::uint32_t up = (y & half) != 0 ? 1 : 0;
    index += std::uint64_t{half} * half * ((3 * right) ^ up);
    // The lower quadrants hold the curve rotated (and, bottom right, reflected): bring
    // the point into the frame of the unrotated curve for the finer levels.
    if (up == 0) {
      if (right == 1) {
        x = side - 1 - x;
        y = side - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return index;
}

std::vector<std::uint32_t> hilbert_order(const std::vector<Point2>& points) {
  constexpr int kOrder = 16;
  constexpr double kCells = 65536.0;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Point2& p : points) {
    if (!is_finite(p)) continue;
    x0 = std::min(x0, p.x);
    y0 = std::min(y0, p.y);
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, p.y);
  }
  const double extent = std::max(x1 - x0, y1 - y0);
  const double per_metre = extent > 0.0 ? (kCells - 1.0) / extent : 0.0;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
  for (std::uint32_t i = 0; i < points.size(); ++i) {
    const Point2& p = points[i];
    keyed[i] = {is_finite(p) ? hilbert_index(static_cast<std::uint32_t>((p.x - x0) * per_metre),
                                             static_cast<std::uint32_t>((p.y - y0) * per_metre), kOrder)
                             : UINT64_MAX,
                i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(points.size());
  std::transform(keyed.begin(), keyed.end(), order.begin(), [](const auto& k) { return k.second; });
  return order;
}

}  // namespace kew::geometry
