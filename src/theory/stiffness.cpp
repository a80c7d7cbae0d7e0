// The micro-macro stiffness tensor of seed 002 eq. (10) and its sound speeds (theory/stiffness.hpp).
#include "theory/stiffness.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace granwave::theory {

Tensor4& Tensor4::operator+=(const Tensor4& o) {
  for (std::size_t i = 0; i < c_.size(); ++i) c_[i] += o.c_[i];
  return *this;
}

Tensor4 Tensor4::operator*(double s) const {
  Tensor4 r = *this;
  for (auto& v : r.c_) v *= s;
  return r;
}

namespace {
double max_abs(const std::array<double, 81>& c) {
  double m = 0.0;
  for (double v : c) m = std::max(m, std::abs(v));
  return m;
}

// The largest |C_abgf - C_(permuted)| over every index and every given permutation, relative to the
// largest entry (0 for the zero tensor).
template <class... Permuted>
double relative_asymmetry(const Tensor4& t, Permuted... permuted) {
  const double scale = max_abs(t.data());
  if (scale == 0.0) return 0.0;
  double m = 0.0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int g = 0; g < 3; ++g)
        for (int f = 0; f < 3; ++f) ((m = std::max(m, std::abs(t(a, b, g, f) - permuted(a, b, g, f)))), ...);
  return m / scale;
}
}  // namespace

double Tensor4::major_asymmetry() const {
  return relative_asymmetry(*this, [this](int a, int b, int g, int f) { return (*this)(g, f, a, b); });
}

double Tensor4::minor_asymmetry() const {
  return relative_asymmetry(*this, [this](int a, int b, int g, int f) { return (*this)(b, a, g, f); },
                            [this](int a, int b, int g, int f) { return (*this)(a, b, f, g); });
}

Tensor4 Tensor4::symmetrised() const {
  Tensor4 s;
  const Tensor4& c = *this;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int g = 0; g < 3; ++g)
        for (int f = 0; f < 3; ++f) {
          const double minor = c(a, b, g, f) + c(b, a, g, f) + c(a, b, f, g) + c(b, a, f, g);
          const double major = c(g, f, a, b) + c(g, f, b, a) + c(f, g, a, b) + c(f, g, b, a);
          s(a, b, g, f) = (minor + major) / 8.0;
        }
  return s;
}

Voigt6 Tensor4::voigt() const {
  // Voigt pairs in the order xx, yy, zz, yz, xz, xy.
  static constexpr int pair[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  Voigt6 v;
  for (int I = 0; I < 6; ++I)
    for (int J = 0; J < 6; ++J) v(I, J) = (*this)(pair[I][0], pair[I][1], pair[J][0], pair[J][1]);
  return v;
}

Eigen::Matrix3d Tensor4::christoffel(const Vec3& m) const {
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  for (int b = 0; b < 3; ++b)
    for (int f = 0; f < 3; ++f)
      for (int a = 0; a < 3; ++a)
        for (int g = 0; g < 3; ++g) G(b, f) += (*this)(a, b, g, f) * m[a] * m[g];
  return G;
}

Tensor4 stiffness_tensor(std::span<const ContactGeometry> contacts, double volume, bool include_kt) {
  if (!(volume > 0.0)) throw InputError("stiffness_tensor: the representative volume must be > 0");
  Tensor4 C;
  for (const auto& c : contacts) {
    const double l2 = c.branch.squaredNorm();
    if (l2 == 0.0) throw InputError("stiffness_tensor: a contact has a zero branch vector");
    const Vec3 n = c.branch / std::sqrt(l2);
    // Eq. (10): each contact end carries l^2/2; `weight` counts the ends inside V (1 = both).
    const double wn = c.weight * l2 * c.k;
    const double wt = include_kt ? c.weight * l2 * c.kt : 0.0;
    // Tangent-plane projector: sum over the two tangents t t = I - n n.
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int g = 0; g < 3; ++g)
          for (int f = 0; f < 3; ++f) {
            double v = wn * n[a] * n[b] * n[g] * n[f];
            if (wt != 0.0) v += wt * n[a] * n[g] * P(b, f);
            C(a, b, g, f) += v;
          }
  }
  return C * (1.0 / volume);
}

}  // namespace granwave::theory
