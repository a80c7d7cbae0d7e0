// The sheared and moving periodic box of the static probe's box strains (crystal::ImageMotion): the
// neighbour search with a shift of the +y images against a brute-force search over images, and a
// contact across the box's faces against the same contact inside a large box, its second sphere at
// the image's place and with the image's velocity (the shift in the branch vector, the box's rates
// in the relative velocity that stretches a tangential spring).
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "contact/linear_luding_params.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/neighbors.hpp"

using namespace granwave;

namespace {

using Pair = std::tuple<int, int, int, int>;  // i, j, image_x, image_y

std::vector<Pair> brute_force(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z,
                              const std::vector<double>& a, double box_x, double box_y, double skin, double shift) {
  std::vector<Pair> out;
  const int n = static_cast<int>(x.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int sy = -6; sy <= 6; ++sy)
        for (int sx = -8; sx <= 8; ++sx) {
          const double dx = x[j] + sx * box_x + sy * shift - x[i], dy = y[j] + sy * box_y - y[i], dz = z[j] - z[i];
          const double reach = a[i] + a[j] + skin;
          if (dx * dx + dy * dy + dz * dz < reach * reach) out.emplace_back(i, j, sx, sy);
        }
  std::sort(out.begin(), out.end());
  return out;
}

// Two spheres of radius a = 1 mm (rho = 2000) at p0 and p1 in a box box_x by box_y.
crystal::Packing two_spheres(const std::array<double, 3>& p0, const std::array<double, 3>& p1, double box) {
  crystal::Packing p;
  const double a = 1e-3, m = 2000.0 * 4.0 / 3.0 * std::numbers::pi * a * a * a;
  p.x = {p0[0], p1[0]};
  p.y = {p0[1], p1[1]};
  p.z = {p0[2], p1[2]};
  p.radius = {a, a};
  p.mass = {m, m};
  p.inertia = {0.4 * m * a * a, 0.4 * m * a * a};
  p.layer = {0, 0};
  p.fixed = {0, 0};
  p.box_x = p.box_y = box;
  p.d = p.d_prime = 2 * a;
  p.l0 = p.d / std::numbers::sqrt2;
  p.nx = p.ny = 1;
  p.layers = 1;
  return p;
}

}  // namespace

TEST_CASE("find_pairs in a sheared box = a brute-force search over the images", "[crystal][neighbors]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double box_x = 9.0, box_y = 7.0, skin = 0.1;
  std::vector<double> x, y, z, a;
  for (int p = 0; p < 90; ++p) {
    x.push_back(box_x * u(rng));
    y.push_back(box_y * u(rng));
    z.push_back(6.0 * u(rng));
    a.push_back(0.4 + 0.4 * u(rng));
  }
  for (const double shift : {0.0, 1e-7 * box_y, 0.37 * box_x, -1.6 * box_x, 4.3}) {
    const crystal::PairList found =
        crystal::find_pairs(x.data(), y.data(), z.data(), a.data(), x.size(), box_x, box_y, skin, nullptr, shift);
    std::vector<Pair> got;
    for (std::size_t c = 0; c < found.size(); ++c) got.emplace_back(found.i[c], found.j[c], found.image_x[c], found.image_y[c]);
    const std::vector<Pair> want = brute_force(x, y, z, a, box_x, box_y, skin, shift);
    INFO("shift " << shift);
    CHECK(want.size() > 100);
    CHECK(got == want);  // sorted by (i, j, image) as the contact list needs
  }
}

TEST_CASE("find_pairs in boxes one to three spheres across, fixed pairs left out = a brute-force search", "[crystal][neighbors]") {
  // Boxes so small that a pair touches through two images, one to three cells across.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t twice = 0;  // pairs found through more than one image
  for (const auto& [box_x, box_y] : {std::pair{2.1, 1.9}, std::pair{3.3, 5.0}, std::pair{1.2, 7.5}}) {
    std::vector<double> x, y, z, a;
    std::vector<std::uint8_t> skip;
    for (int p = 0; p < 120; ++p) {
      x.push_back(box_x * u(rng) + (p % 7 == 0 ? 3.0 * box_x : 0.0));  // some outside the box: any image
      y.push_back(box_y * u(rng) - (p % 5 == 0 ? 2.0 * box_y : 0.0));
      z.push_back(9.0 * u(rng));
      a.push_back(0.4 + 0.4 * u(rng));
      skip.push_back(p % 3 == 0);
    }
    const crystal::PairList found =
        crystal::find_pairs(x.data(), y.data(), z.data(), a.data(), x.size(), box_x, box_y, 0.1, skip.data());
    std::vector<Pair> got;
    for (std::size_t c = 0; c < found.size(); ++c) got.emplace_back(found.i[c], found.j[c], found.image_x[c], found.image_y[c]);
    std::vector<Pair> want;
    for (const Pair& q : brute_force(x, y, z, a, box_x, box_y, 0.1, 0.0))
      if (!(skip[std::get<0>(q)] && skip[std::get<1>(q)])) want.push_back(q);
    for (std::size_t k = 1; k < want.size(); ++k)
      twice += std::get<0>(want[k]) == std::get<0>(want[k - 1]) && std::get<1>(want[k]) == std::get<1>(want[k - 1]);
    INFO("box " << box_x << " x " << box_y);
    CHECK(want.size() > 200);
    CHECK(got == want);
  }
  CHECK(twice > 0);
}

