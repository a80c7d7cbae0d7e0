// Throughput of the crystal time step (issue 4, "Speed"): particle-steps per second for the
// 3200-particle crystal of seed 002 with and without friction, on one and two threads; the
// cost per step as the number of layers grows; memory per particle.
// Usage: bench_crystal [steps=2000]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "config/case.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"

using namespace granwave;

namespace {

config::Case seed_case(int layers, double kt) {
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_p.toml");
  c.crystal->cells[2] = layers;
  c.contact.kt = kt;
  return c;
}

template <class T>
std::size_t bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

std::size_t state_bytes(const crystal::Dynamics& d) {
  std::size_t b = 0;
  for (const auto* v : {&d.x, &d.y, &d.z, &d.vx, &d.vy, &d.vz, &d.wx, &d.wy, &d.wz, &d.fx, &d.fy, &d.fz, &d.tx,
                        &d.ty, &d.tz, &d.x0, &d.y0, &d.z0, &d.radius, &d.mass, &d.inv_mass, &d.inv_inertia,
                        &d.inertia})
    b += bytes(*v);
  b += bytes(d.mobile);
  const auto& C = d.contacts;
  b += bytes(C.i) + bytes(C.j) + bytes(C.image_x) + bytes(C.image_y) + bytes(C.sliding) + bytes(C.first) +
       bytes(C.entries);
  for (const auto* v : {&C.shift_x, &C.shift_y, &C.xi_x, &C.xi_y, &C.xi_z, &C.delta, &C.f_x, &C.f_y, &C.f_z,
                        &C.nf_x, &C.nf_y, &C.nf_z, &C.dissipated})
    b += bytes(*v);
  return b + 3 * d.size() * sizeof(double);  // positions at the last list build
}

// Seconds per step after a short warm-up; the crystal is excited so the forces are not trivial.
double seconds_per_step(crystal::Dynamics& dyn, long steps) {
  for (int k = 0; k < 20; ++k) dyn.step();
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) dyn.step();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / steps;
}

crystal::Dynamics excited(const config::Case& c) {
  const crystal::Packing p = crystal::make_packing(c);
  crystal::Dynamics dyn(p, c.contact, *c.integrator.dt);
  std::vector<std::size_t> source;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.layer[q] < p.fixed_layers) source.push_back(q);
  dyn.displace(source, 0.0, 0.0, 1e-4 * p.d);
  return dyn;
}

}  // namespace

int main(int argc, char** argv) {
  const long steps = argc > 1 ? std::atol(argv[1]) : 2000;
  int max_threads = 1;
#ifdef _OPENMP
  max_threads = omp_get_max_threads();
#endif
  std::printf("crystal time step, %ld steps per measurement (OpenMP max threads %d)\n", steps, max_threads);
  std::printf("%-34s %8s %14s %14s\n", "case", "threads", "us/step", "particle-steps/s");
  for (double kt : {0.0, 1e5}) {
    const config::Case c = seed_case(200, kt);
    for (int threads : {1, 2}) {
#ifdef _OPENMP
      omp_set_num_threads(threads);
#else
      if (threads > 1) continue;
#endif
      crystal::Dynamics dyn = excited(c);
      dyn.parallel_min_particles = 0;  // force OpenMP on for this small crystal
      const double s = seconds_per_step(dyn, steps);
      std::printf("%-34s %8d %14.2f %14.3g\n", kt > 0 ? "4x4x200, kt = k (friction)" : "4x4x200, frictionless",
                  threads, 1e6 * s, dyn.size() / s);
    }
  }
#ifdef _OPENMP
  omp_set_num_threads(1);
#endif
  std::printf("\ncost per step as layers grow (frictionless, 1 thread)\n%-10s %10s %14s %16s %14s\n", "layers",
              "particles", "us/step", "ns/particle-step", "bytes/particle");
  for (int layers : {200, 2000, 20000}) {
    const config::Case c = seed_case(layers, 0.0);
    crystal::Dynamics dyn = excited(c);
    const long n = std::max<long>(20, steps * 200 / layers);
    const double s = seconds_per_step(dyn, n);
    std::printf("%-10d %10zu %14.1f %16.1f %14.0f\n", layers, dyn.size(), 1e6 * s, 1e9 * s / dyn.size(),
                double(state_bytes(dyn)) / dyn.size());
  }
  return 0;
}
