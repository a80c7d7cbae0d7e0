// The slab decomposition of one crystal run (crystal/slab.hpp, docs/design.md §2.8) without MPI:
// the plan (who owns which layers, the halo depth, the refusals), and R ranks played by R threads
// of this process through an in-process SlabComm, whose traces must be the serial run's bit for
// bit. The same logic runs under mpirun in tests/mpi/run_ranks.py; this one also runs under
// ASan/UBSan and in builds without MPI.
#include <catch2/catch.hpp>
#include <algorithm>
#include <barrier>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

#include "config/case.hpp"
#include "core/error.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "crystal/slab.hpp"

using namespace granwave;

namespace {

config::Case small_case() {
  return config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_small.toml");
}

// R ranks as threads: every call is collective, as MPI's are; two barriers per call so that no
// rank overwrites its slot before every rank has read it.
struct Team {
  explicit Team(int ranks) : R(ranks), sync(ranks), slot(ranks), slot2(ranks), value(ranks) {}
  int R;
  std::barrier<> sync;
  std::vector<std::vector<double>> slot, slot2;
  std::vector<double> value;
};

class ThreadComm final : public crystal::SlabComm {
 public:
  ThreadComm(Team& t, int rank) : t_(t), rank_(rank) {}
  int rank() const override { return rank_; }
  int ranks() const override { return t_.R; }
  void exchange(const std::vector<double>& to_below, std::vector<double>& from_below, const std::vector<double>& to_above,
                std::vector<double>& from_above) override {
    t_.slot[rank_] = to_above;
    t_.slot2[rank_] = to_below;
    t_.sync.arrive_and_wait();
    if (rank_ > 0) copy_sized(t_.slot[rank_ - 1], from_below);
    if (rank_ + 1 < t_.R) copy_sized(t_.slot2[rank_ + 1], from_above);
    t_.sync.arrive_and_wait();
  }
  double max(double v) override {
    t_.value[rank_] = v;
    t_.sync.arrive_and_wait();
    const double m = *std::max_element(t_.value.begin(), t_.value.end());
    t_.sync.arrive_and_wait();
    return m;
  }
  void allgather(const std::vector<double>& mine, std::vector<double>& all) override { collect(mine, all, true); }
  void gather(const std::vector<double>& mine, std::vector<double>& all) override { collect(mine, all, rank_ == 0); }

 private:
  static void copy_sized(const std::vector<double>& from, std::vector<double>& to) {
    // MPI would truncate or fail: the sizes must agree. (Not a Catch2 assertion: this runs on
    // the ranks' threads; an exception there ends the test executable, a failure either way.)
    if (from.size() != to.size()) throw std::logic_error("halo message sizes differ between neighbours");
    std::copy(from.begin(), from.end(), to.begin());
  }
  void collect(const std::vector<double>& mine, std::vector<double>& all, bool receive) {
    t_.slot[rank_] = mine;
    t_.sync.arrive_and_wait();
    if (receive) {
      all.clear();
      for (const auto& s : t_.slot) all.insert(all.end(), s.begin(), s.end());
    }
    t_.sync.arrive_and_wait();
  }
  Team& t_;
  int rank_;
};

// Rank 0's result of simulate() on R thread-ranks.
crystal::RunResult on_ranks(const config::Case& c, const crystal::Packing& p, int R) {
  Team team(R);
  std::vector<crystal::RunResult> out(static_cast<std::size_t>(R));
  std::vector<std::thread> threads;
  for (int r = 0; r < R; ++r)
    threads.emplace_back([&, r] { out[r] = crystal::simulate(c, p, {}, std::make_shared<ThreadComm>(team, r)); });
  for (auto& t : threads) t.join();
  return out[0];
}

void same_traces(const crystal::Traces& a, const crystal::Traces& b) {
  // Exact equality of every series: the trace file's datasets, bit for bit.
  CHECK(a.time == b.time);
  CHECK(a["layer_stress_zz"] == b["layer_stress_zz"]);
  CHECK(a["layer_stress_zx"] == b["layer_stress_zx"]);
  CHECK(a["layer_displacement_z"] == b["layer_displacement_z"]);
  CHECK(a["layer_displacement_x"] == b["layer_displacement_x"]);
  CHECK(a["layer_velocity_z"] == b["layer_velocity_z"]);
  CHECK(a["layer_velocity_x"] == b["layer_velocity_x"]);
  CHECK(a["coordination"] == b["coordination"]);
  CHECK(a["kinetic"] == b["kinetic"]);
  CHECK(a["potential"] == b["potential"]);
  CHECK(a["dissipated"] == b["dissipated"]);
  CHECK(a["work_in"] == b["work_in"]);
  CHECK(a["verlet_correction"] == b["verlet_correction"]);
}

}  // namespace

