// The processor's ceilings, measured on the machine it runs on (issue #41 item 1): divider and
// square-root throughput and latency (scalar, 256-bit, 512-bit where built for), add and multiply
// for reference, the gather rows' shuffles (in-lane unpacks and lane shuffles, and whether they share a
// port), the gather rate against scalar loads (L1, L2-size and memory-size tables), a
// STREAM-like triad on 1 and 2 threads, the CPU's model, flags and whether logical CPUs share a core.
// Usage: ceilings [--quick] [--json FILE]
// Every figure is the minimum over many short timed blocks (the best block is the one no other
// process interrupted: robust to a second process on the cores). Cycles are core cycles from a
// calibration (a chain of dependent 64-bit integer multiplies, 3 cycles each on Intel and AMD cores),
// not rdtsc ticks: rdtsc counts a constant reference clock (also reported).
// The timed instructions are inline asm (asm volatile), so the compiler can neither fold nor move
// them; checked with objdump -d build/ceilings (GCC 12, -O3 -march=native): each block is the
// named instruction repeated, on xmm, ymm or zmm registers as stated; the gathers compile to
// vgatherdpd (ymm, zmm).
#include <immintrin.h>
#include <x86intrin.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/json.hpp"

using granwave::Json;

#if defined(__AVX2__)  // the 256-bit asm and gathers (a GRANWAVE_NATIVE=OFF build: the stub at the end)
namespace {

double now_ns() {
  return std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Minimum over `reps` calls of block(), in ns (block() does the work once).
template <class F>
double min_ns(int reps, F&& block) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const double t0 = now_ns();
    block();
    best = std::min(best, now_ns() - t0);
  }
  return best;
}

// ---- Clocks ----
// 100 dependent 64-bit `imul`s per iteration: 3 core cycles each (Intel since Nehalem, AMD since Zen;
// both vendors' tables). Not `add $1`: Golden Cove (Sapphire Rapids) folds chains of immediate adds at
// rename and ran 100 of them in ~20 cycles, a "15 GHz" clock.
double ns_per_core_cycle(int reps) {
  constexpr int kIter = 2000;
  std::uint64_t r = 3;
  const double t = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k) {
#define MUL10 "imul %[r], %[r]\n\timul %[r], %[r]\n\timul %[r], %[r]\n\timul %[r], %[r]\n\timul %[r], %[r]\n\t" \
              "imul %[r], %[r]\n\timul %[r], %[r]\n\timul %[r], %[r]\n\timul %[r], %[r]\n\timul %[r], %[r]\n\t"
      asm volatile(MUL10 MUL10 MUL10 MUL10 MUL10 MUL10 MUL10 MUL10 MUL10 MUL10 : [r] "+r"(r));
#undef MUL10
    }
  });
  return t / (3.0 * 100.0 * kIter);
}

// rdtsc ticks per ns over ~50 ms.
double tsc_per_ns() {
  const double t0 = now_ns();
  const std::uint64_t c0 = __rdtsc();
  while (now_ns() - t0 < 5e7) {
  }
  const std::uint64_t c1 = __rdtsc();
  return double(c1 - c0) / (now_ns() - t0);
}

// ---- Arithmetic: throughput (12 independent results per block of 12) and latency (one chain) ----
// V is the register type (__m128d: xmm, __m256d: ymm,
// __m512d: zmm; GCC names the register by the operand's type).
#define T12(INS)                                                                                           \
  INS " %[b], %[a], %[d0]\n\t" INS " %[b], %[a], %[d1]\n\t" INS " %[b], %[a], %[d2]\n\t" INS              \
      " %[b], %[a], %[d3]\n\t" INS " %[b], %[a], %[d4]\n\t" INS " %[b], %[a], %[d5]\n\t" INS " %[b], %[a], " \
      "%[d6]\n\t" INS " %[b], %[a], %[d7]\n\t" INS " %[b], %[a], %[d8]\n\t" INS " %[b], %[a], %[d9]\n\t" INS  \
      " %[b], %[a], %[d10]\n\t" INS " %[b], %[a], %[d11]\n\t"
