// Throughput of the chain integrators: bead-steps per second for a 500-bead chain on one core
// (issue 2: velocity Verlet >= 3e8, RK4 >= 8e7). Plain program: prints one line per scheme.
//   bench_chain [nbeads=500] [seconds=1.0]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

#include "chain/chain.hpp"
#include "config/case.hpp"
#include "../tests/physics/chain_cases.hpp"  // the Table 1 materials

using namespace granwave;

// CPU time of this thread: on a shared machine it leaves out the time other processes held the core.
static double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

int main(int argc, char** argv) {
  const int nbeads = argc > 1 ? std::atoi(argv[1]) : 500;
  const double seconds = argc > 2 ? std::atof(argv[2]) : 1.0;
  // Random (large steel, aluminium) dimers with a large-steel striker against the brass wall;
  // dt = 1e-8 s, so the pulse stays inside the chain for the whole timed window.
  std::string spins;
  for (int k = 0; k < nbeads / 2; ++k) spins += (k * 7 % 3 == 0) ? '0' : '1';
  const std::string text = R"([case]
name = "bench"
model = "chain"
)" + std::string(chain_test::kMaterials) + R"([chain]
striker = { material = "large_steel", velocity = 0.443 }
wall = "brass"
cell = ["large_steel", "aluminium"]
[[chain.segment]]
spins = ")" + spins + R"("
[integrator]
dt = 1e-8
t_end = 1e-3
)";
  const auto c = config::parse_case(text, "bench");
  const auto sys = chain::build_chain(c);
  std::printf("chain of %zu beads, dt = 1e-8 s, one core\n", sys.nbeads());
  for (auto scheme : {config::Scheme::verlet, config::Scheme::rk4}) {
    chain::Stepper st(sys, scheme, 1e-8);
    st.advance(1000);  // warm up
    std::size_t steps = 0, batch = 1000;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_seconds();
    double elapsed = 0.0;
    while (elapsed < seconds) {
      st.advance(batch);
      steps += batch;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    const double cpu = thread_cpu_seconds() - c0;
    const double work = static_cast<double>(steps) * static_cast<double>(sys.nbeads());
    const double rate = work / cpu;
    std::printf("%-16s %.3g bead-steps/s of CPU time (%.3f ns per bead-step; wall clock %.3g/s), %zu steps, t = %.3g ms, "
                "E_kin %.6g J\n",
                scheme == config::Scheme::verlet ? "velocity Verlet" : "RK4", rate, 1e9 / rate, work / elapsed, steps,
                st.time() * 1e3, st.kinetic_energy());
  }
  return 0;
}
