// Throughput of the crystal time step (issue 4, "Speed"): particle-steps per second for the
// 3200-particle crystal of seed 002 with and without friction (and with Hertz-Mindlin contacts,
// issue #14: data/cases/crystal_hertz.toml), on one and two threads; the
// cost per step as the number of layers grows; memory per particle. Beside the two-thread speed-up, its
// ceiling here: two copies of the crystal stepped at once, one a thread.
// Usage: bench_crystal [--passes | --routes] [steps=2000] [repeats=3]  (--passes: the passes alone and a run by
// phase, bench/ceilings_figure.py's achieved times, issue #41; --routes: a frictionless crystal's run steps by the
// lattice rows' pass, crystal/lattice.hpp, against the list's, paired runs in turn)
// Each figure is the best of `repeats` measurements, by wall clock and by CPU time (on a loaded
// machine the wall clock also counts other processes' turns; CPU time does not). The passes of
// one step are timed alone as well, each the fastest of many single calls (robust under load).
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "config/case.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/kernel.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"

#include "bench_crystal_cases.hpp"

using namespace granwave;
using bench::excited, bench::fastest, bench::seed_case;

namespace {

template <class T, class A>
std::size_t bytes(const std::vector<T, A>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t state_bytes(const crystal::Dynamics& d) {
  std::size_t b = 0;
  for (const auto* v : {&d.x, &d.y, &d.z, &d.vx, &d.vy, &d.vz, &d.wx, &d.wy, &d.wz, &d.fx, &d.fy, &d.fz, &d.tx,
                        &d.ty, &d.tz, &d.x0, &d.y0, &d.z0, &d.radius, &d.mass, &d.inv_mass, &d.inv_inertia,
                        &d.inertia})
    b += bytes(*v);
  b += bytes(d.mobile) + bytes(d.gather_rows) + bytes(d.contact_sums);
  const auto& C = d.contacts;
  b += bytes(C.i) + bytes(C.j) + bytes(C.image_x) + bytes(C.image_y) + bytes(C.j_first) + bytes(C.j_contacts) + bytes(C.i_first);
  for (const auto* v : {&C.history, &C.delta, &C.f_x, &C.f_y, &C.f_z, &C.nf_x, &C.nf_y,
                        &C.nf_z, &C.dissipated})
    b += bytes(*v);
  // The observers' per-layer lists (built at the first sample after a list build) and their
  // scratch: the layer stress's lever arms (16 bytes per contact: Dynamics::end_arms, made by a
  // one-thread contact pass, or simulation.cpp's scratch) and the particle energy terms (16 bytes
  // per particle, dynamics.cpp).
  const crystal::Dynamics::LayerOrder& o = d.layer_order();
  for (const auto* l : {&o.particles, &o.contacts, &o.ends}) b += bytes(l->first) + bytes(l->entries);
  b += bytes(o.counted_ends) + (d.end_arms.empty() ? 16 * C.size() : bytes(d.end_arms)) + 16 * d.size();
  return b + 3 * d.size() * sizeof(float);  // displacements at the last list build
}

double cpu_seconds() {  // all threads of the process
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct StepCost {
  double wall = 1e300, cpu = 1e300;  // seconds per step; cpu = summed over threads / threads
};

// `steps` steps (a multiple of kSampleEvery) as a run takes them (crystal/simulation.cpp): advances
// of kSampleEvery steps, each step's finish joined to the next drift, the forces kept at the last
// step of each for its sample (the samples' observers not timed). dyn.step() would keep them at
// every step and finish each step apart: on two threads that step scaled 1.46x where a run's
// scaled 1.86x (frictionless, 32 000 particles; docs/benchmarks.md session 34).
constexpr long kSampleEvery = 5;  // bench/side_by_side.py's cases: a sample every 5 steps
void advance_as_run(crystal::Dynamics& dyn, long steps) {
  for (long k = 0; k < steps; k += kSampleEvery) dyn.advance(kSampleEvery, true);
}
long as_run_steps(long steps) { return std::max(kSampleEvery, steps / kSampleEvery * kSampleEvery); }

// Seconds per step after a short warm-up, best of `repeats`; the crystal is excited so the
// forces are not trivial.
StepCost seconds_per_step(crystal::Dynamics& dyn, long steps, int repeats, int threads) {
  steps = as_run_steps(steps);
  for (int k = 0; k < 20; ++k) dyn.step();
  StepCost best;
  for (int r = 0; r < repeats; ++r) {
    const double c0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    advance_as_run(dyn, steps);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = (cpu_seconds() - c0) / threads;
    best.wall = std::min(best.wall, wall / steps);
    best.cpu = std::min(best.cpu, cpu / steps);
  }
  return best;
}

// The phases of `steps` more steps taken as a run takes them (Dynamics::advance's clock), us a step:
// the one that does not halve on two threads is the one that caps their speed-up.
void print_phases(crystal::Dynamics& dyn, long steps) {
  steps = as_run_steps(steps);
  crystal::PhaseTimes times;
  crystal::PhaseClock clock(times, crystal::PhaseClock::Clock::now());
  for (long k = 0; k < steps; k += kSampleEvery) dyn.advance(kSampleEvery, true, &clock);
  std::printf("%-34s %8s ", "", "");
  for (int q = 0; q < crystal::PhaseTimes::kPhases; ++q)
    if (times.seconds[q] > 0.0) std::printf(" %s %.1f", crystal::PhaseTimes::names[q], 1e6 * times.seconds[q] / steps);
  std::printf("  (us/step)\n");
}

// Issue #14: the same crystal of glass beads with Hertz normal and Mindlin tangential forces.
config::Case hertz_case() {
  return config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_hertz.toml");
}

#ifdef _OPENMP
// Two crystals of case c stepped at once, one a thread, each on one thread (no shared data, no
// barrier within a step): seconds per step of the slower and the faster, best of `repeats`. What two
// of this machine's cores give a step is the ceiling of the two-thread speed-up of one crystal.
struct TwoCopies {
  double slower = 1e300, faster = 1e300;
  std::size_t particles = 0;  // of one copy
};
TwoCopies two_copies(const config::Case& c, long steps, int repeats) {
  steps = as_run_steps(steps);
  TwoCopies best;
  if (omp_get_num_procs() < 2) return best;  // no second CPU: nothing to measure
  crystal::Dynamics d0 = excited(c), d1 = excited(c);
  crystal::Dynamics* copy[2] = {&d0, &d1};
  best.particles = d0.size();
  double took[2] = {0.0, 0.0};
  omp_set_num_threads(2);
  for (int r = 0; r < repeats; ++r) {
#pragma omp parallel num_threads(2)
    {
      crystal::Dynamics& d = *copy[omp_get_thread_num()];
      d.parallel_min_particles = d.size() + 1;
      if (r == 0)
        for (int k = 0; k < 20; ++k) d.step();
#pragma omp barrier
      const auto t0 = std::chrono::steady_clock::now();
      advance_as_run(d, steps);
      took[omp_get_thread_num()] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    best.slower = std::min(best.slower, std::max(took[0], took[1]) / steps);
    best.faster = std::min(best.faster, std::min(took[0], took[1]) / steps);
  }
  return best;
}
#endif

// The vector extensions this binary was compiled for (the loops use what the compiler may).
const char* build_flags() {
#if defined(__AVX512F__)
  return "AVX-512F (AVX-512VL, 256-bit vectors in the crystal's loops)";
#elif defined(__AVX2__)
  return "AVX2 (256-bit vectors, no AVX-512)";
#elif defined(__AVX__)
  return "AVX";
#else
  return "SSE2 only";
#endif
}

// A run's steps (`per_call` in one advance: the finish joined to the next drift), phase by phase, each
// the fastest of `calls` advances: the contact pass per contact, the particle pass per particle.
void run_phases(crystal::Dynamics& d, int calls, long per_call) {
  crystal::PhaseTimes best;
  best.seconds.fill(1e300);
  double run_step = 1e300;
  for (int k = 0; k < calls; ++k) {
    crystal::PhaseTimes t;
    crystal::PhaseClock clock(t, std::chrono::steady_clock::now());
    d.advance(per_call, false, &clock);
    for (std::size_t q = 0; q < t.seconds.size(); ++q) best.seconds[q] = std::min(best.seconds[q], t.seconds[q] / per_call);
    run_step = std::min(run_step, t.total() / per_call);
  }
  using P = crystal::PhaseTimes;
  std::printf("%-34s run step %.2f ns/particle: contact pass %.2f ns/contact, particle pass (kick, drift, "
              "finish) %.2f ns/particle, list upkeep %.2f ns/particle\n", "", 1e9 * run_step / d.size(),
              1e9 * best.seconds[P::contact_pass] / d.contacts.size(),
              1e9 * (best.seconds[P::kick_drift] + best.seconds[P::finish]) / d.size(),
              1e9 * best.seconds[P::list_upkeep] / d.size());
}

// --routes: the frictionless crystal's run steps by the lattice rows' pass (crystal/lattice.hpp) and by the list's,
// `pairs` paired measurements taken in turn (a slow spell of the machine hits both), the median of the ratios.
void compare_routes(long steps, int pairs) {
  std::printf("lattice pass against the list's pass, frictionless, %d paired runs in turn (median; min-max)\n"
              "%-24s %8s %10s %14s %14s %22s\n", pairs, "case", "threads", "particles", "lattice us", "list us",
              "lattice / list");
  struct Size {
    int layers, threads;
  };
  for (const Size z : {Size{200, 1}, Size{2000, 1}, Size{2000, 2}, Size{20000, 1}}) {
#ifdef _OPENMP
    omp_set_num_threads(z.threads);
#else
    if (z.threads > 1) continue;
#endif
    const config::Case c = seed_case(z.layers, 0.0);
    crystal::Dynamics lattice = excited(c), list = excited(c);
    list.lattice_pass = false;
    for (crystal::Dynamics* d : {&lattice, &list}) d->parallel_min_particles = z.threads > 1 ? 0 : d->size() + 1;
    const long n = as_run_steps(std::max<long>(20, steps * 200 / z.layers));
    std::vector<double> ratio, t_lattice, t_list;
    for (int k = 0; k < pairs; ++k) {
      const StepCost a = seconds_per_step(lattice, n, 1, z.threads), b = seconds_per_step(list, n, 1, z.threads);
      t_lattice.push_back(a.wall), t_list.push_back(b.wall), ratio.push_back(a.wall / b.wall);
    }
    if (lattice.lattice_rows() == nullptr) std::printf("(the lattice pass did not apply)\n");
    if (z.threads == 1 && z.layers == 2000) {
      std::printf("phases, lattice:"), print_phases(lattice, n);
      std::printf("phases, list:   "), print_phases(list, n);
    }
    auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    std::printf("%-24s %8d %10zu %14.2f %14.2f %10.3f (%.3f-%.3f)\n", ("4x4x" + std::to_string(z.layers)).c_str(),
                z.threads, lattice.size(), 1e6 * median(t_lattice), 1e6 * median(t_list), median(ratio),
                *std::min_element(ratio.begin(), ratio.end()), *std::max_element(ratio.begin(), ratio.end()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  // bench_crystal [--passes] [STEPS [REPEATS]]: whole numbers >= 1 (anything else, --help included: usage,
  // exit 2); --passes: the passes alone only
  auto usage = [] {
    std::fprintf(stderr, "usage: bench_crystal [--passes | --routes] [STEPS [REPEATS]]  (steps per measurement, "
                         "default 2000; best of REPEATS, default 3 (--routes: paired runs, at least 7); whole numbers "
                         ">= 1; --passes: the passes alone only; --routes: the lattice pass against the list's)\n");
    std::exit(2);
  };
  const bool passes_only = argc > 1 && std::string(argv[1]) == "--passes";
  const bool routes = argc > 1 && std::string(argv[1]) == "--routes";
  if (passes_only || routes) --argc, ++argv;
  auto count = [&](int k, long fallback) { return bench::whole_argument(argc, argv, k, fallback, usage); };
  if (argc > 3) usage();
  const long steps = count(1, 2000);
  const int repeats = static_cast<int>(count(2, 3));
  int max_threads = 1;
#ifdef _OPENMP
  max_threads = omp_get_max_threads();
#endif
  std::printf("crystal time step, %ld steps per measurement, best of %d (OpenMP max threads %d); built for %s\n",
              steps, repeats, max_threads, build_flags());
  if (routes) {
    compare_routes(steps, std::max(7, repeats));
    return 0;
  }
  std::printf("%-34s %8s %12s %18s %18s\n", "case", "threads", "us/step", "particle-steps/s", "(by CPU time)");
  // The contact-point lever arm (YADE's and LIGGGHTS' convention) costs one more sum per contact.
  struct Row {
    double kt;
    config::LeverArm arm;
    const char* name;
    bool hertz = false;
    bool rolling = false;  // bench/cases/crystal_rolling.toml (passes alone only)
    config::Case make() const {
      if (rolling) return config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/bench/cases/crystal_rolling.toml");
      return hertz ? hertz_case() : seed_case(200, kt, arm);
    }
  };
  const Row rows[] = {Row{0.0, config::LeverArm::radius, "4x4x200, frictionless"},
                      Row{1e5, config::LeverArm::radius, "4x4x200, kt = k (friction)"},
                      Row{1e5, config::LeverArm::contact_point, "4x4x200, kt = k, contact-point arm"},
                      Row{0.0, config::LeverArm::radius, "4x4x200, Hertz-Mindlin", true}};
  for (const Row& row : rows) {
    if (passes_only) break;
    const config::Case c = row.make();
    for (int threads : {1, 2}) {
#ifdef _OPENMP
      omp_set_num_threads(threads);
#else
      if (threads > 1) continue;
#endif
      crystal::Dynamics dyn = excited(c);
      // One thread: the serial code path (no OpenMP region); two: force OpenMP on for this small crystal.
      dyn.parallel_min_particles = threads > 1 ? 0 : dyn.size() + 1;
      const StepCost s = seconds_per_step(dyn, steps, repeats, threads);
      std::printf("%-34s %8d %12.2f %18.3g %18.3g\n", row.name, threads, 1e6 * s.wall, dyn.size() / s.wall,
                  dyn.size() / s.cpu);
    }
  }
#ifdef _OPENMP
  omp_set_num_threads(1);
#endif
  // The passes alone, 1 thread: ns per contact for the contact pass, per particle for a step.
  // ns/contact: the pass of a sampled step (the gather rows refilled, the forces kept); "in a step":
  // the pass of the other steps (rows fresh from the drift, no forces kept: bench/ceilings.cpp's
  // comparison, docs/benchmarks.md issue #41).
  std::printf("\npasses alone (1 thread, fastest of %d calls)\n%-34s %9s %14s %16s %16s %16s\n", 50 * repeats,
              "case", "contacts", "ns/contact", "step ns/particle", "step-contact ns", "in a step ns/c");
  std::vector<Row> pass_rows(std::begin(rows), std::end(rows));
  pass_rows.push_back(Row{1e5, config::LeverArm::radius, "4x4x200, rolling and torsion", false, true});
  for (const Row& row : pass_rows) {
    crystal::Dynamics dyn = excited(row.make());
    dyn.parallel_min_particles = dyn.size() + 1;
    for (int k = 0; k < 20; ++k) dyn.step();
    const int calls = 50 * repeats;
    const double pass = fastest(calls, [&] { dyn.model().contact_pass(dyn, {dyn.dt(), true, false, true}); });
    const double step = fastest(calls, [&] { dyn.step(); });
    // The state each measurement starts from: 20 steps after the excitation (the calls above moved
    // the springs without moving the particles; a Hertz-Mindlin pass then took the exact sweep)
    auto fresh = [&] {
      crystal::Dynamics f = excited(row.make());
      f.parallel_min_particles = f.size() + 1;
      for (int k = 0; k < 20; ++k) f.step();
      return f;
    };
    crystal::Dynamics d2 = fresh();
    const double in_step = fastest(calls, [&] { d2.model().contact_pass(d2, {d2.dt(), true, true, false}); });
    std::printf("%-34s %9zu %14.2f %16.2f %16.2f %16.2f\n", row.name, dyn.contacts.size(),
                1e9 * pass / dyn.contacts.size(), 1e9 * step / dyn.size(), 1e9 * (step - pass) / dyn.size(),
                1e9 * in_step / dyn.contacts.size());
    if (passes_only) {  // a run's steps, by phase
      crystal::Dynamics d3 = fresh();
      run_phases(d3, calls, 20);
      continue;
    }
    // The observers of one sample (crystal/simulation.cpp), us per call.
    std::vector<double> zz, zx;
    double sink = 0.0;
    const double t_stress = fastest(calls, [&] { crystal::layer_stress(dyn, zz, zx); });
    const double t_coord = fastest(calls, [&] { sink += crystal::coordination(dyn); });
    const double t_pot = fastest(calls, [&] { sink += dyn.potential_energy(); });
    const double t_diss = fastest(calls, [&] { sink += dyn.dissipated_energy(); });
    const double t_kin = fastest(calls, [&] { sink += dyn.kinetic_energy() + dyn.verlet_correction(); });
    std::printf("%-34s sample: layer_stress %.1f us, coordination %.1f us, potential %.1f us, dissipated %.1f us, "
                "kinetic + Verlet %.1f us%s\n",
                "", 1e6 * t_stress, 1e6 * t_coord, 1e6 * t_pot, 1e6 * t_diss, 1e6 * t_kin, sink == 0.123 ? " " : "");
  }
  if (passes_only) {  // and a crystal beyond the L3 (320000 particles, ~1.9 million contacts): memory's share
    std::printf("\na crystal beyond the L3 (1 thread, fastest of %d advances of 5 steps)\n", 2 * repeats);
    for (double kt : {0.0, 1e5}) {
      crystal::Dynamics big = excited(seed_case(20000, kt));
      big.parallel_min_particles = big.size() + 1;
      for (int k = 0; k < 5; ++k) big.step();
      std::printf("%-34s %9zu contacts\n", kt > 0 ? "4x4x20000, kt = k (friction)" : "4x4x20000, frictionless",
                  big.contacts.size());
      run_phases(big, 2 * repeats, 5);
    }
    return 0;
  }
  // Thread scaling where threads pay (OpenMP from 20000 particles on): 4x4x2000, 32000 particles.
#ifdef _OPENMP
  std::printf("\nthread scaling, 4x4x2000 (32000 particles)\n%-34s %8s %12s %18s %18s %9s\n", "case", "threads",
              "us/step", "particle-steps/s", "(by CPU time)", "speed-up");
  for (const Row& row : {Row{0.0, config::LeverArm::radius, "4x4x2000, frictionless"},
                         Row{1e5, config::LeverArm::contact_point, "4x4x2000, kt = k, contact-point arm"}}) {
    const config::Case c = seed_case(2000, row.kt, row.arm);
    double one = 0.0;
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      crystal::Dynamics dyn = excited(c);
      const StepCost s = seconds_per_step(dyn, std::max<long>(20, steps / 10), repeats, threads);
      if (threads == 1) one = s.wall;
      std::printf("%-34s %8d %12.1f %18.3g %18.3g %8.2fx\n", row.name, threads, 1e6 * s.wall, dyn.size() / s.wall,
                  dyn.size() / s.cpu, one / s.wall);
      print_phases(dyn, std::max<long>(20, steps / 10));
    }
    // The ceiling of that speed-up on this machine: two copies of the crystal, one a thread, nothing
    // shared and no synchronisation within a step; their steps against one copy's alone.
    const TwoCopies two = two_copies(c, std::max<long>(20, steps / 10), repeats);
    if (two.slower < 1e300)  // two CPUs to be had
      std::printf("%-34s %8s %12.1f %18.3g %18s %8.2fx  (two copies, one a thread: the slower %.1f, the faster %.1f "
                "us/step)\n",
                row.name, "2 copies", 1e6 * two.slower, 2 * two.particles / two.slower, "-",
                2 * one / two.slower, 1e6 * two.slower, 1e6 * two.faster);
  }
  omp_set_num_threads(1);
#endif
  std::printf("\ncost per step as layers grow (1 thread)\n%-13s %10s %10s %12s %16s %16s %14s\n", "case", "layers",
              "particles", "us/step", "ns/particle-step", "(by CPU time)", "bytes/particle");
  for (double kt : {0.0, 1e5}) {
    for (int layers : {200, 2000, 20000}) {
      const config::Case c = seed_case(layers, kt);
      crystal::Dynamics dyn = excited(c);
      dyn.parallel_min_particles = dyn.size() + 1;
      const long n = std::max<long>(20, steps * 200 / layers);
      const StepCost s = seconds_per_step(dyn, n, repeats, 1);
      std::printf("%-13s %10d %10zu %12.1f %16.1f %16.1f %14.0f\n", kt > 0 ? "kt = k" : "frictionless", layers,
                  dyn.size(), 1e6 * s.wall, 1e9 * s.wall / dyn.size(), 1e9 * s.cpu / dyn.size(),
                  double(state_bytes(dyn)) / dyn.size());
    }
  }
  return 0;
}
