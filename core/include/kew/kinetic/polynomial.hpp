#pragma once
// Real polynomials of degree ≤ 4: the certificate functions of a kinetic Delaunay
// triangulation of linearly moving points (thesis Eq. 7.1). The variable is time in
// seconds local to the engine's current time (SPEC §4), never epoch seconds.

#include <array>
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
  int degree() const;
  bool is_zero() const { return degree() < 0; }
  double coefficient(int i) const { return c_[static_cast<unsigned>(i)]; }
  void set_coefficient(int i, double v) { c_[static_cast<unsigned>(i)] = v; }
  /// Value at t (Horner).
  double operator()(double t) const;
  Polynomial derivative() const;
  /// Largest absolute coefficient; 0 for the zero polynomial.
  double max_abs_coefficient() const;

  friend Polynomial operator+(const Polynomial& a, const Polynomial& b);
  friend Polynomial operator-(const Polynomial& a, const Polynomial& b);
  friend Polynomial operator*(double s, const Polynomial& a);
  /// Product; the caller guarantees deg a + deg b ≤ kMaxDegree (checked by assert).
  friend Polynomial operator*(const Polynomial& a, const Polynomial& b);

 private:
  std::array<double, kMaxDegree + 1> c_{};
};

}  // namespace kew::kinetic
