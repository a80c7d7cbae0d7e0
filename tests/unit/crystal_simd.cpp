// The SIMD layer (crystal/simd.hpp) and what is built on it (crystal/kernel_gather.hpp,
// crystal/particle_lanes.hpp), each vector routine against its scalar twin written out here, bit
// for bit: the 4 x 4 transpose, a lattice row's shifted vectors, the masks, the widened floats, the particle rows, the gather of a
// chunk's columns, the scatter of contact sums into rows (the particle pass's order of additions),
// the particle passes' rows of sums, torques, kicks and drift. Values include signed zeros,
// subnormals and large magnitudes, and counts that are not multiples of four (the scalar tails).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "crystal/kernel_gather.hpp"
#include "crystal/packing.hpp"
#include "crystal/particle_lanes.hpp"
#include "crystal/simd.hpp"

using namespace granwave;
using namespace granwave::crystal;

#ifdef GRANWAVE_GATHER_VECTORS

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Doubles of many kinds: signs, zeros, subnormals, large and small magnitudes (no sum or product
// overflows: a NaN's payload is not what is compared here).
std::vector<double> mixed_values(std::size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double kinds[] = {0.0, -0.0, std::numeric_limits<double>::denorm_min(), -3e-310, 1e150, -7.5e-3, 1.0, 2.5e12};
  std::vector<double> v(n);
  for (std::size_t k = 0; k < n; ++k) v[k] = k % 5 == 0 ? kinds[(k / 5) % 8] : u(rng) * std::pow(10.0, static_cast<int>(k % 7) - 3);
  return v;
}

// A Dynamics of n particles (a 2 x 2 crystal cut to n) whose state is set to mixed values.
Dynamics particles(std::size_t n) {
  config::Case c = config::parse_case(
      "[case]\nname = \"simd\"\nmodel = \"crystal\"\n[crystal]\nlattice = \"fcc\"\ncells = [2, 2, 8]\nradius = 1e-3\n"
      "density = 2000\noverlap = 1e-3\nfixed_layers = 1\n[contact]\nkn = 1e5\nkt = 5e4\nmu_static = 0.5\n"
      "mu_dynamic = 0.5\n[excitation]\nmode = \"P\"\namplitude = 1e-4\n[integrator]\ndt = 1e-7\nt_end = 1e-6\n",
      "simd");
  Dynamics d(lattice_packing(c), c.contact, 1e-7);
  REQUIRE(d.size() >= n);
  for (auto* v : {&d.x, &d.y, &d.z, &d.vx, &d.vy, &d.vz, &d.wx, &d.wy, &d.wz, &d.radius}) v->resize(n);
  int seed = 1;
  for (auto* v : {&d.x, &d.y, &d.z, &d.vx, &d.vy, &d.vz, &d.wx, &d.wy, &d.wz, &d.radius}) {
    const std::vector<double> m = mixed_values(n, seed++);
    v->assign(m.begin(), m.end());
  }
  return d;
}

}  // namespace

