// The 3-vector of the contact laws (header-only, no SIMD of its own).
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

namespace granwave::contact {

// A plain 3-vector. Unlike Eigen::Vector3d it carries no SIMD of its own, so a loop over
// contacts that calls these laws vectorises across contacts; sums run left to right,
// (a_0 b_0 + a_1 b_1) + a_2 b_2, the order Eigen used, so results are unchanged.
struct Vec3 {
  double vx = 0.0, vy = 0.0, vz = 0.0;
  Vec3() = default;
  Vec3(double x, double y, double z) : vx(x), vy(y), vz(z) {}
  static Vec3 Zero() { return {}; }
  double x() const { return vx; }
  double y() const { return vy; }
  double z() const { return vz; }
  double dot(const Vec3& b) const { return vx * b.vx + vy * b.vy + vz * b.vz; }
  double squaredNorm() const { return dot(*this); }
  double norm() const { return std::sqrt(squaredNorm()); }
  Vec3 normalized() const { return *this / norm(); }
  Vec3 cross(const Vec3& b) const { return {vy * b.vz - vz * b.vy, vz * b.vx - vx * b.vz, vx * b.vy - vy * b.vx}; }
  friend Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.vx + b.vx, a.vy + b.vy, a.vz + b.vz}; }
  friend Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.vx - b.vx, a.vy - b.vy, a.vz - b.vz}; }
  friend Vec3 operator-(const Vec3& a) { return {-a.vx, -a.vy, -a.vz}; }
  friend Vec3 operator*(double s, const Vec3& a) { return {s * a.vx, s * a.vy, s * a.vz}; }
  friend Vec3 operator*(const Vec3& a, double s) { return {a.vx * s, a.vy * s, a.vz * s}; }
  friend Vec3 operator/(const Vec3& a, double s) { return {a.vx / s, a.vy / s, a.vz / s}; }
};

// c ? a : b, bit for bit, as a blend of the two bit patterns: no branch. Both sides are
// computed anyway; written as a ternary, GCC moves the arithmetic of a side into a branch that
// only it needs, and a loop with arithmetic under a branch vectorises only with AVX-512's masked
// operations (-ftrapping-math forbids executing it unconditionally). With select the loop over
// contacts vectorises on AVX2 as well, with the same bits.
inline double select(bool c, double a, double b) {
  const std::uint64_t m = std::uint64_t{0} - static_cast<std::uint64_t>(c);
  return std::bit_cast<double>((std::bit_cast<std::uint64_t>(a) & m) | (std::bit_cast<std::uint64_t>(b) & ~m));
}
// Componentwise.
inline Vec3 select(bool c, const Vec3& a, const Vec3& b) {
  return {select(c, a.vx, b.vx), select(c, a.vy, b.vy), select(c, a.vz, b.vz)};
}

}  // namespace granwave::contact