#define OUT12 \
  [d0] "=&v"(d0), [d1] "=&v"(d1), [d2] "=&v"(d2), [d3] "=&v"(d3), [d4] "=&v"(d4), [d5] "=&v"(d5), \
      [d6] "=&v"(d6), [d7] "=&v"(d7), [d8] "=&v"(d8), [d9] "=&v"(d9), [d10] "=&v"(d10), [d11] "=&v"(d11)
// Unary (sqrt): the scalar form takes the upper half from a second source: `vsqrtsd b, a, d`,
// `vsqrtpd b, d` (the a operand dropped by the packed forms' macro below).
#define U12(INS)                                                                                             \
  INS " %[b], %[d0]\n\t" INS " %[b], %[d1]\n\t" INS " %[b], %[d2]\n\t" INS " %[b], %[d3]\n\t" INS " %[b], " \
      "%[d4]\n\t" INS " %[b], %[d5]\n\t" INS " %[b], %[d6]\n\t" INS " %[b], %[d7]\n\t" INS " %[b], %[d8]\n\t" \
      INS " %[b], %[d9]\n\t" INS " %[b], %[d10]\n\t" INS " %[b], %[d11]\n\t"

// One chain: a = b OP a (div: 1.3 -> 2/1.3 -> 1.3 ..., stays normal), 12 per asm block.
#define C12(INS)                                                                                            \
  INS " %[a], %[b], %[a]\n\t" INS " %[a], %[b], %[a]\n\t" INS " %[a], %[b], %[a]\n\t" INS " %[a], %[b], "  \
      "%[a]\n\t" INS " %[a], %[b], %[a]\n\t" INS " %[a], %[b], %[a]\n\t" INS " %[a], %[b], %[a]\n\t" INS      \
      " %[a], %[b], %[a]\n\t" INS " %[a], %[b], %[a]\n\t" INS " %[a], %[b], %[a]\n\t" INS " %[a], %[b], "   \
      "%[a]\n\t" INS " %[a], %[b], %[a]\n\t"

// Instruction kinds timed (the same for every width).
enum class Op { div, sqrt, mul, add, div_sqrt };

template <class V>
V splat(double x) {
  if constexpr (sizeof(V) == 16) return _mm_set1_pd(x);
  else if constexpr (sizeof(V) == 32) return _mm256_set1_pd(x);
#ifdef __AVX512F__
  else return _mm512_set1_pd(x);
#endif
}

constexpr int kIter = 200;  // asm blocks of 12 instructions per timed block

// Throughput: ns per instruction with 12 independent results (div_sqrt: 6 divisions and 6 roots
// interleaved, per instruction).
template <class V, bool Scalar, Op op>
double throughput(int reps) {
  V a = splat<V>(2.0), b = splat<V>(1.3);
  const double t = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k) {
      // 12 named locals, never stored (an array was stored to the stack every block: 12 stores, which
      // halved the multiply's measured rate)
      V d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10, d11;
      if constexpr (Scalar) {
        switch (op) {  // a constant: one case compiled
          case Op::div: asm volatile(T12("vdivsd") : OUT12 : [a] "v"(a), [b] "v"(b)); break;
          case Op::sqrt: asm volatile(T12("vsqrtsd") : OUT12 : [a] "v"(a), [b] "v"(b)); break;
          case Op::mul: asm volatile(T12("vmulsd") : OUT12 : [a] "v"(a), [b] "v"(b)); break;
          case Op::add: asm volatile(T12("vaddsd") : OUT12 : [a] "v"(a), [b] "v"(b)); break;
          case Op::div_sqrt:
            asm volatile("vdivsd %[b], %[a], %[d0]\n\tvsqrtsd %[b], %[a], %[d1]\n\t"
                         "vdivsd %[b], %[a], %[d2]\n\tvsqrtsd %[b], %[a], %[d3]\n\t"
                         "vdivsd %[b], %[a], %[d4]\n\tvsqrtsd %[b], %[a], %[d5]\n\t"
                         "vdivsd %[b], %[a], %[d6]\n\tvsqrtsd %[b], %[a], %[d7]\n\t"
                         "vdivsd %[b], %[a], %[d8]\n\tvsqrtsd %[b], %[a], %[d9]\n\t"
                         "vdivsd %[b], %[a], %[d10]\n\tvsqrtsd %[b], %[a], %[d11]\n\t"
                         : OUT12 : [a] "v"(a), [b] "v"(b));
            break;
        }
      } else {
        switch (op) {  // a constant: one case compiled
          case Op::div: asm volatile(T12("vdivpd") : OUT12 : [a] "v"(a), [b] "v"(b)); break;
          case Op::sqrt: asm volatile(U12("vsqrtpd") : OUT12 : [b] "v"(b)); break;
          case Op::mul: asm volatile(T12("vmulpd") : OUT12 : [a] "v"(a), [b] "v"(b)); break;
          case Op::add: asm volatile(T12("vaddpd") : OUT12 : [a] "v"(a), [b] "v"(b)); break;
          case Op::div_sqrt:
            asm volatile("vdivpd %[b], %[a], %[d0]\n\tvsqrtpd %[b], %[d1]\n\t"
                         "vdivpd %[b], %[a], %[d2]\n\tvsqrtpd %[b], %[d3]\n\t"
                         "vdivpd %[b], %[a], %[d4]\n\tvsqrtpd %[b], %[d5]\n\t"
                         "vdivpd %[b], %[a], %[d6]\n\tvsqrtpd %[b], %[d7]\n\t"
                         "vdivpd %[b], %[a], %[d8]\n\tvsqrtpd %[b], %[d9]\n\t"
                         "vdivpd %[b], %[a], %[d10]\n\tvsqrtpd %[b], %[d11]\n\t"
                         : OUT12 : [a] "v"(a), [b] "v"(b));
            break;
        }
      }
    }
  });
  return t / (12.0 * kIter);
}

