// The packing of seed 002 sec. 2.2 (geometry, contacts across periodic faces, system file) and
// the refusals of `crystal::check` / failures of `crystal::run`.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <vector>

#include "config/case.hpp"
#include "core/error.hpp"
#include "crystal/packing.hpp"
#include "crystal/simulation.hpp"
#include "crystal/trace_writer.hpp"
#include "io/h5.hpp"
#include "models.hpp"

using namespace granwave;

namespace {
config::Case small_case() {
  return config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_small.toml");
}
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("granwave_crystal_" + name)).string();
}
}  // namespace

TEST_CASE("FCC packing geometry: d', l0, box, equal overlaps, coordination 12", "[crystal][packing]") {
  config::Case c = small_case();
  c.crystal->cells = {4, 4, 12};
  const crystal::Packing p = crystal::make_packing(c);
  REQUIRE(p.size() == 4u * 4u * 12u);
  CHECK(p.d_prime == Approx(2e-3 * (1 - 1e-3)).epsilon(1e-15));
  CHECK(p.l0 == Approx(p.d_prime / std::numbers::sqrt2).epsilon(1e-15));
  CHECK(p.box_x == Approx(4 * p.d_prime).epsilon(1e-15));
  CHECK(p.delta == Approx(2e-6).epsilon(1e-9));
  CHECK(p.inertia[7] == Approx(0.4 * p.mass[7] * 1e-6).epsilon(1e-15));
  CHECK(p.mass[0] == Approx(2000 * 4.0 / 3.0 * std::numbers::pi * 1e-9).epsilon(1e-15));
  const auto contacts = crystal::list_contacts(p);
  std::vector<int> count(p.size(), 0);
  for (const auto& k : contacts) {
    CHECK(k.overlap == Approx(2e-6).epsilon(1e-6));
    ++count[k.i];
    ++count[k.j];
  }
  for (std::size_t q = 0; q < p.size(); ++q) {
    const bool end_layer = p.layer[q] == 0 || p.layer[q] == 11;
    CHECK(count[q] == (end_layer ? 8 : 12));
  }
  // Without pairs of two fixed particles: the two bottom and two top layers lose theirs.
  CHECK(crystal::list_contacts(p, false).size() < contacts.size());
}

TEST_CASE("a box two particles across: both periodic images are contacts", "[crystal][packing]") {
  const crystal::Packing p = crystal::make_packing(small_case());  // 2 x 2 x 40
  std::vector<int> count(p.size(), 0);
  for (const auto& k : crystal::list_contacts(p)) {
    ++count[k.i];
    ++count[k.j];
    CHECK(std::sqrt(k.bx * k.bx + k.by * k.by + k.bz * k.bz) == Approx(p.d_prime).epsilon(1e-12));
  }
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.layer[q] > 0 && p.layer[q] < 39) CHECK(count[q] == 12);
}

TEST_CASE("system file round trip and reuse by a run", "[crystal][packing]") {
  const config::Case c = small_case();
  const std::string path = temp_path("system.h5");
  crystal::build(c, path);
  const crystal::Packing a = crystal::make_packing(c), b = crystal::read_system(path);
  CHECK(a.x == b.x);
  CHECK(a.z == b.z);
  CHECK(a.radius == b.radius);
  CHECK(a.fixed == b.fixed);
  CHECK(a.layer == b.layer);
  CHECK(a.box_x == b.box_x);
  CHECK(a.l0 == b.l0);
  // run --system gives the same trace as a fresh build.
  RunRequest req;
  req.trace_path = temp_path("a.h5");
  std::ostringstream out;
  CHECK(crystal::run(c, req, out) == 0);
  req.trace_path = temp_path("b.h5");
  req.system_path = path;
  req.json = true;
  std::ostringstream out_json;
  CHECK(crystal::run(c, req, out_json) == 0);
  CHECK(out_json.str().front() == '{');
  io::H5Reader ra(temp_path("a.h5")), rb(temp_path("b.h5"));
  CHECK(ra.read_double("/crystal/layer_stress_zz") == rb.read_double("/crystal/layer_stress_zz"));
  CHECK(ra.attr_string("/", "time_convention") == "synchronous");
  CHECK(ra.attr_string("/", "status") == "complete");
  CHECK(ra.has("/system/position"));
  std::vector<std::size_t> dims;
  ra.read_double("/crystal/layer_velocity_z", &dims);
  CHECK(dims == std::vector<std::size_t>{101, 40});
  for (const char* f : {"a.h5", "b.h5", "system.h5"}) std::filesystem::remove(temp_path(f));
}

