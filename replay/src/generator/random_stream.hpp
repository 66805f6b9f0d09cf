#pragma once
// Random draws whose results are the same on every platform: std::uniform_real_distribution
// and std::normal_distribution are implementation-defined, so the generator draws through
// this class only. Everything but exponential() uses integer arithmetic and IEEE-754
// basic operations (kew builds in ISO mode, where GCC does not contract a·b + c to FMA).

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace kew::replay::detail {

/// SplitMix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators",
/// OOPSLA 2014): 8 bytes of state, so every aircraft can own independent streams.
class RandomStream {
 public:
  explicit RandomStream(std::uint64_t seed = 0) : state_(seed) {}

  /// 64 uniformly distributed bits.
  std::uint64_t bits() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1), a multiple of 2⁻⁵³.
  double uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }

  /// Uniform in [lo, hi) (lo ≤ hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

  /// Uniform integer in [0, n), n ≥ 1 (bias below 2⁻⁵³·n, irrelevant here).
  std::size_t index(std::size_t n) {
    const auto i = static_cast<std::size_t>(uniform() * static_cast<double>(n));
    return i < n ? i : n - 1;
  }

  /// True with probability p.
  bool chance(double p) { return uniform() < p; }

  /// Standard normal approximated by Irwin–Hall: the sum of twelve uniforms minus 6 has
  /// mean 0 and variance 1 and is bounded at ±6. The twelve uniforms are the 16-bit
  /// quarters of three draws, so the sum is an exact integer.
  double gaussian() {
    std::uint64_t sum = 0;
    for (int draw = 0; draw < 3; ++draw) {
      const std::uint64_t word = bits();
      sum += (word & 0xFFFF) + ((word >> 16) & 0xFFFF) + ((word >> 32) & 0xFFFF) + (word >> 48);
    }
    // Each quarter q stands for the uniform (q + ½)/65536, whose mean is ½; subtracting 6
    // from the twelve of them leaves (sum − (6·65536 − 6))/65536.
    constexpr double kCentre = 6.0 * 65536.0 - 6.0;
    return (static_cast<double>(sum) - kCentre) * 0x1.0p-16;
  }

  /// Exponential with the given mean (> 0). Uses std::log1p: identical wherever the C
  /// library's log1p is (used only for early terminations).
  double exponential(double mean) { return -mean * std::log1p(-uniform()); }

 private:
  std::uint64_t state_;
};

}  // namespace kew::replay::detail