// Latency: ns per instruction of one dependent chain. div: a = 2 / a. mul: a = a * 1. add: a = a + 0.
// sqrt: a = sqrt(a) then a = a * a (sqrt's latency = the pair's minus the multiply's).
template <class V, bool Scalar, Op op>
double latency(int reps) {
  V a = splat<V>(1.3), two = splat<V>(2.0), one = splat<V>(1.0), zero = splat<V>(0.0);
  const double t = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k) {
      if constexpr (Scalar) {
        switch (op) {  // a constant: one case compiled
          case Op::div: asm volatile(C12("vdivsd") : [a] "+v"(a) : [b] "v"(two)); break;
          case Op::mul: asm volatile(C12("vmulsd") : [a] "+v"(a) : [b] "v"(one)); break;
          case Op::add: asm volatile(C12("vaddsd") : [a] "+v"(a) : [b] "v"(zero)); break;
          case Op::sqrt:
            for (int q = 0; q < 6; ++q)
              asm volatile("vsqrtsd %[a], %[a], %[a]\n\tvmulsd %[a], %[a], %[a]\n\t" : [a] "+v"(a));
            break;
          default: break;
        }
      } else {
        switch (op) {  // a constant: one case compiled
          case Op::div: asm volatile(C12("vdivpd") : [a] "+v"(a) : [b] "v"(two)); break;
          case Op::mul: asm volatile(C12("vmulpd") : [a] "+v"(a) : [b] "v"(one)); break;
          case Op::add: asm volatile(C12("vaddpd") : [a] "+v"(a) : [b] "v"(zero)); break;
          case Op::sqrt:
            for (int q = 0; q < 6; ++q)
              asm volatile("vsqrtpd %[a], %[a]\n\tvmulpd %[a], %[a], %[a]\n\t" : [a] "+v"(a));
            break;
          default: break;
        }
      }
    }
  });
  return t / (12.0 * kIter);
}

struct WidthRow {
  const char* name;
  int lanes;
  double tput[5], lat[4];  // Op order: div, sqrt, mul, add (, div_sqrt: throughput only)
};

template <class V, bool Scalar>
WidthRow measure_width(const char* name, int lanes, int reps) {
  WidthRow w{name, lanes, {}, {}};
  // the op a template argument: one tight loop per instruction (a switch inside the timed loop
  // halved the measured multiply rate on ymm)
  w.tput[0] = throughput<V, Scalar, Op::div>(reps);
  w.tput[1] = throughput<V, Scalar, Op::sqrt>(reps);
  w.tput[2] = throughput<V, Scalar, Op::mul>(reps);
  w.tput[3] = throughput<V, Scalar, Op::add>(reps);
  w.tput[4] = throughput<V, Scalar, Op::div_sqrt>(reps);
  w.lat[0] = latency<V, Scalar, Op::div>(reps);
  w.lat[1] = latency<V, Scalar, Op::sqrt>(reps);
  w.lat[2] = latency<V, Scalar, Op::mul>(reps);
  w.lat[3] = latency<V, Scalar, Op::add>(reps);
  w.lat[1] = 2.0 * w.lat[1] - w.lat[2];  // a pair (sqrt, multiply) per two counted instructions
  return w;
}

