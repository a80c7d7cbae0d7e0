// Counter-based random numbers: a stream depends only on (seed, stream index), so an
// ensemble member's draw is the same for any thread count or run order.
#pragma once
#include <cstdint>

namespace granwave {

// SplitMix64 finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mixer.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// The n-th number of stream `stream` under `seed`; no state, so any draw can be recomputed.
class CounterRng {
 public:
  constexpr CounterRng(std::uint64_t seed, std::uint64_t stream)
      : key_(mix64(seed ^ mix64(stream + 0x632be59bd9b4e019ULL))) {}
  constexpr std::uint64_t next_u64() { return mix64(key_ + mix64(counter_++)); }
  // Uniform in [0, 1) with 53 random bits.
  constexpr double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  // Uniform integer in [0, n), unbiased (rejection).
  constexpr std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = ~std::uint64_t{0} - (~std::uint64_t{0} % n);
    std::uint64_t x;
    do { x = next_u64(); } while (x >= limit);
    return x % n;
  }

 private:
  std::uint64_t key_;
  std::uint64_t counter_ = 0;
};

}  // namespace granwave
