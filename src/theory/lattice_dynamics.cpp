// Lattice dynamics of a Bravais packing with translations and rotations (theory/lattice_dynamics.hpp).
#include "theory/lattice_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "core/error.hpp"
#include "core/numbers.hpp"

namespace granwave::theory {
namespace {

using cd = std::complex<double>;

void check_cell(const LatticeCell& cell) {
  if (!(cell.mass > 0.0) || !(cell.inertia > 0.0))
    throw InputError("lattice dynamics: the particle needs mass > 0 and inertia > 0");
  if (cell.bonds.empty()) throw InputError("lattice dynamics: the particle has no contacts");
  for (const auto& b : cell.bonds)
    if (!(b.branch.norm() > 0.0) || !std::isfinite(b.kn) || !std::isfinite(b.kt) || !std::isfinite(b.f0) ||
        !std::isfinite(b.arm) || !std::isfinite(b.k_roll) || !std::isfinite(b.k_twist))
      throw InputError("lattice dynamics: a contact has a zero branch vector or a non-finite constant");
}

// The 3x3 blocks of one bond, each to be multiplied by its Bloch factor.
struct BondBlocks {
  Eigen::Matrix3d K, N, P;  // K = kn n n + (kt - f0/l) P, N = [n]_x, P = I - n n
  Eigen::Matrix3d Q;        // k_roll P + k_twist n n: the angular springs on the relative turn
  double kt_arm = 0.0, kt_arm2 = 0.0;
};
BondBlocks blocks(const LatticeBond& b) {
  BondBlocks r;
  const double l = b.branch.norm();
  const Vec3 n = -b.branch / l;  // seed 002: n = (r_i - r_j)/|r_i - r_j|, i = this particle
  r.P = Eigen::Matrix3d::Identity() - n * n.transpose();
  r.K = b.kn * n * n.transpose() + (b.kt - b.f0 / l) * r.P;
  r.N = cross_matrix(n);
  r.Q = b.k_roll * r.P + b.k_twist * n * n.transpose();
  r.kt_arm = b.kt * b.arm;
  r.kt_arm2 = b.kt * b.arm * b.arm;
  return r;
}

Eigen::Matrix<double, 6, 1> inverse_sqrt_mass(const LatticeCell& cell) {
  Eigen::Matrix<double, 6, 1> s;
  const double a = 1.0 / std::sqrt(cell.mass), b = 1.0 / std::sqrt(cell.inertia);
  s << a, a, a, b, b, b;
  return s;
}

Matrix6cd mass_weighted(const LatticeCell& cell, const Matrix6cd& Phi) {
  const auto s = inverse_sqrt_mass(cell);
  Matrix6cd D;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) D(r, c) = Phi(r, c) * (s[r] * s[c]);
  return D;
}

// Eigenvectors `V` (columns) of a degenerate eigenspace, rotated to diagonalise diag(w) inside it
// and ordered by its expectation value; `tie` groups columns with equal expectation.
void diagonalise_in(Eigen::Ref<Eigen::MatrixXcd> V, const std::array<double, 6>& w, std::vector<double>* expectation) {
  const Eigen::Index g = V.cols();
  Eigen::MatrixXcd Q(g, g);
  for (Eigen::Index a = 0; a < g; ++a)
    for (Eigen::Index b = 0; b < g; ++b) {
      cd s = 0.0;
      for (int i = 0; i < 6; ++i) s += std::conj(V(i, a)) * w[i] * V(i, b);
      Q(a, b) = s;
    }
  Q = 0.5 * (Q + Q.adjoint()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> es(Q);
  const Eigen::MatrixXcd U = es.eigenvectors();
  V = (V * U).eval();
  expectation->assign(es.eigenvalues().data(), es.eigenvalues().data() + g);
}

// Family of a wave along z: (u_x, theta_y), (u_y, theta_x), (u_z, theta_z); then translation/rotation.
constexpr std::array<double, 6> kFamilyWeight = {1, 2, 3, 2, 1, 3};
constexpr std::array<double, 6> kKindWeight = {1, 1, 1, 2, 2, 2};

void refine_degenerate(Eigen::Ref<Eigen::MatrixXcd> V) {
  std::vector<double> ex;
  diagonalise_in(V, kFamilyWeight, &ex);
  for (Eigen::Index a = 0; a < V.cols();) {
    Eigen::Index b = a + 1;
    while (b < V.cols() && std::abs(ex[b] - ex[a]) <= 1e-6) ++b;
    if (b - a > 1) {
      std::vector<double> ex2;
      diagonalise_in(V.middleCols(a, b - a), kKindWeight, &ex2);
    }
    a = b;
  }
}

}  // namespace

int LatticeMode::dominant() const {
  return static_cast<int>(std::max_element(content.begin(), content.end()) - content.begin());
}

Matrix6cd force_constants(const LatticeCell& cell, const Vec3& k) {
  check_cell(cell);
  Matrix6cd Phi = Matrix6cd::Zero();
  for (const auto& bond : cell.bonds) {
    const BondBlocks B = blocks(bond);
    const cd ph = std::polar(1.0, k.dot(bond.branch));  // Bloch factor of the neighbour
    Phi.block<3, 3>(0, 0) += B.K.cast<cd>() * (1.0 - ph);
    Phi.block<3, 3>(0, 3) += B.N.cast<cd>() * (B.kt_arm * (1.0 + ph));
    Phi.block<3, 3>(3, 0) += B.N.cast<cd>() * (-B.kt_arm * (1.0 - ph));
    Phi.block<3, 3>(3, 3) += B.P.cast<cd>() * (B.kt_arm2 * (1.0 + ph)) + B.Q.cast<cd>() * (1.0 - ph);
  }
  return Phi;
}

Matrix6cd dynamical_matrix(const LatticeCell& cell, const Vec3& k) { return mass_weighted(cell, force_constants(cell, k)); }

Matrix6cd dynamical_matrix_derivative(const LatticeCell& cell, const Vec3& k, const Vec3& h) {
  check_cell(cell);
  Matrix6cd dPhi = Matrix6cd::Zero();
  for (const auto& bond : cell.bonds) {
    const BondBlocks B = blocks(bond);
    const cd dph = cd(0.0, h.dot(bond.branch)) * std::polar(1.0, k.dot(bond.branch));
    dPhi.block<3, 3>(0, 0) += B.K.cast<cd>() * (-dph);
    dPhi.block<3, 3>(0, 3) += B.N.cast<cd>() * (B.kt_arm * dph);
    dPhi.block<3, 3>(3, 0) += B.N.cast<cd>() * (B.kt_arm * dph);
    dPhi.block<3, 3>(3, 3) += B.P.cast<cd>() * (B.kt_arm2 * dph) - B.Q.cast<cd>() * dph;
  }
  return mass_weighted(cell, dPhi);
}

double hermitian_defect(const Matrix6cd& D) {
  const double scale = D.cwiseAbs().maxCoeff();
  if (scale == 0.0) return 0.0;
  return (D - D.adjoint()).cwiseAbs().maxCoeff() / scale;
}

std::array<LatticeMode, 6> lattice_modes(const LatticeCell& cell, const Vec3& h, double s) {
  const Matrix6cd D = dynamical_matrix(cell, s * h);
  const Matrix6cd H = 0.5 * (D + D.adjoint());
  Eigen::SelfAdjointEigenSolver<Matrix6cd> es(H);
  if (es.info() != Eigen::Success) throw RunError("lattice dynamics: the eigensolver failed");
  const Eigen::Matrix<double, 6, 1> w2 = es.eigenvalues();
  Eigen::MatrixXcd V = es.eigenvectors();
  // Degenerate eigenspaces: equal to a relative 1e-9 of the largest eigenvalue.
  const double tol = 1e-9 * w2.cwiseAbs().maxCoeff();
  for (int a = 0; a < 6;) {
    int b = a + 1;
    while (b < 6 && w2[b] - w2[b - 1] <= tol) ++b;
    if (b - a > 1) refine_degenerate(V.middleCols(a, b - a));
    a = b;
  }
  const Matrix6cd dD = dynamical_matrix_derivative(cell, s * h, h);
  std::array<LatticeMode, 6> modes;
  for (int m = 0; m < 6; ++m) {
    LatticeMode& md = modes[m];
    Vector6cd e = V.col(m);
    e /= e.norm();
    // A definite phase: the largest component real and positive.
    Eigen::Index imax = 0;
    e.cwiseAbs().maxCoeff(&imax);
    e *= std::conj(e[imax]) / std::abs(e[imax]);
    md.e = e;
    md.omega2 = w2[m];
    md.omega = md.omega2 >= 0.0 ? std::sqrt(md.omega2) : -std::sqrt(-md.omega2);
    for (int i = 0; i < 6; ++i) md.content[i] = std::norm(e[i]);
    // Hellmann-Feynman: d(omega^2)/ds = e^H D' e (the basis above is the one that diagonalises D'
    // inside degenerate spaces of a wave along z).
    const double dw2 = (e.adjoint() * dD * e)(0, 0).real();
    // Undefined where omega = 0 (eigenvalue round-off ~1e-16 of the largest).
    md.group_velocity = std::abs(md.omega2) > 1e-13 * w2.cwiseAbs().maxCoeff() ? dw2 / (2.0 * md.omega) : kNaN;
  }
  return modes;
}

LatticeLongWave lattice_long_wave(const LatticeCell& cell, const Vec3& h_in) {
  check_cell(cell);
  const Vec3 h = h_in.normalized();
  Eigen::Matrix3d S = Eigen::Matrix3d::Zero(), G = Eigen::Matrix3d::Zero(), R = Eigen::Matrix3d::Zero();
  for (const auto& bond : cell.bonds) {
    const BondBlocks B = blocks(bond);
    const double bh = bond.branch.dot(h);
    S += 0.5 * bh * bh * B.K;
    G += B.kt_arm * bh * B.N;
    R += 2.0 * B.kt_arm2 * B.P;
  }
  // R^+ (R = 0 without tangential springs: the rotations are then free and decoupled).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> rs(0.5 * (R + R.transpose()));
  const double rmax = rs.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::Matrix3d Rplus = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) {
    const double lam = rs.eigenvalues()[i];
    if (lam > 1e-12 * rmax && rmax > 0.0) Rplus += rs.eigenvectors().col(i) * rs.eigenvectors().col(i).transpose() / lam;
  }
  LatticeLongWave r;
  r.direction = h;
  r.affine = S / cell.mass;
  r.with_rotations = (S + G * Rplus * G) / cell.mass;
  r.with_rotations = 0.5 * (r.with_rotations + r.with_rotations.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> as(r.with_rotations);
  for (int i = 0; i < 3; ++i) {
    const double v2 = as.eigenvalues()[i];
    r.speed[i] = v2 >= 0.0 ? std::sqrt(v2) : -std::sqrt(-v2);
    r.polarisation[i] = as.eigenvectors().col(i);
    r.omega_rotation_k0[i] = std::sqrt(std::max(0.0, rs.eigenvalues()[i]) / cell.inertia);
  }
  return r;
}

double LatticeLongWave::speed_along(const Vec3& e, bool rotations) const {
  const Vec3 u = e.normalized();
  const double v2 = u.dot((rotations ? with_rotations : affine) * u);
  return v2 >= 0.0 ? std::sqrt(v2) : -std::sqrt(-v2);
}

double layer_period(const LatticeCell& cell, const Vec3& h_in) {
  const Vec3 h = h_in.normalized();
  double bmax = 0.0;
  for (const auto& b : cell.bonds) bmax = std::max(bmax, b.branch.norm());
  double p = 0.0;
  for (const auto& b : cell.bonds) {
    const double x = std::abs(b.branch.dot(h));
    if (x > 1e-9 * bmax && (p == 0.0 || x < p)) p = x;
  }
  return p;
}

LatticeDispersion lattice_dispersion(const LatticeCell& cell, const Vec3& h_in, double period, int nk) {
  if (nk < 3 || nk % 2 == 0) throw InputError("lattice dispersion: the k grid needs an odd number of points >= 3");
  if (!(period > 0.0)) throw InputError("lattice dispersion: the period (layer spacing) must be > 0");
  const Vec3 h = h_in.normalized();
  LatticeDispersion d;
  d.direction = h;
  d.period = period;
  const int mid = (nk - 1) / 2;
  d.k.resize(nk);
  for (int i = 0; i < nk; ++i) d.k[i] = std::numbers::pi / period * static_cast<double>(i - mid) / mid;
  for (auto& b : d.branches) b.resize(nk);

  std::vector<std::array<LatticeMode, 6>> at(nk);
  for (int i = 0; i < nk; ++i) {
    at[i] = lattice_modes(cell, h, d.k[i]);
    d.max_hermitian_defect = std::max(d.max_hermitian_defect, hermitian_defect(dynamical_matrix(cell, d.k[i] * h)));
  }
  // Follow branches outwards from k = 0 by the largest total overlap |<e_prev|e_new>|^2, on a grid
  // 16 times finer than the output (eigenvectors turn fast near an avoided crossing).
  constexpr int kSub = 16;
  auto match = [](const std::array<Vector6cd, 6>& prev, const std::array<LatticeMode, 6>& next) {
    std::array<int, 6> perm, best;
    std::iota(perm.begin(), perm.end(), 0);
    best = perm;
    double O[6][6];
    for (int b = 0; b < 6; ++b)
      for (int m = 0; m < 6; ++m) O[b][m] = std::norm(prev[b].dot(next[m].e));
    double best_sum = -1.0;
    do {
      double s = 0.0;
      for (int b = 0; b < 6; ++b) s += O[b][perm[b]];
      if (s > best_sum + 1e-12) best_sum = s, best = perm;
    } while (std::next_permutation(perm.begin(), perm.end()));
    return best;
  };
  for (int b = 0; b < 6; ++b) d.branches[b][mid] = at[mid][b];
  auto follow = [&](int from, int to) {
    std::array<Vector6cd, 6> e;
    for (int b = 0; b < 6; ++b) e[b] = d.branches[b][from].e;
    for (int j = 1; j < kSub; ++j) {
      const double kj = d.k[from] + (d.k[to] - d.k[from]) * j / kSub;
      const auto sub = lattice_modes(cell, h, kj);
      const auto p = match(e, sub);
      for (int b = 0; b < 6; ++b) e[b] = sub[p[b]].e;
    }
    const auto p = match(e, at[to]);
    for (int b = 0; b < 6; ++b) d.branches[b][to] = at[to][p[b]];
  };
  for (int i = mid + 1; i < nk; ++i) follow(i - 1, i);
  for (int i = mid - 1; i >= 0; --i) follow(i + 1, i);

  const LatticeLongWave lw = lattice_long_wave(cell, h);
  double scale = 0.0;
  for (const auto& m : at[nk - 1]) scale = std::max(scale, std::abs(m.omega2));
  for (const auto& m : at[mid + 1]) scale = std::max(scale, std::abs(m.omega2));
  const double zero = 1e-9 * scale;
  d.min_omega2 = std::numeric_limits<double>::infinity();
  for (int b = 0; b < 6; ++b) {
    auto& br = d.branches[b];
    d.dominant[b] = br[mid + 1].dominant();
    d.acoustic[b] = std::abs(br[mid].omega2) <= zero && br[mid].translation() > 0.5;
    bool flat_zero = true;
    for (const auto& m : br) {
      d.min_omega2 = std::min(d.min_omega2, m.omega2);
      flat_zero = flat_zero && std::abs(m.omega2) <= zero;
    }
    d.zero[b] = flat_zero && !d.acoustic[b];
    d.rotational_acoustic[b] = !flat_zero && !d.acoustic[b] && std::abs(br[mid].omega2) <= zero;
    if (flat_zero) {
      for (auto& m : br) m.group_velocity = 0.0;  // free rotations (no tangential spring)
    } else if (d.acoustic[b]) {
      // k = 0: the long-wave speed of the mode's translation.
      Vec3 u(std::abs(br[mid].e[0]), std::abs(br[mid].e[1]), std::abs(br[mid].e[2]));
      br[mid].group_velocity = lw.speed_along(u, true);
    }
  }
  return d;
}

RidgeComparison compare_ridge(const std::vector<double>& spectrum, const std::vector<double>& k_axis,
                              const std::vector<double>& omega_axis, const LatticeDispersion& d, int branch,
                              int k_sign, double vg_fraction) {
  const std::size_t nw = omega_axis.size(), nkc = k_axis.size();
  if (nw < 3 || nkc < 1 || spectrum.size() != nw * nkc) throw InputError("compare_ridge: spectrum size differs from its axes");
  if (branch < 0 || branch >= 6 || d.k.size() < 3) throw InputError("compare_ridge: no such branch");
  const auto& br = d.branches[branch];
  // The branch on k >= 0 (omega and v_g are even and odd in k).
  std::vector<double> kb, wb, vb;
  double wlo = std::numeric_limits<double>::infinity(), whi = -wlo, vmax = 0.0;
  for (std::size_t i = 0; i < d.k.size(); ++i) {
    wlo = std::min(wlo, br[i].omega), whi = std::max(whi, br[i].omega);
    if (d.k[i] < 0.0) continue;
    kb.push_back(d.k[i]);
    wb.push_back(br[i].omega);
    vb.push_back(std::abs(br[i].group_velocity));
    if (std::isfinite(vb.back())) vmax = std::max(vmax, vb.back());
  }
  auto interp = [&](const std::vector<double>& y, double x) {
    if (x <= kb.front()) return y.front();
    if (x >= kb.back()) return y.back();
    const auto it = std::upper_bound(kb.begin(), kb.end(), x);
    const std::size_t j = static_cast<std::size_t>(it - kb.begin());
    const double t = (x - kb[j - 1]) / (kb[j] - kb[j - 1]);
    return y[j - 1] + t * (y[j] - y[j - 1]);
  };
  RidgeComparison r;
  r.domega = omega_axis[1] - omega_axis[0];
  std::vector<double> offsets;
  for (std::size_t c = 0; c < nkc; ++c) {
    const double kc = k_axis[c];
    if (kc == 0.0 || (kc > 0.0) != (k_sign > 0)) continue;
    const double ak = std::abs(kc);
    if (ak > kb.back() * (1 + 1e-12)) continue;
    const double vg = interp(vb, ak);
    if (!(vg >= vg_fraction * vmax)) continue;
    ++r.columns;
    double best = -1.0;
    std::size_t jbest = 0;
    for (std::size_t j = 1; j + 1 < nw; ++j) {
      if (!(omega_axis[j] > wlo && omega_axis[j] < whi)) continue;
      const double a = spectrum[j * nkc + c];
      if (a > spectrum[(j - 1) * nkc + c] && a >= spectrum[(j + 1) * nkc + c] && a > best) best = a, jbest = j;
    }
    if (best < 0.0) continue;
    ++r.with_ridge;
    const double wbr = interp(wb, ak);
    const double off = (omega_axis[jbest] - wbr) / r.domega;
    if (std::abs(off) <= 1.0) ++r.within_one_bin;
    r.max_offset_bins = std::max(r.max_offset_bins, std::abs(off));
    offsets.push_back(std::abs(off));
    r.k.push_back(kc);
    r.omega_ridge.push_back(omega_axis[jbest]);
    r.omega_branch.push_back(wbr);
  }
  if (!offsets.empty()) {
    std::sort(offsets.begin(), offsets.end());
    const std::size_t n = offsets.size();
    r.median_offset_bins = n % 2 ? offsets[n / 2] : 0.5 * (offsets[n / 2 - 1] + offsets[n / 2]);
  }
  return r;
}

std::optional<LatticeCell> lattice_cell(const ContactNetwork& net, SlabSelection slab, const LatticeCellOptions& opt,
                                        std::string* why_not) {
  auto fail = [&](const std::string& why) -> std::optional<LatticeCell> {
    if (why_not) *why_not = why;
    return std::nullopt;
  };
  const int np = static_cast<int>(net.particles.size());
  if (np == 0) return fail("the network has no particles");
  int lmin = net.particles[0].layer, lmax = lmin;
  for (const auto& p : net.particles) lmin = std::min(lmin, p.layer), lmax = std::max(lmax, p.layer);
  const int lo = slab.layer_lo >= 0 ? slab.layer_lo : lmin + 1;
  const int hi = slab.layer_hi >= 0 ? slab.layer_hi : lmax - 1;
  if (hi < lo) return fail("the slab is empty");
  auto inside = [&](int p) { return net.particles[p].layer >= lo && net.particles[p].layer <= hi; };
  for (int p = 0; p < np; ++p)
    if (inside(p) && !(net.particles[p].radius > 0.0 && net.particles[p].inertia > 0.0))
      return fail("the network carries no radius or moment of inertia for particle " + std::to_string(p));

  // Bonds of every particle in the slab, branch from the particle to its neighbour.
  std::vector<std::vector<LatticeBond>> bonds(np);
  for (const auto& c : net.contacts) {
    if (c.i < 0 || c.j < 0 || c.i >= np || c.j >= np) throw InputError("lattice dynamics: contact index out of range");
    const double l = c.branch.norm();
    const double delta = net.particles[c.i].radius + net.particles[c.j].radius - l;
    const double arm_i = net.particles[c.i].radius - opt.arm_shift * delta;
    const double arm_j = net.particles[c.j].radius - opt.arm_shift * delta;
    const double shift_r = opt.rolling_arm_shift;  // a' of the rolling and torsion springs
    const double roll_i = net.particles[c.i].radius - shift_r * delta, roll_j = net.particles[c.j].radius - shift_r * delta;
    const double lever = roll_i * roll_j / (roll_i + roll_j);
    const double k_roll = opt.k_roll + opt.kr * lever * lever, k_twist = opt.k_twist + opt.ko * lever * lever;
    if (inside(c.i))
      bonds[c.i].push_back({c.branch, c.k_of(net.k), c.kt_of(net.kt), c.normal_force, arm_i, k_roll, k_twist});
    if (inside(c.j))
      bonds[c.j].push_back({-c.branch, c.k_of(net.k), c.kt_of(net.kt), c.normal_force, arm_j, k_roll, k_twist});
  }
  // Reference: the first particle of the middle layer.
  const int mid_layer = (lo + hi) / 2;
  int ref = -1;
  for (int p = 0; p < np && ref < 0; ++p)
    if (net.particles[p].layer == mid_layer) ref = p;
  if (ref < 0) return fail("the middle layer of the slab is empty");
  const auto& R = bonds[ref];
  const auto& pr = net.particles[ref];
  auto close = [&](double a, double b) { return std::abs(a - b) <= opt.tolerance * std::max(std::abs(a), std::abs(b)); };
  for (int p = 0; p < np; ++p) {
    if (!inside(p)) continue;
    const auto& q = net.particles[p];
    if (!close(q.mass, pr.mass) || !close(q.radius, pr.radius) || !close(q.inertia, pr.inertia))
      return fail("particle " + std::to_string(p) + " differs in mass, radius or inertia from particle " +
                  std::to_string(ref) + " (not a Bravais lattice: polydisperse?)");
    if (bonds[p].size() != R.size())
      return fail("particle " + std::to_string(p) + " has " + std::to_string(bonds[p].size()) + " contacts, particle " +
                  std::to_string(ref) + " " + std::to_string(R.size()));
    for (const auto& b : bonds[p]) {
      bool found = false;
      for (const auto& r : R)
        if ((b.branch - r.branch).norm() <= opt.tolerance * r.branch.norm() && close(b.f0, r.f0) && close(b.arm, r.arm)) {
          found = true;
          break;
        }
      if (!found)
        return fail("particle " + std::to_string(p) + " has a contact that particle " + std::to_string(ref) +
                    " lacks (branch, force or lever arm differ by more than " + std::to_string(opt.tolerance) +
                    " relative: not a Bravais lattice)");
    }
  }
  LatticeCell cell;
  cell.mass = pr.mass;
  cell.inertia = pr.inertia;
  cell.bonds = R;
  return cell;
}

}  // namespace granwave::theory
