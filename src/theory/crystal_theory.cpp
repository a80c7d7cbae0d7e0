// Continuum predictions for the crystal from its contact network (theory/crystal_theory.hpp).
#include "theory/crystal_theory.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace granwave::theory {

ContactTime linear_contact_time(double k, double gamma_n, double m_ij, bool clip_tension) {
  if (!(k > 0.0) || !(m_ij > 0.0) || !(gamma_n >= 0.0))
    throw InputError("linear_contact_time: needs k > 0, m_ij > 0, gamma_n >= 0");
  ContactTime r;
  r.eta0 = gamma_n / (2.0 * m_ij);
  const double w2 = k / m_ij - r.eta0 * r.eta0;
  if (!(w2 > 0.0)) throw InputError("linear_contact_time: overdamped contact (eta_0^2 >= k/m_ij), no bounce");
  r.omega = std::sqrt(w2);
  if (!clip_tension) {
    // Sec. 2.1: half period of the damped oscillation; the contact ends at delta = 0.
    r.t_c = std::numbers::pi / r.omega;
    r.restitution = std::exp(-r.eta0 * r.t_c);
    return r;
  }
  // delta(t) = (v/omega) e^{-eta t} sin(omega t); the force k delta + gamma delta_dot = -m_ij delta''
  // first vanishes at tan(omega t) = 2 eta omega / (eta^2 - omega^2), in (pi/2, pi].
  const double phase = std::numbers::pi - std::atan2(2.0 * r.eta0 * r.omega, w2 - r.eta0 * r.eta0);
  r.t_c = phase / r.omega;
  const double vrel = std::exp(-r.eta0 * r.t_c) * (std::cos(phase) - (r.eta0 / r.omega) * std::sin(phase));
  r.restitution = std::abs(vrel);
  return r;
}

double lattice_omega(double omega0, double k, double l0) { return omega0 * std::sin(0.5 * k * l0); }

namespace {

// e . K_c . e for K_c = k n n + kt (I - n n) - (f0/l)(I - n n).
double directional_stiffness(const Vec3& e, const Vec3& n, double k, double kt, double f0_over_l) {
  const double en = e.dot(n);
  const double tang = e.squaredNorm() - en * en;
  return k * en * en + (kt - f0_over_l) * tang;
}

}  // namespace

