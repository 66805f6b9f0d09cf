// (e) brute: every live track for every update (BlueSky's state-based detection tests
// all pairs, the same CPA), sampled when it would take too long.

#include <cstdint>
#include <memory>

#include "baseline.hpp"

namespace kew::bench::peers {

namespace {

class BruteForce {
 public:
  void rebuild(const World&, double, PeriodResult&) {}
  template <class F>
  void for_each_candidate(const World& world, Slot, Point2, double, F&& f) const {
    for (Slot s = 0; s < world.live.size(); ++s)  // the live ones not indexed are the driver's extras
      if (world.indexed[s]) f(s);
  }
  std::uint64_t audit() const { return 0; }
};

}  // namespace

std::unique_ptr<Method> make_brute_force(std::size_t sample_stride) {
  return std::make_unique<Baseline<BruteForce>>("brute", "brute force, all pairs per update (BlueSky state-based)",
                                                sample_stride);
}

}  // namespace kew::bench::peers