TEST_CASE("simd: transpose4, transpose4_rows, mask4, the root, widened floats and bytes = their scalar twins", "[crystal][simd]") {
  const std::vector<double> v = mixed_values(64, 3);
  for (std::size_t k = 0; k + 16 <= v.size(); k += 16) {
    simd::V4 c[4];
    simd::transpose4(simd::load4(&v[k]), simd::load4(&v[k + 4]), simd::load4(&v[k + 8]), simd::load4(&v[k + 12]), c[0],
                     c[1], c[2], c[3]);
    double out[16];
    for (int q = 0; q < 4; ++q) simd::store4(out + 4 * q, c[q]);
    for (int r = 0; r < 4; ++r)
      for (int q = 0; q < 4; ++q) CHECK(same_bits(out[4 * q + r], v[k + 4 * r + q]));  // column q, lane r = row r's q
  }
  // The transpose from memory (the gather's): rows anywhere, 8-byte aligned; and its halves with a
  // lane-wise subtraction between, against the scalar differences (the gather's v_i - v_j).
  for (std::size_t k = 0; k + 19 <= v.size(); k += 5) {
    const double* r[4] = {&v[k + 15], &v[k + 1], &v[k + 7], &v[k + 3]};  // overlapping, out of order
    simd::V4 c[4];
    simd::transpose4_rows(r[0], r[1], r[2], r[3], c[0], c[1], c[2], c[3]);
    for (int q = 0; q < 4; ++q)
      for (int l = 0; l < 4; ++l) CHECK(same_bits(c[q][l], r[l][q]));
    const double* s[4] = {&v[k + 2], &v[k + 11], &v[k + 9], &v[k]};
    simd::V4 hi[4], hj[4];
    simd::row_halves4(r[0], r[1], r[2], r[3], hi[0], hi[1], hi[2], hi[3]);
    simd::row_halves4(s[0], s[1], s[2], s[3], hj[0], hj[1], hj[2], hj[3]);
    simd::columns_of_halves4(hi[0] - hj[0], hi[1] - hj[1], hi[2] - hj[2], hi[3] - hj[3], c[0], c[1], c[2], c[3]);
    for (int q = 0; q < 4; ++q)
      for (int l = 0; l < 4; ++l) CHECK(same_bits(c[q][l], r[l][q] - s[l][q]));
  }
  const std::uint8_t flags[8] = {0, 1, 2, 255, 0, 0, 7, 1};
  for (int k = 0; k < 8; k += 4) {
    const simd::V4m m = simd::mask4(flags + k);
    for (int q = 0; q < 4; ++q) CHECK(m[q] == (flags[k + q] ? -1LL : 0LL));
  }
  const std::int8_t b[7] = {0, -128, 127, -1, 1, -7, 64};
  for (int k = 0; k < 4; ++k) {  // every alignment
    const simd::V4 e = simd::load4(b + k);
    for (int q = 0; q < 4; ++q) CHECK(same_bits(e[q], static_cast<double>(b[k + q])));
  }
  // The lane-wise root: std::sqrt's bits, subnormals, zeros of both signs and a negative (NaN) included.
  for (std::size_t k = 0; k + 4 <= v.size(); k += 4) {
    const simd::V4 q = simd::sqrt4(simd::load4(&v[k]));
    for (int l = 0; l < 4; ++l) CHECK(same_bits(q[l], std::sqrt(v[k + l])));
  }
  const float f[6] = {0.5f, -0.0f, 1e-40f, 3.25e7f, -1.0f, 7.0f};
  const simd::V4 w = simd::load4(f + 1);  // unaligned
  for (int q = 0; q < 4; ++q) CHECK(same_bits(w[q], static_cast<double>(f[1 + q])));
}

TEST_CASE("simd: row_shifted4 = the row's values taken one place along, wrapping", "[crystal][simd]") {
  for (int m : {1, 2, 3}) {
    const std::vector<double> row = mixed_values(4 * m, 7 + m);
    for (int k = 0; k < m; ++k) {
      const simd::V4 s0 = simd::row_shifted4<0>(row.data(), m, k), up = simd::row_shifted4<1>(row.data(), m, k),
                     down = simd::row_shifted4<-1>(row.data(), m, k);
      for (int l = 0; l < 4; ++l) {
        CAPTURE(m, k, l);
        const int at = 4 * k + l, n = 4 * m;
        CHECK(same_bits(s0[l], row[at]));
        CHECK(same_bits(up[l], row[(at + 1) % n]));
        CHECK(same_bits(down[l], row[(at - 1 + n) % n]));
      }
    }
  }
}

TEST_CASE("simd: stream_copy = the values copied one at a time", "[crystal][simd]") {
  const std::vector<double> v = mixed_values(37, 5);
  for (const std::int64_t n : {0, 1, 2, 7, 37}) {
    std::vector<double> out(38, 1.0);
    simd::stream_copy(out.data(), v.data(), n);
    simd::fence_streams();
    for (std::int64_t u = 0; u < n; ++u) CHECK(same_bits(out[u], v[u]));
    CHECK(out[n] == 1.0);  // nothing beyond
  }
}

TEST_CASE("simd: the particle rows (fill_rows) = the state copied one value at a time", "[crystal][simd]") {
  // Plain stores, and stores past the caches (simd::stream4) into rows whose four particles are
  // one cache line apart (the SpreadAllocator of Dynamics::gather_rows) or only 16 bytes aligned.
  for (const std::size_t n : {std::size_t{4}, std::size_t{13}, std::size_t{30}})
  for (const int route : {0, 1, 2}) {
    const Dynamics d = particles(n);
    std::vector<double> storage(12 * n + 2, 1.0);
    SpreadVector<double> lined(12 * n, 1.0);
    double* rows = route == 0 ? storage.data() : route == 1 ? lined.data() : storage.data() + 2;
    if (route == 0)
      kernel::fill_rows(d, rows, 0, static_cast<std::int64_t>(n));
    else
      kernel::fill_rows<true>(d, rows, 0, static_cast<std::int64_t>(n)), simd::fence_streams();
    for (std::size_t p = 0; p < n; ++p) {
      const double want[12] = {d.x[p], d.y[p], d.z[p], d.radius[p], d.vx[p], d.vy[p],
                               d.vz[p], 0.0,    d.wx[p], d.wy[p],     d.wz[p], 0.0};
      for (int k = 0; k < 4; ++k) {
        CHECK(same_bits(rows[4 * p + k], want[k]));
        CHECK(same_bits(rows[4 * (n + p) + k], want[4 + k]));
        CHECK(same_bits(rows[4 * (2 * n + p) + k], want[8 + k]));
      }
    }
  }
}

