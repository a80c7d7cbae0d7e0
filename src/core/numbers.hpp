// Numbers every part of granwave uses: the NaN that marks a quantity not measured or not defined.
#pragma once
#include <cmath>
#include <limits>

namespace granwave {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// std::round's value (halves away from zero) for every double, inlined: GCC calls libm's round,
// which cost more than the distance test around it in the touching pairs' search (a periodic
// image per axis and candidate). trunc is one instruction (SSE4.1), and x - trunc(x) is exact.
inline double round_half_away(double x) {
  const double t = std::trunc(x);
  return std::abs(x - t) >= 0.5 ? t + std::copysign(1.0, x) : t;
}

}  // namespace granwave
