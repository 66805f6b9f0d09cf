#include "kew/kinetic/polynomial.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace kew::kinetic {

Polynomial::Polynomial(std::initializer_list<double> low_to_high) {
  assert(low_to_high.size() <= c_.size());
  std::copy(low_to_high.begin(), low_to_high.end(), c_.begin());
}

int Polynomial::degree() const {
  for (int i = kMaxDegree; i >= 0; --i)
    if (c_[static_cast<unsigned>(i)] != 0.0) return i;
  return -1;
}

double Polynomial::operator()(double t) const {
  double v = c_[kMaxDegree];
  for (int i = kMaxDegree - 1; i >= 0; --i) v = v * t + c_[static_cast<unsigned>(i)];
  return v;
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

Polynomial operator+(const Polynomial& a, const Polynomial& b) {
  Polynomial r;
  for (unsigned i = 0; i < r.c_.size(); ++i) r.c_[i] = a.c_[i] + b.c_[i];
  return r;
}

Polynomial operator-(const Polynomial& a, const Polynomial& b) {
  Polynomial r;
  for (unsigned i = 0; i < r.c_.size(); ++i) r.c_[i] = a.c_[i] - b.c_[i];
  return r;
}

Polynomial operator*(double s, const Polynomial& a) {
  Polynomial r;
  for (unsigned i = 0; i < r.c_.size(); ++i) r.c_[i] = s * a.c_[i];
  return r;
}

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  const int da = a.degree();
  const int db = b.degree();
  Polynomial r;
  if (da < 0 || db < 0) return r;
  assert(da + db <= Polynomial::kMaxDegree);
  for (int i = 0; i <= da; ++i)
    for (int j = 0; j <= db; ++j)
      r.c_[static_cast<unsigned>(i + j)] += a.c_[static_cast<unsigned>(i)] * b.c_[static_cast<unsigned>(j)];
  return r;
}

}  // namespace kew::kinetic