TEST_CASE("simd: the state read back from the particle rows (state_of_rows) = the state the rows were filled from",
          "[crystal][simd]") {
  for (const std::size_t n : {std::size_t{4}, std::size_t{16}}) {
    const Dynamics d = particles(n);
    SpreadVector<double> rows(12 * n, 1.0);
    kernel::fill_rows(d, rows.data(), 0, static_cast<std::int64_t>(n));
    for (std::int64_t p = 0; p < static_cast<std::int64_t>(n); p += 4) {
      simd::V4 q[10];
      lanes::state_of_rows(rows.data(), static_cast<std::int64_t>(n), p, q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7],
                           q[8], q[9]);
      for (int l = 0; l < 4; ++l) {
        const std::size_t i = static_cast<std::size_t>(p + l);
        const double want[10] = {d.x[i], d.y[i], d.z[i], d.radius[i], d.vx[i], d.vy[i], d.vz[i], d.wx[i], d.wy[i], d.wz[i]};
        for (int k = 0; k < 10; ++k) CHECK(same_bits(q[k][l], want[k]));
      }
    }
  }
}

TEST_CASE("simd: the gather of a chunk's columns = the contact's own scalar expressions", "[crystal][simd]") {
  const std::size_t n = 30;
  const Dynamics d = particles(n);
  std::vector<double> rows(12 * n);
  kernel::fill_rows(d, rows.data(), 0, static_cast<std::int64_t>(n));
  std::mt19937 rng(5);
  std::vector<std::int32_t> ci, cj;
  std::vector<std::int8_t> imx, imy;
  for (int c = 0; c < 47; ++c) {  // not a multiple of four
    ci.push_back(static_cast<std::int32_t>(rng() % n));
    cj.push_back(static_cast<std::int32_t>(rng() % n));
    imx.push_back(static_cast<std::int8_t>(static_cast<int>(rng() % 5) - 2));
    imy.push_back(static_cast<std::int8_t>(static_cast<int>(rng() % 255) - 127));
  }
  const double box_x = 3.1e-3, box_y = 7.7e-3;
  for (const std::int64_t s0 : {std::int64_t{0}, std::int64_t{3}}) {
    const std::int64_t s1 = static_cast<std::int64_t>(ci.size());
    kernel::Gathered g;
    kernel::gather(g, s0, s1, ci.data(), cj.data(), imx.data(), imy.data(), box_x, box_y, rows.data(),
                   rows.data() + 4 * n, rows.data() + 8 * n);
    using G = kernel::Gathered;
    for (std::int64_t c = s0; c < s1; ++c) {
      const std::int64_t u = c - s0;
      const int i = ci[c], j = cj[c];
      CHECK(same_bits(g.col[G::bx][u], (d.x[j] + imx[c] * box_x) - d.x[i]));
      CHECK(same_bits(g.col[G::by][u], (d.y[j] + imy[c] * box_y) - d.y[i]));
      CHECK(same_bits(g.col[G::bz][u], d.z[j] - d.z[i]));
      const double bx = (d.x[j] + imx[c] * box_x) - d.x[i], by = (d.y[j] + imy[c] * box_y) - d.y[i],
                   bz = d.z[j] - d.z[i];
      CHECK(same_bits(g.col[G::r][u], std::sqrt(bx * bx + by * by + bz * bz)));
      CHECK(same_bits(g.col[G::inv_r][u], 1.0 / std::sqrt(bx * bx + by * by + bz * bz)));
      CHECK(same_bits(g.col[G::reach][u], d.radius[i] + d.radius[j]));
      CHECK(same_bits(g.col[G::a_i][u], d.radius[i]));
      CHECK(same_bits(g.col[G::a_j][u], d.radius[j]));
      CHECK(same_bits(g.col[G::dvx][u], d.vx[i] - d.vx[j]));
      CHECK(same_bits(g.col[G::dvy][u], d.vy[i] - d.vy[j]));
      CHECK(same_bits(g.col[G::dvz][u], d.vz[i] - d.vz[j]));
      CHECK(same_bits(g.col[G::wix][u], d.wx[i]));
      CHECK(same_bits(g.col[G::wjz][u], d.wz[j]));
    }
  }
}