// ---- L1 load and store throughput: 12 independent 256-bit loads (stores) per block, ns per instruction ----
struct L1Rate {
  double load_ns, store_ns;
};

L1Rate l1_rates(int reps) {
  alignas(64) static double buf[512];  // 4 KiB: L1
  for (double& v : buf) v = 1.0;
  double* p = buf;
  L1Rate r{};
  r.load_ns = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k) {
      __m256d d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10, d11;
      asm volatile(
          "vmovapd 0(%[p]), %[d0]\n\tvmovapd 32(%[p]), %[d1]\n\tvmovapd 64(%[p]), %[d2]\n\tvmovapd 96(%[p]), %[d3]\n\t"
          "vmovapd 128(%[p]), %[d4]\n\tvmovapd 160(%[p]), %[d5]\n\tvmovapd 192(%[p]), %[d6]\n\tvmovapd 224(%[p]), %[d7]\n\t"
          "vmovapd 256(%[p]), %[d8]\n\tvmovapd 288(%[p]), %[d9]\n\tvmovapd 320(%[p]), %[d10]\n\t"
          "vmovapd 352(%[p]), %[d11]\n\t"
          : OUT12 : [p] "r"(p) : "memory");
    }
  }) / (12.0 * kIter);
  const __m256d v = _mm256_set1_pd(1.0);
  r.store_ns = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k)
      asm volatile(
          "vmovapd %[v], 0(%[p])\n\tvmovapd %[v], 32(%[p])\n\tvmovapd %[v], 64(%[p])\n\tvmovapd %[v], 96(%[p])\n\t"
          "vmovapd %[v], 128(%[p])\n\tvmovapd %[v], 160(%[p])\n\tvmovapd %[v], 192(%[p])\n\tvmovapd %[v], 224(%[p])\n\t"
          "vmovapd %[v], 256(%[p])\n\tvmovapd %[v], 288(%[p])\n\tvmovapd %[v], 320(%[p])\n\t"
          "vmovapd %[v], 352(%[p])\n\t"
          :
          : [p] "r"(p), [v] "v"(v)
          : "memory");
  }) / (12.0 * kIter);
  return r;
}

// ---- Shuffles: the gather's row transposes (crystal/kernel_gather.hpp) are in-lane unpacks and 128-bit
// lane shuffles on ymm; 12 independent per block, ns per instruction. The mix (6 unpacks and 6 lane
// shuffles interleaved) tells whether they share one port: it then costs their sum, else about the
// lane shuffles' alone. ----
struct ShuffleRate {
  double unpack_ns, lanes_ns, mix_ns;  // vunpcklpd ymm; vshuff64x2 ymm (AVX-512VL) or vperm2f128; the mix
  const char* lanes_name;
};

ShuffleRate shuffle_rates(int reps) {
  __m256d a = _mm256_set1_pd(1.0), b = _mm256_set1_pd(2.0);
  ShuffleRate r{};
  r.unpack_ns = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k) {
      __m256d d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10, d11;
      asm volatile(T12("vunpcklpd") : OUT12 : [a] "v"(a), [b] "v"(b));
    }
  }) / (12.0 * kIter);
#ifdef __AVX512VL__
#define LANES(D) "vshuff64x2 $1, %[b], %[a], %[" D "]\n\t"
  r.lanes_name = "vshuff64x2";
#else
#define LANES(D) "vperm2f128 $0x21, %[b], %[a], %[" D "]\n\t"
  r.lanes_name = "vperm2f128";
