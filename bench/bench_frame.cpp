// What the contact pass's frame costs (issue #41): each crystal row's contact pass against the same law's
// evaluation with no frame at all, timed in turns in one process.
//
// granwave's pass reads its particles through the contact list (the gather into a chunk's columns, or
// for a law without torques the direct loads by index) and sums its forces into per-particle rows (the
// scatter). The frame-free pass is what no layout of a contact list can beat: the crystal's six forward
// neighbour directions as six streams of contacts with j = i + off[q] (a lattice with no seams), so that
// every particle value is a contiguous load and every sum a contiguous stream; the law's own
// evaluate_contact in between (crystal/kernel.hpp), at 256 and at 512 bits. It is a bound, not a
// solver: its pairs at the seams are not the crystal's, and its sums are not added in the list's order
// (other bits). Its overlaps of the pairs it shares with the list (j = i + off[q], no image) are checked
// against the list's, bit for bit.
//
// Usage: bench_frame [CALLS [ROUNDS]]  (each figure the fastest of CALLS single calls, in ROUNDS rounds of
// the three passes in turn; the ratio is the median of the rounds' own; defaults 100 and 15; whole
// numbers >= 1). One thread.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "config/case.hpp"
#include "contact/case_laws.hpp"
#include "crystal/derive.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"
#include "crystal/packing.hpp"

#include "bench_crystal_cases.hpp"

using namespace granwave;
using bench::excited, bench::fastest, bench::seed_case;

namespace {

// The crystal's particles (wrapped past their end so that j = i + off stays in the arrays) and the
// frame-free pass's per-contact columns and per-particle sums.
struct Streams {
  std::int64_t n = 0;
  static constexpr std::int64_t kPad = 32;
  static constexpr std::array<int, 6> off = {1, 4, 16, 17, 20, 21};  // +x, +y and the four above (4 x 4 layers)
  std::vector<double> x, y, z, a, vx, vy, vz, wx, wy, wz;
  std::vector<double> delta, dissipated, history, out, sums;
};

}  // namespace

// The frame-free pass, once for each vector width (the laws' units: law_model_<law>.cpp, _wide.cpp).
namespace width256 {
#pragma GCC push_options
#pragma GCC target("prefer-vector-width=256")
#include "bench_frame_pass.hpp"
#pragma GCC pop_options
}  // namespace width256
namespace width512 {
#pragma GCC push_options
#pragma GCC target("prefer-vector-width=512")
#include "bench_frame_pass.hpp"
#pragma GCC pop_options
}  // namespace width512