TEST_CASE("simd: the scatter into rows = the particle pass's sums in list order", "[crystal][simd]") {
  // A list as the contact list is: sorted by i, j > i, runs of equal i, particles met as j first.
  const std::int64_t n = 23;
  std::mt19937 rng(9);
  std::vector<std::int32_t> ci, cj;
  for (std::int32_t i = 0; i < n - 1; ++i)
    for (int k = 0; k < static_cast<int>(rng() % 4); ++k) {
      ci.push_back(i);
      cj.push_back(static_cast<std::int32_t>(i + 1 + rng() % (n - 1 - i)));
    }
  const std::int64_t m = static_cast<std::int64_t>(ci.size());
  REQUIRE(m % 4 != 0);
  std::vector<double> f[3], nf[3], cp[3];
  for (int q = 0; q < 3; ++q) f[q] = mixed_values(m, 20 + q), nf[q] = mixed_values(m, 30 + q), cp[q] = mixed_values(m, 40 + q);
  const std::vector<double> delta = mixed_values(m, 50);
  // The scalar twin: each sum starts from 0.0; i adds f, n x f^t, delta n x f^t and the couple; j
  // subtracts f and the couple and adds the others, contact by contact in list order.
  constexpr int K = 3;
  std::vector<double> want(4 * (K + 1) * n, 0.0);
  for (std::int64_t c = 0; c < m; ++c)
    for (int q = 0; q < 3; ++q) {
      double* w = want.data();
      const std::int64_t i = ci[c], j = cj[c];
      w[4 * i + q] += f[q][c];
      w[4 * (n + i) + q] += nf[q][c];
      w[4 * (2 * n + i) + q] += delta[c] * nf[q][c];
      w[4 * (3 * n + i) + q] += cp[q][c];
      w[4 * j + q] -= f[q][c];
      w[4 * (n + j) + q] += nf[q][c];
      w[4 * (2 * n + j) + q] += delta[c] * nf[q][c];
      w[4 * (3 * n + j) + q] -= cp[q][c];
    }
  std::vector<double> rows(4 * (K + 1) * n, 0.0);
  // In two calls, as two chunks of the contact pass (the second starting inside a run of equal i).
  const std::int64_t half = m / 2 + 1;
  for (const auto& [c0, c1] : {std::pair{std::int64_t{0}, half}, std::pair{half, m}})
    kernel::scatter<K, true>(rows.data(), n, c1 - c0, ci.data() + c0, cj.data() + c0, f[0].data() + c0,
                             f[1].data() + c0, f[2].data() + c0, nf[0].data() + c0, nf[1].data() + c0,
                             nf[2].data() + c0, delta.data() + c0, cp[0].data() + c0, cp[1].data() + c0,
                             cp[2].data() + c0);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    INFO("row entry " << k << ": " << rows[k] << " against " << want[k]);
    CHECK(same_bits(rows[k], want[k]));
  }
}