#endif
  r.lanes_ns = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k) {
      __m256d d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10, d11;
      asm volatile(LANES("d0") LANES("d1") LANES("d2") LANES("d3") LANES("d4") LANES("d5") LANES("d6")
                       LANES("d7") LANES("d8") LANES("d9") LANES("d10") LANES("d11")
                   : OUT12 : [a] "v"(a), [b] "v"(b));
    }
  }) / (12.0 * kIter);
  r.mix_ns = min_ns(reps, [&] {
    for (int k = 0; k < kIter; ++k) {
      __m256d d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10, d11;
      asm volatile("vunpcklpd %[b], %[a], %[d0]\n\t" LANES("d1") "vunpcklpd %[b], %[a], %[d2]\n\t" LANES("d3")
                   "vunpcklpd %[b], %[a], %[d4]\n\t" LANES("d5") "vunpcklpd %[b], %[a], %[d6]\n\t" LANES("d7")
                   "vunpcklpd %[b], %[a], %[d8]\n\t" LANES("d9") "vunpcklpd %[b], %[a], %[d10]\n\t" LANES("d11")
                   : OUT12 : [a] "v"(a), [b] "v"(b));
    }
  }) / (12.0 * kIter);
#undef LANES
  return r;
}

// ---- Gathers against scalar loads: ns per double loaded from `table` at random indices ----
struct GatherRow {
  std::string where;
  std::size_t bytes;
  double scalar_ns, g256_ns, g512_ns;  // per element
};

GatherRow gather_rates(const std::string& where, std::size_t bytes, int reps) {
  const std::size_t n = bytes / sizeof(double);
  std::vector<double> table(n);
  for (std::size_t k = 0; k < n; ++k) table[k] = 1.0 + 1e-9 * double(k % 1000);
  constexpr std::size_t kIdx = 4096;  // indices per timed block (16 KiB: stays in L1 beside the table)
  std::vector<std::int32_t> idx(kIdx);
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<std::int32_t> pick(0, static_cast<std::int32_t>(n - 1));
  for (auto& v : idx) v = pick(rng);
  volatile double sink = 0.0;
  GatherRow row{where, bytes, 0, 0, 0};
  row.scalar_ns = min_ns(reps, [&] {  // 8 sums: their add chains (3 cycles) stay below the loads' rate
    double s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < kIdx; k += 8)
      for (int q = 0; q < 8; ++q) s[q] += table[idx[k + q]];
    sink = s[0] + s[1] + s[2] + s[3] + s[4] + s[5] + s[6] + s[7];
  }) / kIdx;
  row.g256_ns = min_ns(reps, [&] {
    __m256d s0 = _mm256_setzero_pd(), s1 = s0;
    for (std::size_t k = 0; k < kIdx; k += 8) {
      s0 = _mm256_add_pd(s0, _mm256_i32gather_pd(table.data(), _mm_loadu_si128((const __m128i*)&idx[k]), 8));
      s1 = _mm256_add_pd(s1, _mm256_i32gather_pd(table.data(), _mm_loadu_si128((const __m128i*)&idx[k + 4]), 8));
    }
    double o[4];
    _mm256_storeu_pd(o, _mm256_add_pd(s0, s1));
    sink = o[0] + o[3];
  }) / kIdx;
#ifdef __AVX512F__
  row.g512_ns = min_ns(reps, [&] {
    __m512d s0 = _mm512_setzero_pd(), s1 = s0;
    for (std::size_t k = 0; k < kIdx; k += 16) {
      s0 = _mm512_add_pd(s0, _mm512_i32gather_pd(_mm256_loadu_si256((const __m256i*)&idx[k]), table.data(), 8));
      s1 = _mm512_add_pd(s1, _mm512_i32gather_pd(_mm256_loadu_si256((const __m256i*)&idx[k + 8]), table.data(), 8));
    }
    sink = _mm512_reduce_add_pd(_mm512_add_pd(s0, s1));
  }) / kIdx;
#endif
  return row;
}

// ---- STREAM-like triad a = b + s c (no FMA: -ffp-contract=off), 24 bytes per element counted ----
double triad_gbs(std::size_t n, int threads, int reps) {
  std::vector<double> a(n), b(n), c(n);
  const double s = 3.0;
  auto triad = [&] {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    const std::int64_t m = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t k = 0; k < m; ++k) pa[k] = pb[k] + s * pc[k];
  };
  // first touch by the threads that use the pages
  {
    double* pa = a.data();
    double* pb = b.data();
    double* pc = c.data();
    const std::int64_t m = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t k = 0; k < m; ++k) pa[k] = 0.0, pb[k] = 1.0, pc[k] = 2.0;
  }
  const double t = min_ns(reps, triad);
  return 24.0 * double(n) / t;  // bytes per ns = GB/s
}