TEST_CASE("a contact across the faces of a sheared, moving box = the same contact inside a large box",
          "[crystal][neighbors]") {
  const double a = 1e-3, box = 10 * a, shift = 3 * a, dt = 1e-8, overlap = 2e-6;
  // Sphere 1's image (-1, -1) touches sphere 0 along an oblique normal.
  const std::array<double, 3> p0{0.6 * a, 0.7 * a, 5 * a};
  const double e[3] = {-0.6, -0.7, 0.4};
  const double norm = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  std::array<double, 3> img;
  for (int k = 0; k < 3; ++k) img[k] = p0[k] + (2 * a - overlap) * e[k] / norm;
  const int sx = -1, sy = -1;
  const std::array<double, 3> p1{img[0] - sx * box - sy * shift, img[1] - sy * box, img[2]};
  crystal::ImageMotion motion;
  motion.shift_x = shift;
  motion.rate_x = 0.01, motion.rate_y = -0.02, motion.rate_shift = 0.03;  // m/s
  const double v_img[3] = {sx * motion.rate_x + sy * motion.rate_shift, sy * motion.rate_y, 0.0};

  contact::LinearLudingParams hooke;  // frictionless: the direct contact pass, positions only
  hooke.kn = 1e5;
  contact::LinearLudingParams spring = hooke;  // tangential spring: the gathered pass, the image velocity too
  spring.kt = 5e4;
  spring.friction.mu_static = spring.friction.mu_dynamic = 0.5;
  for (const bool with_spring : {false, true}) {
    INFO((with_spring ? "kt = kn/2" : "frictionless"));
    const contact::LinearLudingParams& law = with_spring ? spring : hooke;
    crystal::Dynamics sheared(two_spheres(p0, p1, box), law, dt);
    CHECK(sheared.contacts.size() == 0);  // unsheared, the image is 2.4 a from sphere 0
    sheared.set_box(box, box, with_spring ? motion : crystal::ImageMotion{shift});
    sheared.rebuild();
    REQUIRE(sheared.contacts.size() == 1);
    CHECK(sheared.contacts.image_x[0] == sx);
    CHECK(sheared.contacts.image_y[0] == sy);
    crystal::Dynamics inside(two_spheres(p0, img, 1.0), law, dt);
    REQUIRE(inside.contacts.size() == 1);
    if (with_spring) inside.vx[1] = v_img[0], inside.vy[1] = v_img[1], inside.vz[1] = v_img[2];
    sheared.compute_forces();  // the spring advances by v_t dt
    inside.compute_forces();
    CHECK(sheared.contacts.delta[0] == Approx(overlap).epsilon(1e-9));
    CHECK(sheared.contacts.delta[0] == Approx(inside.contacts.delta[0]).epsilon(1e-9));
    const double f_scale = hooke.kn * overlap;
    for (int p = 0; p < 2; ++p) {
      CHECK(std::abs(sheared.fx[p] - inside.fx[p]) < 1e-9 * f_scale);
      CHECK(std::abs(sheared.fy[p] - inside.fy[p]) < 1e-9 * f_scale);
      CHECK(std::abs(sheared.fz[p] - inside.fz[p]) < 1e-9 * f_scale);
      CHECK(std::abs(sheared.tx[p] - inside.tx[p]) < 1e-9 * f_scale * a);
      CHECK(std::abs(sheared.ty[p] - inside.ty[p]) < 1e-9 * f_scale * a);
      CHECK(std::abs(sheared.tz[p] - inside.tz[p]) < 1e-9 * f_scale * a);
    }
    if (with_spring) {  // the spring stretched: a tangential force of kt |v_t| dt
      const double ft = std::hypot(inside.tx[0], inside.ty[0], inside.tz[0]) / a;
      const double vn = (v_img[0] * e[0] + v_img[1] * e[1]) / norm;
      const double vt = std::sqrt(v_img[0] * v_img[0] + v_img[1] * v_img[1] - vn * vn);
      CHECK(ft == Approx(spring.kt * vt * dt).epsilon(1e-6));
    }
  }
}
