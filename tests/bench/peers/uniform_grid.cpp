// (d) grid: a uniform grid of R_max cells rebuilt every period.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <vector>

#include "baseline.hpp"

namespace kew::bench::peers {

namespace {

class UniformGrid {
 public:
  explicit UniformGrid(double cell_m) : cell_(cell_m) {}

  void rebuild(const World& world, double t0, PeriodResult&) {
    entries_.clear();
    double min_x = INFINITY, min_y = INFINITY, max_x = -INFINITY, max_y = -INFINITY;
    for (Slot s = 0; s < world.live.size(); ++s) {
      if (!world.live[s]) continue;
      const Point2 p = world.state[s].at(t0).position;
      entries_.push_back({p, s});
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
    }
    if (entries_.empty()) return;
    origin_ = {min_x, min_y};
    columns_ = static_cast<std::size_t>((max_x - min_x) / cell_) + 1;
    rows_ = static_cast<std::size_t>((max_y - min_y) / cell_) + 1;
    // Counting sort of the entries by cell: each cell's entries are contiguous.
    cell_start_.assign(columns_ * rows_ + 1, 0);
    for (const Entry& e : entries_) ++cell_start_[cell_of(e.p) + 1];
    std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
    sorted_.resize(entries_.size());
    fill_.assign(cell_start_.begin(), cell_start_.end() - 1);
    for (const Entry& e : entries_) sorted_[fill_[cell_of(e.p)]++] = e;
  }

  template <class F>
  void for_each_candidate(const World&, Slot, Point2 centre, double radius, F&& f) const {
    if (sorted_.empty()) return;
    const double r2 = radius * radius;
    const std::size_t x0 = clamp_cell(centre.x - radius - origin_.x, columns_);
    const std::size_t x1 = clamp_cell(centre.x + radius - origin_.x, columns_);
    const std::size_t y0 = clamp_cell(centre.y - radius - origin_.y, rows_);
    const std::size_t y1 = clamp_cell(centre.y + radius - origin_.y, rows_);
    for (std::size_t y = y0; y <= y1; ++y)
      for (std::size_t i = cell_start_[y * columns_ + x0]; i < cell_start_[y * columns_ + x1 + 1]; ++i)
        if (squared_distance(sorted_[i].p, centre) <= r2) f(sorted_[i].slot);
  }

  std::uint64_t audit() const { return 0; }

 private:
  struct Entry {
    Point2 p;
    Slot slot;
  };
  std::size_t clamp_cell(double offset, std::size_t count) const {
    const double cell = std::floor(offset / cell_);
    return cell <= 0.0 ? 0 : std::min(count - 1, static_cast<std::size_t>(cell));
  }
  std::size_t cell_of(Point2 p) const {
    return clamp_cell(p.y - origin_.y, rows_) * columns_ + clamp_cell(p.x - origin_.x, columns_);
  }

  double cell_;
  Point2 origin_;
  std::size_t columns_ = 0, rows_ = 0;
  std::vector<Entry> entries_, sorted_;
  std::vector<std::size_t> cell_start_, fill_;
};

}  // namespace

std::unique_ptr<Method> make_uniform_grid(double cell_m) {
  return std::make_unique<Baseline<UniformGrid>>("grid", "uniform grid (cell = R_max) rebuilt per period", 1, cell_m);
}

}  // namespace kew::bench::peers
