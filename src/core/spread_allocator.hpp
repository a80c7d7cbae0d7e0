// Storage for the long arrays that the crystal's passes read and write side by side (a particle's
// x, v, f, ... or a contact's columns, each a stream of its own). Every array is aligned to a cache
// line (crystal/simd.hpp's stream4 writes lines whole, not reading them first). A large one (from
// 64 KiB) also starts at a cache-line offset within its page of its own, one of 63, taken in turn:
// the C library gives every large allocation its own mapping at the same offset within a page, so
// that element p of two dozen arrays falls in the same set of the L1 (8 ways) and loads wait on
// stores to other arrays with the same low address bits (4K aliasing). Where an array starts changes
// no result, only the time (docs/benchmarks.md, session 28).
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace granwave {

namespace spread {
inline constexpr std::size_t kLine = 64, kPage = 4096;
inline constexpr std::size_t kLarge = 64 * 1024;  // bytes from which an array is spread
inline constexpr std::size_t kSlots = kPage / kLine - 1;  // offsets 64 .. 4032 bytes
// The offset of the next large array: 29 is prime to 63, so 63 arrays in a row take every slot.
inline std::size_t next_offset() {
  static std::atomic<std::size_t> count{0};
  return kLine * (1 + (count.fetch_add(1, std::memory_order_relaxed) * 29) % kSlots);
}
}  // namespace spread

template <class T>
struct SpreadAllocator {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = SpreadAllocator<U>;
  };
  SpreadAllocator() = default;
  template <class U>
  SpreadAllocator(const SpreadAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < spread::kLarge) return static_cast<T*>(::operator new(bytes, std::align_val_t{spread::kLine}));
    // A page-aligned block one page longer; the array starts at its offset within the first page,
    // so the block's start is the array's rounded down to the page.
    auto* block = static_cast<unsigned char*>(::operator new(bytes + spread::kPage, std::align_val_t{spread::kPage}));
    return reinterpret_cast<T*>(block + spread::next_offset());
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < spread::kLarge) return ::operator delete(p, std::align_val_t{spread::kLine});
    const auto start = reinterpret_cast<std::uintptr_t>(p) & ~std::uintptr_t{spread::kPage - 1};
    ::operator delete(reinterpret_cast<void*>(start), std::align_val_t{spread::kPage});
  }
  template <class U>
  bool operator==(const SpreadAllocator<U>&) const noexcept { return true; }
};

// A vector in such storage.
template <class T>
using SpreadVector = std::vector<T, SpreadAllocator<T>>;

}  // namespace granwave