TEST_CASE("check refuses unstable dt, mu_d > mu_s, negative stiffness, warns above t_c/50", "[crystal][check]") {
  config::Case c = small_case();
  std::ostringstream out;
  crystal::check(c, out);
  CHECK(out.str().find("prestress sigma_0") != std::string::npos);
  CHECK(crystal::derive(c).sigma_0 == Approx(1.417e5).epsilon(3e-4));
  CHECK(crystal::derive(c).t_c == Approx(2.033e-5).epsilon(3e-4));
  CHECK(out.str().find("warning") == std::string::npos);
  c.integrator.dt = 1e-6;  // above t_c/50 = 4.07e-7, below the stability limit
  std::ostringstream warn;
  crystal::check(c, warn);
  CHECK(warn.str().find("warning: dt") != std::string::npos);
  c.integrator.dt = 1e-5;
  CHECK_THROWS_AS(crystal::check(c, out), InputError);
  c = small_case();
  c.contact.friction().mu_dynamic = 0.6;
  CHECK_THROWS_AS(crystal::check(c, out), InputError);
  c = small_case();
  c.contact.get<contact::LinearLudingParams>().kn = -1.0;
  CHECK_THROWS_AS(crystal::check(c, out), InputError);
  c = small_case();
  c.crystal->cells = {1, 2, 40};
  CHECK_THROWS_AS(crystal::check(c, out), InputError);
}

TEST_CASE("an unstable run stops naming the step and the particle and keeps its samples", "[crystal][check]") {
  config::Case c = small_case();
  c.integrator.dt = 2e-5;  // ten times the stability limit
  c.output.interval = 2e-5;
  std::ostringstream out;
  CHECK_THROWS_AS(crystal::check(c, out), InputError);  // run refuses it up front ...
  const crystal::Packing p = crystal::make_packing(c);
  const crystal::RunResult r = crystal::simulate(c, p);  // ... forced, it blows up
  REQUIRE(r.failed);
  CHECK(r.error.find("step") != std::string::npos);
  CHECK(r.error.find("particle") != std::string::npos);
  CHECK(r.traces.samples() >= 1);
  const std::string path = temp_path("unstable.h5");
  {
    io::H5Writer w(path);
    crystal::write_trace(c, p, r, w);
    w.commit();
  }
  io::H5Reader h(path);
  CHECK(h.attr_string("/", "status").rfind("failed", 0) == 0);
  CHECK(h.read_double("/time").size() == r.traces.samples());
  std::filesystem::remove(path);
}