CrystalPrediction crystal_prediction(const ContactNetwork& net, SlabSelection slab) {
  const int np = static_cast<int>(net.particles.size());
  if (np == 0) throw InputError("crystal theory: the network has no particles");
  if (!(net.box_x > 0.0 && net.box_y > 0.0)) throw InputError("crystal theory: box_x and box_y must be > 0");
  int lmin = net.particles[0].layer, lmax = lmin;
  for (const auto& p : net.particles) {
    lmin = std::min(lmin, p.layer);
    lmax = std::max(lmax, p.layer);
  }
  CrystalPrediction r;
  r.layer_lo = slab.layer_lo >= 0 ? slab.layer_lo : lmin + 1;
  r.layer_hi = slab.layer_hi >= 0 ? slab.layer_hi : lmax - 1;
  if (r.layer_hi - r.layer_lo < 1)
    throw InputError("crystal theory: the representative slab needs at least two layers (got " +
                     std::to_string(r.layer_lo) + ".." + std::to_string(r.layer_hi) + ")");
  auto inside = [&](int p) {
    const int l = net.particles[p].layer;
    return l >= r.layer_lo && l <= r.layer_hi;
  };

  // Slab: mass, and the thickness from the mean heights of its end layers.
  double z_lo = 0.0, z_hi = 0.0;
  int n_lo = 0, n_hi = 0;
  for (int p = 0; p < np; ++p) {
    if (!inside(p)) continue;
    const auto& q = net.particles[p];
    r.mass += q.mass;
    ++r.n_particles;
    if (q.layer == r.layer_lo) z_lo += q.z, ++n_lo;
    if (q.layer == r.layer_hi) z_hi += q.z, ++n_hi;
  }
  if (n_lo == 0 || n_hi == 0) throw InputError("crystal theory: an end layer of the slab is empty");
  const int n_layers = r.layer_hi - r.layer_lo + 1;
  r.l0 = (z_hi / n_hi - z_lo / n_lo) / (n_layers - 1);
  if (!(r.l0 > 0.0)) throw InputError("crystal theory: layers are not stacked upwards in z");
  r.volume = net.box_x * net.box_y * r.l0 * n_layers;
  r.rho_bulk = r.mass / r.volume;

  // Eq. (10) over the contact ends in the slab, and the nearest-layer dynamical matrix.
  std::vector<ContactGeometry> geo;
  geo.reserve(net.contacts.size());
  const Vec3 ez(0, 0, 1), ex(1, 0, 0);
  double kp = 0.0, ks = 0.0, kp_pre = 0.0, ks_pre = 0.0;  // sum over interlayer contact ends of e.K.e
  int ends = 0;
  for (const auto& c : net.contacts) {
    if (c.i < 0 || c.j < 0 || c.i >= np || c.j >= np) throw InputError("crystal theory: contact index out of range");
    const int w = (inside(c.i) ? 1 : 0) + (inside(c.j) ? 1 : 0);
    if (w == 0) continue;
    ends += w;
    const double kc = c.k_of(net.k), ktc = c.kt_of(net.kt);
    geo.push_back({c.branch, kc, ktc, 0.5 * w});
    if (net.particles[c.i].layer != net.particles[c.j].layer) {
      const double l = c.branch.norm();
      const Vec3 n = c.branch / l;
      kp += w * directional_stiffness(ez, n, kc, ktc, 0.0);
      ks += w * directional_stiffness(ex, n, kc, ktc, 0.0);
      kp_pre += w * directional_stiffness(ez, n, kc, ktc, c.normal_force / l);
      ks_pre += w * directional_stiffness(ex, n, kc, ktc, c.normal_force / l);
    }
  }
  r.coordination = static_cast<double>(ends) / r.n_particles;
  r.C = stiffness_tensor(geo, r.volume, true);
  r.C_frictionless = stiffness_tensor(geo, r.volume, false);
  r.C_voigt_sym = r.C.symmetrised().voigt();
  r.major_asymmetry = r.C.major_asymmetry();
  r.minor_asymmetry = r.C.minor_asymmetry();

  // Plane waves along z (sec. 3.3): V^2 = Gamma/rho with Gamma_bf = C_zbzf.
  constexpr int X = 0, Y = 1, Z = 2;
  r.V_pz = std::sqrt(r.C(Z, Z, Z, Z) / r.rho_bulk);
  r.V_sz = std::sqrt(r.C(Z, X, Z, X) / r.rho_bulk);
  r.V_sy = std::sqrt(r.C(Z, Y, Z, Y) / r.rho_bulk);
  r.V_pz_frictionless = std::sqrt(r.C_frictionless(Z, Z, Z, Z) / r.rho_bulk);
  r.V_sz_frictionless = std::sqrt(r.C_frictionless(Z, X, Z, X) / r.rho_bulk);
  r.ratio_xxxx_zzzz = r.C(X, X, X, X) / r.C(Z, Z, Z, Z);
  r.ratio_zxzx_yxyx = r.C(Z, X, Z, X) / r.C(Y, X, Y, X);
  r.ratio_zzzz_zxzx = r.C(Z, Z, Z, Z) / r.C(Z, X, Z, X);

  // Sec. 3.4: a layer moving as a whole, u_n ~ exp(i(k n l0 - omega t)), gives
  // m omega^2 = sum_c e.K_c.e (1 - cos k l0) = 2 sin^2(k l0/2) sum_c e.K_c.e.
  r.omega0_p = std::sqrt(2.0 * kp / r.mass);
  r.omega0_s = std::sqrt(2.0 * ks / r.mass);
  r.omega0_p_prestressed = std::sqrt(2.0 * kp_pre / r.mass);
  r.omega0_s_prestressed = std::sqrt(2.0 * ks_pre / r.mass);
  r.V_k0_p = 0.5 * r.omega0_p * r.l0;
  r.V_k0_s = 0.5 * r.omega0_s * r.l0;
  return r;
}

ContactNetwork fcc_network(int nx, int ny, int layers, double l, double mass, double k, double kt, double f0) {
  if (nx < 2 || ny < 2 || layers < 2) throw InputError("fcc_network: needs nx, ny >= 2 and >= 2 layers");
  ContactNetwork net;
  net.box_x = nx * l;
  net.box_y = ny * l;
  net.k = k;
  net.kt = kt;
  const double l0 = l / std::sqrt(2.0);
  const double a = 0.5 * (l + (k > 0.0 ? f0 / k : 0.0));
  auto id = [&](int i, int j, int n) { return (n * ny + ((j % ny + ny) % ny)) * nx + ((i % nx + nx) % nx); };
  for (int n = 0; n < layers; ++n)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) net.particles.push_back({mass, n, n * l0, a, 0.4 * mass * a * a});
  // Branch vectors from the lattice offsets (not a minimum image, which is ambiguous for nx = 2).
  for (int n = 0; n < layers; ++n)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int p = id(i, j, n);
        net.contacts.push_back({p, id(i + 1, j, n), Vec3(l, 0, 0), f0});
        net.contacts.push_back({p, id(i, j + 1, n), Vec3(0, l, 0), f0});
        if (n + 1 == layers) continue;
        // Odd layers sit over the holes of even ones, shifted by (l/2, l/2).
        const int s = (n % 2 == 0) ? -1 : 0;  // index offset of the lower-left neighbour above
        for (int di = 0; di < 2; ++di)
          for (int dj = 0; dj < 2; ++dj) {
            const double bx = (di == 0 ? -0.5 : 0.5) * l, by = (dj == 0 ? -0.5 : 0.5) * l;
            net.contacts.push_back({p, id(i + s + di, j + s + dj, n + 1), Vec3(bx, by, l0), f0});
          }
      }
  return net;
}

}  // namespace granwave::theory
