// The frame-free contact pass of bench/bench_frame.cpp, included there once for each vector width (inside
// a namespace and a `#pragma GCC target`; no includes of its own). Direction q's contacts are the
// stream i = 0 .. n-1 with j = i + off[q]: their columns (overlap, history, f, n x f^t, the couple) at
// q n + i; then the sums per particle, each a contiguous stream (j's first, then i's own).

// Not inlined: a function keeps its width only where the vectoriser sees it with its own options.
template <class Law>
[[gnu::noinline]] void frame_free_pass(const Law& law, Streams& s, double inc) {
  constexpr std::size_t NH = granwave::contact::history_columns<typename Law::History>;
  constexpr bool couples = granwave::contact::HasCouples<Law>;
  const std::int64_t n = s.n, m = 6 * n, np = n + Streams::kPad;
  const bool third_row = law.lever_arm() == granwave::contact::LeverArm::contact_point;  // delta n x f^t
  const double *x = s.x.data(), *y = s.y.data(), *z = s.z.data(), *a = s.a.data();
  const double *vx = s.vx.data(), *vy = s.vy.data(), *vz = s.vz.data();
  const double *wx = s.wx.data(), *wy = s.wy.data(), *wz = s.wz.data();
  double* out = s.out.data();
  for (int q = 0; q < 6; ++q) {
    const std::int64_t o = Streams::off[q], base = q * n;
    std::array<double*, NH> hist{};
    for (std::size_t h = 0; h < NH; ++h) hist[h] = s.history.data() + h * m + base;
    double* diss = s.dissipated.data() + base;
    double* cdelta = s.delta.data() + base;
    double* fo = out + base;
#pragma GCC ivdep
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t j = i + o;
      const double bx = x[j] - x[i], by = y[j] - y[i], bz = z[j] - z[i];
      const double r = std::sqrt(bx * bx + by * by + bz * bz);
      const granwave::contact::Vec3 dv(vx[i] - vx[j], vy[i] - vy[j], vz[i] - vz[j]);
      const granwave::contact::Vec3 w_i(wx[i], wy[i], wz[i]), w_j(wx[j], wy[j], wz[j]);
      granwave::contact::Response res;
      bool open;
      granwave::crystal::kernel::evaluate_contact<Law, true, false, false>(
          law, hist, diss, cdelta, i, bx, by, bz, r, 1.0 / r, a[i] + a[j], a[i], a[j],
          granwave::contact::reduced_radius(a[i], a[j]), dv, w_i, w_j, inc, res, open);
      using granwave::contact::select;
      fo[i] = select(open, 0.0, res.force.x());
      fo[m + i] = select(open, 0.0, res.force.y());
      fo[2 * m + i] = select(open, 0.0, res.force.z());
      if constexpr (Law::torques) {
        fo[3 * m + i] = select(open, 0.0, res.nf.x());
        fo[4 * m + i] = select(open, 0.0, res.nf.y());
        fo[5 * m + i] = select(open, 0.0, res.nf.z());
      }
      if constexpr (couples) {
        fo[6 * m + i] = select(open, 0.0, res.couple.x());
        fo[7 * m + i] = select(open, 0.0, res.couple.y());
        fo[8 * m + i] = select(open, 0.0, res.couple.z());
      }
    }
  }
  // The sums: f (j: minus), n x f^t (both ends plus), delta n x f^t for the contact-point arm, the couple (j: minus).
  const int kinds = Law::torques ? (third_row ? 9 : 6) + (couples ? 3 : 0) : 3;
  std::fill(s.sums.begin(), s.sums.begin() + kinds * np, 0.0);
  auto add = [&](int k, bool as_j) {
    const int column = third_row && k >= 6 ? k - 3 : k;  // the delta rows read n x f^t, the couples follow
    const bool weighted = third_row && k >= 6 && k < 9;
    const bool minus = as_j && (k < 3 || (couples && k >= kinds - 3));
    for (int q = 0; q < 6; ++q) {
      double* __restrict sum = s.sums.data() + k * np + (as_j ? Streams::off[q] : 0);
      const double* __restrict f = out + column * m + q * n;
      const double* __restrict d = s.delta.data() + q * n;
      if (weighted)
        for (std::int64_t i = 0; i < n; ++i) sum[i] += d[i] * f[i];
      else if (minus)
        for (std::int64_t i = 0; i < n; ++i) sum[i] -= f[i];
      else
        for (std::int64_t i = 0; i < n; ++i) sum[i] += f[i];
    }
  };
  for (int k = 0; k < kinds; ++k) add(k, true), add(k, false);
}