namespace {

[[noreturn]] void usage() {
  std::fprintf(stderr, "usage: bench_frame [CALLS [ROUNDS]]  (whole numbers >= 1; defaults 100 and 15)\n");
  std::exit(2);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// f(law) with the law of case c as its type: the registry's dispatch and the description's model(), as
// crystal::case_model takes them.
template <class F>
void with_law_of(const config::Case& c, const F& f) {
  contact::visit_law(c.contact.law(), [&]<class D>(D) {
    D::model(c.contact.get<typename D::Params>(), c.crystal->density, [&](const auto& law) {
      f(law);
      return 0;
    });
  });
}

}  // namespace

int main(int argc, char** argv) {
  auto count = [&](int k, long fallback) { return bench::whole_argument(argc, argv, k, fallback, usage); };
  if (argc > 3) usage();
  const int calls = static_cast<int>(count(1, 100));
  const int rounds = static_cast<int>(count(2, 15));
  struct Row {
    const char* name;
    config::Case c;
  };
  const std::string src = GRANWAVE_SOURCE_DIR;
  const Row rows[] = {{"frictionless", seed_case(200, 0.0)},
                      {"kt = k (friction), radius arm", seed_case(200, 1e5)},
                      {"kt = k, contact-point arm", seed_case(200, 1e5, config::LeverArm::contact_point)},
                      {"Hertz-Mindlin", config::load_case(src + "/data/cases/crystal_hertz.toml")},
                      {"rolling and torsion", config::load_case(src + "/bench/cases/crystal_rolling.toml")}};
  std::printf("the contact pass against the same law with no frame (1 thread; ns a contact, the median of %d "
              "rounds of the fastest of %d calls)\n", rounds, calls);
  std::printf("%-32s %9s %10s %12s %12s %-22s %s\n", "case", "contacts", "granwave", "no frame 256", "no frame 512",
              "ratio (range)", "overlaps checked");
  int failed = 0;
  for (const Row& row : rows) {
    crystal::Dynamics dyn = excited(row.c);
    dyn.parallel_min_particles = dyn.size() + 1;  // one thread
    for (int k = 0; k < 20; ++k) dyn.step();
    // The streams' particles: the crystal's, wrapped.
    Streams s;
    s.n = static_cast<std::int64_t>(dyn.size());
    const std::int64_t np = s.n + Streams::kPad, m = 6 * s.n;
    const SpreadVector<double>* from[] = {&dyn.x, &dyn.y, &dyn.z, &dyn.radius, &dyn.vx, &dyn.vy, &dyn.vz,
                                         &dyn.wx, &dyn.wy, &dyn.wz};
    std::vector<double>* to[] = {&s.x, &s.y, &s.z, &s.a, &s.vx, &s.vy, &s.vz, &s.wx, &s.wy, &s.wz};
    for (int k = 0; k < 10; ++k) {
      to[k]->resize(np);
      for (std::int64_t q = 0; q < np; ++q) (*to[k])[q] = (*from[k])[q % s.n];
    }
    s.delta.assign(m, 0.0);
    s.dissipated.assign(m, 0.0);
    s.out.assign(9 * m, 0.0);    // f, n x f^t, the couple
    s.sums.assign(12 * np, 0.0);  // and delta n x f^t (the contact-point arm)
    const double inc = dyn.dt();
    auto frame_free = [&](const auto& law) {
      using Law = std::decay_t<decltype(law)>;
      s.history.assign(contact::history_columns<typename Law::History> * m + 1, 0.0);
      std::vector<double> t_gw, t_256, t_512;
      for (int r = 0; r < rounds; ++r) {
        t_gw.push_back(fastest(calls, [&] { dyn.model().contact_pass(dyn, {inc, true, true, false}); }));
        t_256.push_back(fastest(calls, [&] { width256::frame_free_pass(law, s, inc); }));
        t_512.push_back(fastest(calls, [&] { width512::frame_free_pass(law, s, inc); }));
      }
      // The overlaps of the pairs both passes evaluate: the same operations on the same values.
      long checked = 0, differ = 0;
      const crystal::ContactList& C = dyn.contacts;
      for (std::size_t c = 0; c < C.size(); ++c)
        for (int q = 0; q < 6; ++q)
          if (C.j[c] - C.i[c] == Streams::off[q] && C.image_x[c] == 0 && C.image_y[c] == 0) {
            ++checked;
            differ += C.delta[c] != s.delta[q * s.n + C.i[c]];
          }
      const double nc = static_cast<double>(C.size());
      // Each round's ratio (its three figures a few milliseconds apart), then their median and range.
      std::vector<double> ratio;
      for (int r = 0; r < rounds; ++r) ratio.push_back((std::min(t_256[r], t_512[r]) / m) / (t_gw[r] / nc));
      const auto [lo, hi] = std::minmax_element(ratio.begin(), ratio.end());
      std::printf("%-32s %9zu %10.2f %12.2f %12.2f %8.3f (%.3f-%.3f) %ld of %zu%s\n", row.name, C.size(),
                  1e9 * median(t_gw) / nc, 1e9 * median(t_256) / m, 1e9 * median(t_512) / m, median(ratio), *lo, *hi,
                  checked, C.size(), differ ? " DIFFER" : "");
      failed += differ != 0 || checked == 0;
    };
    with_law_of(row.c, frame_free);
  }
  std::printf("(ratio: the faster frame-free width over granwave's pass of a run's step, the median of the rounds' ratios)\n");
  return failed ? 1 : 0;
}
