// Numbers every part of granwave uses: the NaN that marks a quantity not measured or not defined.
#pragma once
#include <limits>

namespace granwave {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace granwave