TEST_CASE("ParaView snapshots: .vtp every vtk_every samples and a .pvd collection", "[crystal][vtk]") {
  config::Case c = small_case();
  c.integrator.t_end = 2e-5;  // 100 steps, 21 samples
  c.output.vtk_every = 10;    // samples 0, 10, 20
  RunRequest req;
  req.trace_path = temp_path("vtk.h5");
  std::ostringstream out;
  REQUIRE(crystal::run(c, req, out) == 0);
  const std::string base = temp_path("vtk");
  for (const char* k : {"_000000.vtp", "_000001.vtp", "_000002.vtp"}) CHECK(std::filesystem::exists(base + k));
  CHECK_FALSE(std::filesystem::exists(base + "_000003.vtp"));
  std::ifstream pvd(base + ".pvd");
  const std::string text((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  CHECK(text.find("granwave_crystal_vtk_000002.vtp") != std::string::npos);
  std::ifstream vtp(base + "_000001.vtp");
  const std::string snap((std::istreambuf_iterator<char>(vtp)), std::istreambuf_iterator<char>());
  CHECK(snap.find("NumberOfPoints=\"160\"") != std::string::npos);
  CHECK(snap.find("Name=\"stress\" NumberOfComponents=\"9\"") != std::string::npos);
  for (const char* k : {"_000000.vtp", "_000001.vtp", "_000002.vtp", ".pvd", ".h5"}) std::filesystem::remove(base + k);
}

TEST_CASE("the source step does not stretch the tangential springs: f_t = 0 at t = 0", "[crystal][excitation]") {
  // Seed 002 sec. 3.5 prepares its friction runs "such that f_t = 0 at t = 0"; YADE and LIGGGHTS
  // move the source without a velocity. So the step changes overlaps only: with kt = k the forces
  // on every particle right after it equal the frictionless crystal's, and the work booked is the
  // normal springs' energy change.
  config::Case c = config::load_case(std::string(GRANWAVE_SOURCE_DIR) + "/data/cases/crystal_small.toml");
  const crystal::Packing p = crystal::make_packing(c);
  std::vector<std::size_t> source;
  for (std::size_t q = 0; q < p.size(); ++q)
    if (p.layer[q] < p.fixed_layers) source.push_back(q);
  const double step = 1e-4 * p.d;
  auto stepped = [&](double kt, bool p_mode) {
    contact::LinearLudingParams cp = c.contact.get<contact::LinearLudingParams>();
    cp.kt = kt;
    cp.friction.mu_static = cp.friction.mu_dynamic = 0.5;
    crystal::Dynamics dyn(p, cp, *c.integrator.dt);
    dyn.displace(source, p_mode ? 0.0 : step, 0.0, p_mode ? step : 0.0);
    dyn.compute_forces();
    return dyn;
  };
  for (bool p_mode : {true, false}) {
    CAPTURE(p_mode);
    const auto frictional = stepped(c.contact.get<contact::LinearLudingParams>().kn, p_mode), frictionless = stepped(0.0, p_mode);
    const auto& C = frictional.contacts;
    REQUIRE(C.history_columns >= 3);  // xi_x, xi_y, xi_z (and a stick/slip flag if mu_s != mu_d)
    for (std::size_t k = 0; k < C.size(); ++k)
      for (std::size_t q = 0; q < 3; ++q) CHECK(C.history_column(q)[k] == 0.0);
    REQUIRE(frictional.size() == frictionless.size());
    for (std::size_t q = 0; q < frictional.size(); ++q) {
      CHECK(frictional.fx[q] == frictionless.fx[q]);
      CHECK(frictional.fz[q] == frictionless.fz[q]);
      CHECK(frictional.tx[q] == 0.0);
      CHECK(frictional.ty[q] == 0.0);
    }
    CHECK(frictional.work_in > 0.0);
    CHECK(frictional.work_in == frictionless.work_in);
  }
}

TEST_CASE("the list is rebuilt exactly when a particle has moved more than half the skin", "[crystal][neighbors]") {
  // Dynamics::step compares d^2 = dx^2 + dy^2 + dz^2 with the largest double whose root is <=
  // skin/2; the decision must be the root's, sqrt(d^2) > skin/2, in the last bits too, where
  // d^2 > (skin/2)^2 differs. A fixed particle is moved by hand in x and y (step() does not move
  // it, the others barely move in one step); the moves are searched for near the threshold.
  config::Case c = small_case();
  c.crystal->cells = {2, 2, 8};
  // A radius whose skin has (skin/2)^2 below the largest d^2 with root <= skin/2 (about half do).
  auto gap = [](double half) {
    double g = half * half;
    while (std::sqrt(std::nextafter(g, 1.0)) <= half) g = std::nextafter(g, 1.0);
    return g > half * half;
  };
  crystal::Packing p;
  for (int k = 0; k < 100; ++k) {
    c.crystal->radius = 1e-3 * (1.0 + 0.01 * k);
    p = crystal::make_packing(c);
    if (gap(0.5 * crystal::list_skin(p))) break;
  }
  const double half = 0.5 * crystal::list_skin(p);
  REQUIRE(gap(half));
  std::size_t q = 0;
  while (!p.fixed[q]) ++q;
  struct Move {
    double x, y;
    bool far;
  };
  std::vector<Move> moves;
  bool root_near_square_far = false;  // sqrt(d^2) <= skin/2 although d^2 > (skin/2)^2
  for (int k = 0; k < 4000 && !(root_near_square_far && moves.size() >= 6); ++k) {
    const double ux = 0.6 + 1e-4 * k, x = p.x[q] + ux * half;
    const double dx = x - p.x[q];
    double y = p.y[q] + std::sqrt(half * half - dx * dx);
    for (int t = 0; t < 8; ++t) y = std::nextafter(y, -1.0);
    for (int t = 0; t < 16; ++t, y = std::nextafter(y, 1.0)) {
      const double dy = y - p.y[q], d2 = dx * dx + dy * dy + 0.0 * 0.0;
      const bool far = std::sqrt(d2) > half, square = d2 > half * half;
      if (far != square && !root_near_square_far) {
        root_near_square_far = true;
        moves.push_back({x, y, far});
      } else if (moves.size() < 6 && t % 5 == 0) {
        moves.push_back({x, y, far});
      }
    }
  }
  REQUIRE(root_near_square_far);  // the threshold's last bits are exercised
  for (const double o : {0.9 * half, std::nextafter(half, 1.0), 1.1 * half})
    moves.push_back({p.x[q] + o, p.y[q], std::sqrt((p.x[q] + o - p.x[q]) * (p.x[q] + o - p.x[q])) > half});
  int rebuilt = 0;
  for (const Move& m : moves) {
    crystal::Dynamics dyn(p, c.contact, crystal::derive(c).dt);
    dyn.x[q] = m.x;  // x_build is 0 at construction: the displacement since the build is x - x0
    dyn.y[q] = m.y;
    const long before = dyn.rebuilds;
    dyn.step();
    INFO("move (" << m.x - p.x[q] << ", " << m.y - p.y[q] << "), half skin " << half);
    CHECK((dyn.rebuilds > before) == m.far);
    rebuilt += m.far;
  }
  CHECK(rebuilt >= 2);
  CHECK(rebuilt < static_cast<int>(moves.size()));
}
