// printf into a std::string: the one formatting helper of the text reports, guards and messages.
#pragma once
#include <algorithm>
#include <cstdio>
#include <string>

namespace granwave {

template <class... T>
std::string fmt(const char* format, T... x) {
  const int n = std::snprintf(nullptr, 0, format, x...);
  std::string out(static_cast<std::size_t>(std::max(n, 0)) + 1, '\0');
  std::snprintf(out.data(), out.size(), format, x...);
  out.pop_back();
  return out;
}

}  // namespace granwave
