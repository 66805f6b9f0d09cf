#pragma once
// Real polynomials of degree ≤ 4: the certificate functions of a kinetic Delaunay
// triangulation of linearly moving points (thesis Eq. 7.1). The variable is time in
// seconds local to the engine's current time (design §4.1), never epoch seconds.

#include <array>
#include <cassert>
#include <initializer_list>

namespace kew::kinetic {

class Polynomial {
 public:
  static constexpr int kMaxDegree = 4;

  /// The zero polynomial.
  constexpr Polynomial() = default;
  /// Coefficients from the constant term upwards: {a0, a1, ...}, at most kMaxDegree + 1.
  Polynomial(std::initializer_list<double> low_to_high);

  /// Degree of the polynomial, -1 for the zero polynomial (exact zero coefficients).
  int degree() const {
    for (int i = kMaxDegree; i >= 0; --i)
      if (c_[static_cast<unsigned>(i)] != 0.0) return i;
    return -1;
  }
  bool is_zero() const { return degree() < 0; }
  double coefficient(int i) const { return c_[static_cast<unsigned>(i)]; }
  void set_coefficient(int i, double v) { c_[static_cast<unsigned>(i)] = v; }
  /// Value at t (Horner).
  double operator()(double t) const {
    double v = c_[kMaxDegree];
    for (int i = kMaxDegree - 1; i >= 0; --i) v = v * t + c_[static_cast<unsigned>(i)];
    return v;
  }
  Polynomial derivative() const;
  /// Largest absolute coefficient; 0 for the zero polynomial.
  double max_abs_coefficient() const;

  // Inline: building one incircle certificate takes some thirty of these.
  friend Polynomial operator+(const Polynomial& a, const Polynomial& b) {
    Polynomial r;
    for (unsigned i = 0; i < r.c_.size(); ++i) r.c_[i] = a.c_[i] + b.c_[i];
    return r;
  }
  friend Polynomial operator-(const Polynomial& a, const Polynomial& b) {
    Polynomial r;
    for (unsigned i = 0; i < r.c_.size(); ++i) r.c_[i] = a.c_[i] - b.c_[i];
    return r;
  }
  friend Polynomial operator*(double s, const Polynomial& a) {
    Polynomial r;
    for (unsigned i = 0; i < r.c_.size(); ++i) r.c_[i] = s * a.c_[i];
    return r;
  }
  /// Product; the caller guarantees deg a + deg b ≤ kMaxDegree (checked by assert).
  friend Polynomial operator*(const Polynomial& a, const Polynomial& b) {
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

 private:
  std::array<double, kMaxDegree + 1> c_{};
};

}  // namespace kew::kinetic