TEST_CASE("slab plan: even split of whole layers, halo 1 for FCC, refusals", "[crystal][slab]") {
  config::Case c = small_case();  // 2 x 2 x 40
  const crystal::Packing p = crystal::make_packing(c);
  Team team(3);
  auto comm = std::make_shared<ThreadComm>(team, 1);
  const crystal::SlabPlan s = crystal::plan_slab(p, crystal::list_skin(p), comm, c.path);
  CHECK(s.halo == 1);
  CHECK(s.first_layer == std::vector<int>{0, 14, 27, 40});  // 40 = 14 + 13 + 13
  CHECK(s.own_lo == 14u * 4u);
  CHECK(s.own_hi == 27u * 4u);
  CHECK(s.held_lo == 13u * 4u);
  CHECK(s.held_hi == 28u * 4u);
  // The bound that keeps the next layer but one out of reach: (2 l0 - d - skin)/2 = 0.18 d here.
  CHECK(s.z_tolerance == Approx(0.5 * (2.0 * p.l0 - p.d - 0.1 * 0.5 * p.d)).epsilon(1e-9));

  Team many(41);
  REQUIRE_THROWS_AS(crystal::plan_slab(p, crystal::list_skin(p), std::make_shared<ThreadComm>(many, 0), c.path),
                    InputError);
  try {
    crystal::plan_slab(p, crystal::list_skin(p), std::make_shared<ThreadComm>(many, 0), c.path);
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("crystal.cells[2] = 40 layers") != std::string::npos);
    CHECK(std::string(e.what()).find("at most 40 ranks") != std::string::npos);
  }
  crystal::Packing shuffled = p;
  std::swap(shuffled.layer[0], shuffled.layer[10]);
  REQUIRE_THROWS_AS(crystal::plan_slab(shuffled, crystal::list_skin(p), comm, c.path), InputError);
}

TEST_CASE("slab ranks as threads give the serial traces bit for bit: P, S with friction, sliding, damped",
          "[crystal][slab]") {
  config::Case c = small_case();
  c.crystal->cells = {3, 3, 16};
  c.integrator.t_end = 3e-5;
  SECTION("P, frictionless") {}
  SECTION("S, kt = k, mu = 0.5, contact-point arm") {
    c.excitation.mode = config::Excitation::Mode::S;
    c.contact.get<contact::LinearLudingParams>().kt = c.contact.get<contact::LinearLudingParams>().kn;
    c.contact.friction().lever_arm = config::LeverArm::contact_point;
  }
  SECTION("sliding and damped with stick-slip: kt = k, mu_s = 0.002, mu_d = 0.001, dashpots, clip") {
    c.excitation.amplitude = 1e-3;
    c.contact.get<contact::LinearLudingParams>().kt = c.contact.get<contact::LinearLudingParams>().kn;
    c.contact.friction().mu_static = 0.002;
    c.contact.friction().mu_dynamic = 0.001;
    c.contact.get<contact::LinearLudingParams>().gamma_n = 0.05;
    c.contact.get<contact::LinearLudingParams>().gamma_t = 0.02;
    c.contact.friction().normal_tension = config::NormalTension::clip;
  }
  SECTION("velocity drive with friction") {
    c.excitation.drive = config::Excitation::Drive::velocity;
    c.excitation.amplitude = 0.02;
    c.contact.get<contact::LinearLudingParams>().kt = c.contact.get<contact::LinearLudingParams>().kn;
  }
  const crystal::Packing p = crystal::make_packing(c);
  const crystal::RunResult serial = crystal::simulate(c, p);
  REQUIRE_FALSE(serial.failed);
  REQUIRE(serial.traces.samples() > 10);
  for (int R : {2, 3, 5}) {
    INFO("R = " << R);
    const crystal::RunResult slab = on_ranks(c, p, R);
    REQUIRE_FALSE(slab.failed);
    CHECK(slab.rebuilds == serial.rebuilds);
    CHECK(slab.rank_seconds.size() == static_cast<std::size_t>(R));
    same_traces(slab.traces, serial.traces);
  }
}

TEST_CASE("slab ranks as threads rebuild on the same steps as the serial run", "[crystal][slab]") {
  config::Case c = small_case();
  c.crystal->cells = {3, 3, 12};
  c.integrator.t_end = 6e-5;
  c.excitation.mode = config::Excitation::Mode::S;
  c.excitation.amplitude = 0.06;  // a shear step beyond the skin: the layers move past it in turn
  const crystal::Packing p = crystal::make_packing(c);
  const crystal::RunResult serial = crystal::simulate(c, p);
  REQUIRE(serial.rebuilds >= 3);
  const crystal::RunResult slab = on_ranks(c, p, 3);
  CHECK(slab.rebuilds == serial.rebuilds);
  same_traces(slab.traces, serial.traces);
}

TEST_CASE("slab ranks as threads: rank 0's phases, the halo exchange one of them, add up to its wall time",
          "[crystal][slab][phases]") {
  // A unit test of the bookkeeping (crystal::RunResult::phases), not physics.
  config::Case c = small_case();
  c.integrator.t_end = 4e-5;
  const crystal::RunResult r = on_ranks(c, crystal::make_packing(c), 2);
  REQUIRE_FALSE(r.failed);
  REQUIRE(r.seconds > 0.0);
  CHECK(r.phases.seconds[crystal::PhaseTimes::halo] > 0.0);
  CHECK(r.phases.seconds[crystal::PhaseTimes::contact_pass] > 0.0);
  CHECK(std::abs(r.phases.total() - r.seconds) <= 0.02 * r.seconds);
}