TEST_CASE("simd: the particle passes' steps four at a time = the passes' scalar code", "[crystal][simd]") {
  const std::vector<double> v = mixed_values(96, 60);
  const std::uint8_t on[4] = {1, 0, 3, 1};
  const simd::V4m m = lanes::mobile4(on, 0);
  const double h = 0.5e-7, dt = 1e-7;
  const simd::V4 hv{h, h, h, h}, dtv{dt, dt, dt, dt};
  auto lane = [](const simd::V4& x, int q) { return x[q]; };
  // take_rows: four rows of a sum as x, y, z lanes, the rows zeroed.
  std::vector<double> rows(v.begin(), v.begin() + 16);
  simd::V4 cx, cy, cz;
  lanes::take_rows(rows.data(), cx, cy, cz);
  for (int q = 0; q < 4; ++q) {
    CHECK(same_bits(lane(cx, q), v[4 * q]));
    CHECK(same_bits(lane(cy, q), v[4 * q + 1]));
    CHECK(same_bits(lane(cz, q), v[4 * q + 2]));
  }
  for (double r : rows) CHECK(same_bits(r, 0.0));
  // torques_of_rows: -a n, + 1/2 delta n (contact-point arm), + the couples (finish_pass's tail).
  const std::vector<double> a(v.begin() + 80, v.begin() + 84);
  for (const int kind : {1, 2, 3}) {
    std::vector<double> rn(v.begin() + 16, v.begin() + 32), rd(v.begin() + 32, v.begin() + 48),
        rc(v.begin() + 48, v.begin() + 64);
    const std::vector<double> n0 = rn, d0 = rd, c0 = rc;
    simd::V4 t[3];
    if (kind == 1) lanes::torques_of_rows<1, false>(rn.data(), rd.data(), rc.data(), a.data(), 0, t[0], t[1], t[2]);
    if (kind == 2) lanes::torques_of_rows<2, true>(rn.data(), rd.data(), rc.data(), a.data(), 0, t[0], t[1], t[2]);
    if (kind == 3) lanes::torques_of_rows<3, true>(rn.data(), rd.data(), rc.data(), a.data(), 0, t[0], t[1], t[2]);
    for (int q = 0; q < 4; ++q)
      for (int k = 0; k < 3; ++k) {
        double want = 0.0;
        if (kind >= 2) want = -a[q] * n0[4 * q + k];
        if (kind == 3) want = want + 0.5 * d0[4 * q + k];
        if (kind >= 2) want = want + c0[4 * q + k];
        CHECK(same_bits(lane(t[k], q), want));
      }
  }
  // kicked4 and kick_drift4: the mobile ones' v += h f/m (twice: a finish's kick and the next
  // step's), x += dt v, and the displacement x - x0 (the passes take x_build from it).
  for (int group = 0; group < 64; ++group) {  // many values: a rounding differs in some lane
    for (const int kicks : {1, 2}) {
      const std::vector<double> w = mixed_values(24, 100 + group);
      std::vector<double> vel(w.begin(), w.begin() + 4), pos(w.begin() + 4, w.begin() + 8);
      const std::vector<double> v0 = vel, x0 = pos, f(w.begin() + 8, w.begin() + 12), inv(w.begin() + 12, w.begin() + 16),
                                r0(w.begin() + 16, w.begin() + 20);
      const float rb[4] = {1.5e-6f, -0.0f, 3e-9f, -2.25e-5f};
      const simd::V4 fv = simd::load4(f.data()), iv = simd::load4(inv.data());
      const simd::V4 k = kicks == 1 ? lanes::kicked4<1>(simd::load4(v0.data()), fv, m, hv, iv)
                                    : lanes::kicked4<2>(simd::load4(v0.data()), fv, m, hv, iv);
      simd::V4 v1, x1;  // the new velocity and coordinate as lanes (finish_kick_drift's rows)
      const simd::V4 u = kicks == 1 ? lanes::kick_drift4<1>(vel.data(), pos.data(), fv, r0.data(), m, hv, dtv, iv, 0, v1, x1)
                                    : lanes::kick_drift4<2>(vel.data(), pos.data(), fv, r0.data(), m, hv, dtv, iv, 0, v1, x1);
      const simd::V4 disp = u - simd::load4(rb);  // the passes' displacement since the build
      simd::V4 v1r, x1r;  // the form that reads the state as values (Dynamics::state_in_rows) and stores nothing
      const simd::V4 ur =
          kicks == 1 ? lanes::kick_drift4<1>(simd::load4(v0.data()), simd::load4(x0.data()), fv, r0.data(), m, hv, dtv, iv, 0, v1r, x1r)
                     : lanes::kick_drift4<2>(simd::load4(v0.data()), simd::load4(x0.data()), fv, r0.data(), m, hv, dtv, iv, 0, v1r, x1r);
      for (int q = 0; q < 4; ++q) {
        double vq = v0[q];
        for (int s = 0; s < kicks; ++s) vq = on[q] ? vq + h * f[q] * inv[q] : vq;
        const double xq = on[q] ? x0[q] + dt * vq : x0[q];
        CHECK(same_bits(lane(k, q), vq));
        CHECK(same_bits(vel[q], vq));
        CHECK(same_bits(pos[q], xq));
        CHECK(same_bits(lane(v1, q), vq));
        CHECK(same_bits(lane(x1, q), xq));
        CHECK(same_bits(lane(disp, q), (xq - r0[q]) - static_cast<double>(rb[q])));
        CHECK(same_bits(lane(v1r, q), vq));
        CHECK(same_bits(lane(x1r, q), xq));
        CHECK(same_bits(lane(ur, q), xq - r0[q]));
      }
    }
  }
}

#endif