// ---- The CPU ----
std::string read_first(const std::string& path) {
  std::ifstream f(path);
  std::string s;
  std::getline(f, s);
  return s;
}

struct CpuInfo {
  std::string model;
  std::string vendor;              // GenuineIntel, AuthenticAMD
  int family = -1, model_number = -1;  // /proc/cpuinfo's "cpu family" and "model" (Zen 5: 26)
  std::vector<std::string> flags;  // of those that matter here
  int logical = 0;
  bool smt = false;                // two logical CPUs share a core
  std::vector<std::string> siblings;
};

CpuInfo cpu_info() {
  CpuInfo info;
  std::ifstream f("/proc/cpuinfo");
  std::string line, flags;
  while (std::getline(f, line)) {
    auto value = [&] { return line.substr(line.find(':') + 2); };
    if (info.model.empty() && line.rfind("model name", 0) == 0) info.model = value();
    if (info.vendor.empty() && line.rfind("vendor_id", 0) == 0) info.vendor = value();
    if (info.family < 0 && line.rfind("cpu family", 0) == 0) info.family = std::atoi(value().c_str());
    if (info.model_number < 0 && line.rfind("model\t", 0) == 0) info.model_number = std::atoi(value().c_str());
    if (flags.empty() && line.rfind("flags", 0) == 0) flags = value();
    if (line.rfind("processor", 0) == 0) ++info.logical;
  }
  std::set<std::string> have;
  std::istringstream in(flags);
  for (std::string w; in >> w;) have.insert(w);
  for (const char* w : {"sse2", "avx", "avx2", "fma", "avx512f", "avx512vl", "avx512dq", "avx512bw", "avx512ifma",
                        "avx512vbmi", "avx512_vnni", "avx512_bf16", "hypervisor"})
    if (have.count(w)) info.flags.push_back(w);
  std::set<std::string> lists;
  for (int c = 0; c < info.logical; ++c) {
    const std::string s = read_first("/sys/devices/system/cpu/cpu" + std::to_string(c) + "/topology/thread_siblings_list");
    if (s.empty()) continue;
    lists.insert(s);
    if (s.find_first_of(",-") != std::string::npos) info.smt = true;
  }
  info.siblings.assign(lists.begin(), lists.end());
  return info;
}

const char* build_target() {
#if defined(__AVX512F__)
  return "AVX-512F (-march=native)";
#elif defined(__AVX2__)
  return "AVX2 (-march=native, no AVX-512)";
#else
  return "SSE2/AVX";
#endif
}

