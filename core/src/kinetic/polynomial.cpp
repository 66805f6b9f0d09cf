#include "kew/kinetic/polynomial.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace kew::kinetic {

Polynomial::Polynomial(std::initializer_list<double> low_to_high) {
  assert(low_to_high.size() <= c_.size());
  std::copy(low_to_high.begin(), low_to_high.end(), c_.begin());
}

Polynomial Polynomial::derivative() const {
  Polynomial d;
  for (int i = 1; i <= kMaxDegree; ++i)
    d.c_[static_cast<unsigned>(i - 1)] = static_cast<double>(i) * c_[static_cast<unsigned>(i)];
  return d;
}

double Polynomial::max_abs_coefficient() const {
  double m = 0.0;
  for (double v : c_) m = std::max(m, std::abs(v));
  return m;
}

}  // namespace kew::kinetic