[[noreturn]] void usage(const char* why) {
  std::fprintf(stderr, "ceilings: %s\nusage: ceilings [--quick] [--json FILE]  (--quick: small sizes and few "
                       "repetitions, a smoke test; FILE: where the JSON goes)\n", why);
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string json_path;
  for (int k = 1; k < argc; ++k) {
    if (std::strcmp(argv[k], "--quick") == 0) quick = true;
    else if (std::strcmp(argv[k], "--json") == 0) {
      if (k + 1 >= argc) usage("--json needs a file name");
      json_path = argv[++k];
    } else usage((std::string("unknown argument '") + argv[k] + "'").c_str());
  }
  const int reps = quick ? 20 : 2000;
  const CpuInfo cpu = cpu_info();
  std::printf("ceilings: %s (%s family %d model %d), %d logical CPUs; built for %s\n", cpu.model.c_str(),
              cpu.vendor.c_str(), cpu.family, cpu.model_number, cpu.logical, build_target());
  std::string fl;
  for (const auto& w : cpu.flags) fl += w + " ";
  std::printf("flags: %s\nSMT: %s (thread_siblings_list: ", fl.c_str(), cpu.smt ? "yes, logical CPUs share a core" : "no, one logical CPU per core");
  for (const auto& s : cpu.siblings) std::printf("[%s]", s.c_str());
  std::printf(")\nevery time is the minimum over %d short timed blocks (robust to another process on the cores)\n",
              reps);
  const double cyc_ns = ns_per_core_cycle(reps);
  const double tsc = tsc_per_ns();
  std::printf("core clock %.3f GHz (dependent integer multiplies, 3 cycles each); rdtsc %.3f GHz (a reference clock)\n\n",
              1.0 / cyc_ns, tsc);

  std::vector<WidthRow> rows;
  rows.push_back(measure_width<__m128d, true>("scalar (sd)", 1, reps));
  rows.push_back(measure_width<__m256d, false>("256-bit (ymm)", 4, reps));
#ifdef __AVX512F__
  rows.push_back(measure_width<__m512d, false>("512-bit (zmm)", 8, reps));
#endif
  const char* names[] = {"div", "sqrt", "mul", "add"};
  std::printf("arithmetic, per instruction: throughput (12 independent) and latency (one chain), cycles [ns]\n");
  std::printf("%-14s %-5s %22s %22s %16s\n", "width", "op", "throughput", "latency", "ns per double");
  for (const WidthRow& w : rows) {
    for (int o = 0; o < 4; ++o)
      std::printf("%-14s %-5s %10.2f [%7.3f ns] %10.2f [%7.3f ns] %12.3f\n", w.name, names[o], w.tput[o] / cyc_ns,
                  w.tput[o], w.lat[o] / cyc_ns, w.lat[o], w.tput[o] / w.lanes);
    // div and sqrt interleaved: shared unit if the mix costs their sum, separate if their max
    const double sum = 0.5 * (w.tput[0] + w.tput[1]), mx = 0.5 * std::max(w.tput[0], w.tput[1]);
    std::printf("%-14s %-5s %10.2f [%7.3f ns]  per instruction, 6 div + 6 sqrt interleaved (shared unit: %.2f, "
                "separate: %.2f)\n", w.name, "mix", w.tput[4] / cyc_ns, w.tput[4], sum / cyc_ns, mx / cyc_ns);
  }

  const L1Rate l1 = l1_rates(reps);
  std::printf("\nL1, 256-bit: a load %.2f cycles [%.3f ns], a store %.2f cycles [%.3f ns] (12 independent per block)\n",
              l1.load_ns / cyc_ns, l1.load_ns, l1.store_ns / cyc_ns, l1.store_ns);
  const ShuffleRate sh = shuffle_rates(reps);
  std::printf("shuffles, 256-bit: vunpcklpd %.2f cycles [%.3f ns], %s %.2f [%.3f ns]; 6 + 6 interleaved %.2f a "
              "shuffle (one port for both: %.2f, apart: %.2f)\n",
              sh.unpack_ns / cyc_ns, sh.unpack_ns, sh.lanes_name, sh.lanes_ns / cyc_ns, sh.lanes_ns, sh.mix_ns / cyc_ns,
              0.5 * (sh.unpack_ns + sh.lanes_ns) / cyc_ns, 0.5 * std::max(sh.unpack_ns, sh.lanes_ns) / cyc_ns);
  struct Level {
    const char* name;
    std::size_t bytes;
  };
  const Level levels[] = {{"L1 (16 KiB)", 16u << 10}, {"L2 (512 KiB)", 512u << 10},
                          {"memory (256 MiB)", quick ? (4u << 20) : (256u << 20)}};
  std::vector<GatherRow> gathers;
  std::printf("\nrandom loads from a table, ns per double (cycles): scalar loads, vgatherdpd ymm (4), zmm (8)\n");
  for (const Level& l : levels) {
    gathers.push_back(gather_rates(l.name, l.bytes, quick ? 10 : 200));
    const GatherRow& g = gathers.back();
    std::printf("%-18s %8.3f (%5.2f) %8.3f (%5.2f) %8.3f (%5.2f)\n", g.where.c_str(), g.scalar_ns,
                g.scalar_ns / cyc_ns, g.g256_ns, g.g256_ns / cyc_ns, g.g512_ns, g.g512_ns / cyc_ns);
  }

  // 3 arrays of 128 KiB (L2: 384 KiB of 1 MiB), of 2 MiB (L3: 6 MiB of the 32 MiB L3) and of 128 MiB
  // (memory: 12 times the L3)
  const std::size_t sizes[3] = {1u << 14, quick ? (1u << 16) : (1u << 18), quick ? (1u << 18) : (1u << 24)};
  auto where = [&](std::size_t n) { return n == sizes[0] ? "L2" : n == sizes[1] ? "L3" : "memory"; };
  int max_threads = 1;
#ifdef _OPENMP
  max_threads = omp_get_max_threads();
#endif
  std::printf("\ntriad a = b + s c, 24 bytes per element counted (STREAM's convention; the write-allocate read of a "
              "is not counted), best of %d%s\n", quick ? 3 : 20, quick ? " (--quick: the arrays are smaller than the levels "
              "named)" : "");
  struct Triad {
    std::size_t n;
    int threads;
    double gbs;
  };
  std::vector<Triad> triads;
  for (std::size_t tn : sizes)
    for (int th : {1, 2}) {
      if (th > max_threads && th > 1) break;
      triads.push_back({tn, th, triad_gbs(tn, th, tn < (1u << 20) ? (quick ? 3 : 500) : (quick ? 3 : 20))});
      std::printf("%-6s %8.3f MiB per array, %d thread%s %8.2f GB/s\n", where(tn), 8.0 * double(tn) / (1 << 20), th,
                  th > 1 ? "s" : " ", triads.back().gbs);
    }

  if (!json_path.empty()) {
    Json j;
    j["format"] = "granwave-ceilings/1";
    j["cpu"] = {{"model", cpu.model},          {"vendor", cpu.vendor},
                {"family", cpu.family},        {"model_number", cpu.model_number},
                {"logical_cpus", cpu.logical}, {"flags", cpu.flags},
                {"smt", cpu.smt},              {"thread_siblings", cpu.siblings}};
    j["build"] = build_target();
    j["method"] = "minimum over short timed blocks; cycles from a chain of dependent integer multiplies";
    j["repetitions"] = reps;
    j["core_ghz"] = 1.0 / cyc_ns;
    j["tsc_ghz"] = tsc;
    Json arith = Json::array();
    for (const WidthRow& w : rows) {
      Json r{{"width", w.name}, {"lanes", w.lanes}};
      for (int o = 0; o < 4; ++o)
        r[names[o]] = {{"throughput_ns", w.tput[o]}, {"throughput_cycles", w.tput[o] / cyc_ns},
                       {"latency_ns", w.lat[o]}, {"latency_cycles", w.lat[o] / cyc_ns}};
      r["div_sqrt_mix_ns"] = w.tput[4];
      arith.push_back(r);
    }
    j["arithmetic"] = arith;
    j["l1_ymm"] = {{"load_ns", l1.load_ns}, {"load_cycles", l1.load_ns / cyc_ns}, {"store_ns", l1.store_ns},
                   {"store_cycles", l1.store_ns / cyc_ns}};
    j["shuffles_ymm"] = {{"unpack_ns", sh.unpack_ns}, {"unpack_cycles", sh.unpack_ns / cyc_ns},
                         {"lanes_instruction", sh.lanes_name}, {"lanes_ns", sh.lanes_ns},
                         {"lanes_cycles", sh.lanes_ns / cyc_ns}, {"mix_ns", sh.mix_ns}, {"mix_cycles", sh.mix_ns / cyc_ns}};
    Json g = Json::array();
    for (const GatherRow& r : gathers)
      g.push_back({{"table", r.where}, {"bytes", r.bytes}, {"scalar_ns_per_double", r.scalar_ns},
                   {"gather256_ns_per_double", r.g256_ns}, {"gather512_ns_per_double", r.g512_ns}});
    j["gathers"] = g;
    Json t = Json::array();
    for (const Triad& r : triads)
      t.push_back({{"threads", r.threads}, {"gb_per_s", r.gbs}, {"doubles_per_array", r.n},
                   {"where", where(r.n)}});
    j["triad"] = t;
    std::ofstream out(json_path);
    if (!out) usage(("cannot write the JSON file '" + json_path + "'").c_str());
    out << granwave::json_text(j);
  }
  return 0;
}
#else
int main() {
  std::fprintf(stderr, "ceilings: built without AVX2 (GRANWAVE_NATIVE=OFF?): nothing measured\n");
  return 77;  // the smoke test's SKIP
}
#endif
