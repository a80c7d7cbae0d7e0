// The relaxed stiffness tensor of a contact network: assembly of H, Xi, A_affine and the sparse
// solve with the zero modes projected out (relaxed_moduli.hpp).
#include "theory/relaxed_moduli.hpp"

#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "core/numbers.hpp"

namespace granwave::theory {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Mat9 = Eigen::Matrix<double, 9, 9>;

// Repulsive forces along these normals can balance (and hold the particle in every direction)
// unless the normals lie in a closed hemisphere {v.n >= 0}; an extreme ray of that set of v is
// perpendicular to two of the normals, so the candidates +-(n_a x n_b) decide it.
bool forces_can_balance(const std::vector<Vec3>& ns) {
  if (ns.size() < 4) return false;
  bool independent = false;
  for (std::size_t a = 0; a < ns.size(); ++a)
    for (std::size_t b = a + 1; b < ns.size(); ++b) {
      Vec3 c = ns[a].cross(ns[b]);
      if (c.norm() < 1e-9) continue;
      independent = true;
      c.normalize();
      for (double s : {1.0, -1.0}) {
        bool hemisphere = true;
        for (const auto& n : ns)
          if (s * c.dot(n) < -1e-12) {
            hemisphere = false;
            break;
          }
        if (hemisphere) return false;
      }
    }
  return independent;
}

Tensor4 to_tensor(const Mat9& M) {
  Tensor4 t;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int g = 0; g < 3; ++g)
        for (int f = 0; f < 3; ++f) t(a, b, g, f) = M(3 * a + b, 3 * g + f);
  return t;
}

int count_negative(const Eigen::VectorXd& D) {
  int n = 0;
  for (Eigen::Index i = 0; i < D.size(); ++i) n += D[i] < 0.0 ? 1 : 0;
  return n;
}

struct Solved {
  Mat9 relaxation = Mat9::Zero();  // Xi^T H^+ Xi
  int zero_modes = 0, unstable = 0;
  double forcing = 0.0, residual = 0.0;
};

// Xi^T H^+ Xi with H's zero modes found by Sylvester's inertia and projected out. `known` are
// exact zero modes (orthonormal columns) used when they are all there is.
// `xi_scale` (N) measures a forcing: the zero modes' share of Xi is reported relative to it.
Solved relax(const SpMat& H, const Eigen::MatrixXd& Xi, const Eigen::MatrixXd& known, double xi_scale,
             const RelaxedOptions& opt) {
  Solved s;
  const Eigen::Index n = H.rows();
  if (n == 0) return s;
  const double scale = H.diagonal().cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) throw RunError("relaxed moduli: the stiffness matrix is zero");
  const double shift = opt.zero_tolerance * scale;
  SpMat I(n, n);
  I.setIdentity();
  Eigen::SimplicialLDLT<SpMat> lo, hi;
  lo.compute(H - shift * I);  // negative pivots: eigenvalues below +shift
  hi.compute(H + shift * I);  // negative pivots: eigenvalues below -shift
  if (lo.info() != Eigen::Success || hi.info() != Eigen::Success)
    throw RunError("relaxed moduli: the sparse LDL^T factorisation failed");
  s.unstable = count_negative(hi.vectorD());
  s.zero_modes = count_negative(lo.vectorD()) - s.unstable;
  if (s.unstable > 0) {
    s.relaxation.setConstant(kNaN);
    return s;
  }
  Eigen::MatrixXd Z;
  if (s.zero_modes == known.cols()) {
    Z = known;
  } else if (s.zero_modes > opt.max_mechanisms + known.cols()) {
    throw RunError("relaxed moduli: " + std::to_string(s.zero_modes) + " zero modes, more than the " +
                   std::to_string(opt.max_mechanisms) + " it projects out (max_mechanisms)");
  } else if (s.zero_modes > 0) {
    // Subspace iteration with (H + s I)^{-1}: zero modes grow by 1/s, the rest by <= 1/lambda_min.
    const Eigen::Index m = s.zero_modes, b = m + 4;
    std::mt19937_64 rng(12345);
    std::normal_distribution<double> g;
    Eigen::MatrixXd Y(n, b);
    for (Eigen::Index j = 0; j < b; ++j)
      for (Eigen::Index i = 0; i < n; ++i) Y(i, j) = g(rng);
    for (int it = 0; it < 12; ++it) {
      Y = hi.solve(Y);
      Eigen::HouseholderQR<Eigen::MatrixXd> qr(Y);
      Y = qr.householderQ() * Eigen::MatrixXd::Identity(n, b);
    }
    const Eigen::MatrixXd T = Y.transpose() * (H * Y);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (T + T.transpose()));
    Z = Y * es.eigenvectors().leftCols(m);
  }
  auto project = [&Z](Eigen::MatrixXd& X) {
    if (Z.cols() > 0) X -= Z * (Z.transpose() * X);
  };
  Eigen::MatrixXd B = Xi;
  project(B);
  s.forcing = (Xi - B).norm() / xi_scale;
  // (H + s I)^{-1} with iterative refinement converges to H^+ B on the complement of Z (error
  // ratio s/(lambda + s) per step).
  Eigen::MatrixXd X = hi.solve(B);
  project(X);
  const double bn = std::max(B.norm(), std::numeric_limits<double>::min());
  for (int it = 0; it < 30; ++it) {
    const Eigen::MatrixXd R = B - H * X;
    s.residual = R.norm() / bn;
    if (s.residual < 1e-14) break;
    Eigen::MatrixXd dX = hi.solve(R);
    project(dX);
    X += dX;
  }
  s.relaxation = B.transpose() * X;
  s.relaxation = 0.5 * (s.relaxation + s.relaxation.transpose()).eval();
  return s;
}

}  // namespace

const char* boundary_name(RelaxedBoundary b) { return b == RelaxedBoundary::bulk ? "bulk" : "slab"; }

RelaxedModuli relaxed_moduli(const ContactNetwork& net, const RelaxedOptions& opt) {
  const int np = static_cast<int>(net.particles.size());
  if (np == 0) throw InputError("relaxed moduli: the network has no particles");
  if (!(net.box_x > 0.0 && net.box_y > 0.0)) throw InputError("relaxed moduli: box_x and box_y must be > 0");
  const bool bulk = opt.boundary == RelaxedBoundary::bulk;
  if (bulk && !(opt.box_z > 0.0)) throw InputError("relaxed moduli: the bulk needs the z period box_z > 0");
  if (!bulk && opt.affine_layers < 1) throw InputError("relaxed moduli: the slab needs affine_layers >= 1");
  if (!opt.tangential_force.empty() && opt.tangential_force.size() != net.contacts.size())
    throw InputError("relaxed moduli: tangential_force needs one entry per contact");
  RelaxedModuli r;
  r.boundary = opt.boundary;
  r.particles = np;
  r.contacts = static_cast<int>(net.contacts.size());

  int lmin = net.particles[0].layer, lmax = lmin;
  double aref = 0.0;
  for (const auto& p : net.particles) {
    lmin = std::min(lmin, p.layer), lmax = std::max(lmax, p.layer);
    if (!(p.radius > 0.0) || !(p.mass > 0.0)) throw InputError("relaxed moduli: every particle needs radius > 0 and mass > 0");
    aref += p.radius / np;
  }
  // Prescribed (affine) particles and the weights of the slab's end layers.
  std::vector<char> prescribed(np, 0);
  const bool by_role = !bulk && !opt.prescribed.empty();
  if (by_role) {
    if (static_cast<int>(opt.prescribed.size()) != np)
      throw InputError("relaxed moduli: prescribed needs one flag per particle");
    if (!(opt.slab_volume > 0.0)) throw InputError("relaxed moduli: a slab prescribed by flags needs slab_volume > 0");
    prescribed = opt.prescribed;
    if (std::find(prescribed.begin(), prescribed.end(), 0) == prescribed.end())
      throw InputError("relaxed moduli: no particle left to relax in the slab");
  } else if (!bulk) {
    if (lmax - lmin + 1 <= 2 * opt.affine_layers) throw InputError("relaxed moduli: no layer left to relax in the slab");
    for (int p = 0; p < np; ++p) {
      const int l = net.particles[p].layer;
      prescribed[p] = (l < lmin + opt.affine_layers || l > lmax - opt.affine_layers) ? 1 : 0;
    }
  }
  auto end_layer = [&](int p) {
    return !bulk && !by_role && (net.particles[p].layer == lmin || net.particles[p].layer == lmax);
  };

  // Volume and density.
  double mass = 0.0;
  if (bulk) {
    r.volume = net.box_x * net.box_y * opt.box_z;
    for (const auto& p : net.particles) mass += p.mass;
  } else if (by_role) {
    r.volume = opt.slab_volume;
    for (const auto& p : net.particles) mass += p.mass;
  } else {
    double zlo = 0.0, zhi = 0.0;
    int nlo = 0, nhi = 0;
    for (int p = 0; p < np; ++p) {
      const auto& q = net.particles[p];
      mass += (end_layer(p) ? 0.5 : 1.0) * q.mass;
      if (q.layer == lmin) zlo += q.z, ++nlo;
      if (q.layer == lmax) zhi += q.z, ++nhi;
    }
    r.volume = net.box_x * net.box_y * (zhi / nhi - zlo / nlo);
    if (!(r.volume > 0.0)) throw InputError("relaxed moduli: the layers are not stacked upwards in z");
  }
  r.rho = mass / r.volume;

  // Rattlers, removed iteratively.
  for (const auto& c : net.contacts)
    if (c.i < 0 || c.j < 0 || c.i >= np || c.j >= np || !(c.branch.norm() > 0.0))
      throw InputError("relaxed moduli: a contact has an index out of range or a zero branch vector");
  std::vector<char> rattler(np, 0);
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::vector<Vec3>> normals(np);
    for (const auto& c : net.contacts) {
      if (!(c.normal_force >= 0.0) || !(c.k_of(net.k) > 0.0) || rattler[c.i] || rattler[c.j]) continue;
      const Vec3 n = c.branch.normalized();
      normals[c.i].push_back(n);
      normals[c.j].push_back(-n);
    }
    for (int p = 0; p < np; ++p)
      if (!prescribed[p] && !rattler[p] && !forces_can_balance(normals[p])) rattler[p] = 1, changed = true;
  }
  for (int p = 0; p < np; ++p) {
    r.rattlers += rattler[p];
    r.free_particles += (!prescribed[p] && !rattler[p]) ? 1 : 0;
  }

  // Degrees of freedom: translations of free particles; rotations of those with a tangential,
  // rolling or torsion spring.
  auto lever = [&](const NetworkContact& c, double shift) {
    const double delta = net.particles[c.i].radius + net.particles[c.j].radius - c.branch.norm();
    return std::pair{net.particles[c.i].radius - shift * delta, net.particles[c.j].radius - shift * delta};
  };
  struct Spring {
    double kn, kt, f0, k_roll, k_twist, arm_i, arm_j, weight;
  };
  std::vector<Spring> springs(net.contacts.size());
  std::vector<char> turns(np, 0);
  for (std::size_t ci = 0; ci < net.contacts.size(); ++ci) {
    const auto& c = net.contacts[ci];
    const auto [ai, aj] = lever(c, opt.contact.arm_shift);
    const auto [ri, rj] = lever(c, opt.contact.rolling_arm_shift);
    const double lv = ri * rj / (ri + rj);
    Spring& s = springs[ci];
    s = {c.k_of(net.k), c.kt_of(net.kt), c.normal_force, opt.contact.k_roll + opt.contact.kr * lv * lv,
         opt.contact.k_twist + opt.contact.ko * lv * lv, ai, aj, 1.0};
    if (end_layer(c.i) && end_layer(c.j) && net.particles[c.i].layer == net.particles[c.j].layer) s.weight = 0.5;
    if (rattler[c.i] || rattler[c.j]) continue;
    ++r.contacts_used;
    if (s.kt != 0.0 || s.k_roll != 0.0 || s.k_twist != 0.0) turns[c.i] = turns[c.j] = 1;
    const double ft = opt.tangential_force.empty() ? 0.0 : std::abs(opt.tangential_force[ci]);
    if (s.kt != 0.0 && ft >= opt.mu * s.f0 * (1.0 - 1e-12)) ++r.sliding_contacts;
  }
  {
    std::vector<Vec3> net_force(np, Vec3::Zero());
    double f_sum = 0.0;
    for (const auto& c : net.contacts) {
      if (rattler[c.i] || rattler[c.j]) continue;
      const Vec3 n = c.branch.normalized();  // f0 > 0 pushes j along n, i against it
      net_force[c.i] -= c.normal_force * n;
      net_force[c.j] += c.normal_force * n;
      f_sum += std::abs(c.normal_force);
    }
    double worst = 0.0;
    for (int p = 0; p < np; ++p)
      if (!prescribed[p] && !rattler[p]) worst = std::max(worst, net_force[p].norm());
    r.unbalanced = f_sum > 0.0 ? worst * r.contacts_used / f_sum : 0.0;
  }
  const int nonrattlers = np - r.rattlers;
  r.coordination = nonrattlers > 0 ? 2.0 * r.contacts_used / nonrattlers : 0.0;
  std::vector<int> tdof(np, -1), rdof(np, -1);
  int ndof = 0;
  for (int p = 0; p < np; ++p) {
    if (prescribed[p] || rattler[p]) continue;
    tdof[p] = ndof, ndof += 3;
    if (turns[p])
      rdof[p] = ndof, ndof += 3;
    else
      r.free_rotation_modes += 3;
  }
  r.dof = ndof;

  // Assembly (rotations scaled by aref: theta' = aref theta, so every block is in N/m).
  auto assemble = [&](bool with_f0, SpMat* H, Eigen::MatrixXd* Xi, Mat9* A, Eigen::Matrix3d* stress) {
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(r.contacts_used * 144);
    Xi->setZero(ndof, 9);
    A->setZero();
    stress->setZero();
    for (std::size_t ci = 0; ci < net.contacts.size(); ++ci) {
      const auto& c = net.contacts[ci];
      if (rattler[c.i] || rattler[c.j]) continue;
      const Spring& s = springs[ci];
      const double l = c.branch.norm();
      const Vec3 n = -c.branch / l;
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
      const double f0 = with_f0 ? s.f0 : 0.0;
      const Eigen::Matrix3d Kd = s.kn * n * n.transpose() - (f0 / l) * P;
      const Eigen::Matrix3d Q = s.k_roll * P + s.k_twist * n * n.transpose();
      // Local columns: u_i, theta'_i, u_j, theta'_j, eps (9, index 3g + f).
      Eigen::Matrix<double, 3, 21> Jd = Eigen::Matrix<double, 3, 21>::Zero(), Jx, Jr = Jd;
      Jd.block<3, 3>(0, 0).setIdentity();
      Jd.block<3, 3>(0, 6) = -Eigen::Matrix3d::Identity();
      for (int g = 0; g < 3; ++g)
        for (int f = 0; f < 3; ++f) Jd(f, 12 + 3 * g + f) = -c.branch[g];
      Jx = P * Jd;
      const Eigen::Matrix3d N = cross_matrix(n);
      Jx.block<3, 3>(0, 3) = N * (s.arm_i / aref);
      Jx.block<3, 3>(0, 9) = N * (s.arm_j / aref);
      Jr.block<3, 3>(0, 3) = Eigen::Matrix3d::Identity() / aref;
      Jr.block<3, 3>(0, 9) = -Eigen::Matrix3d::Identity() / aref;
      const Eigen::Matrix<double, 21, 21> K =
          s.weight * (Jd.transpose() * Kd * Jd + s.kt * Jx.transpose() * Jx + Jr.transpose() * Q * Jr);
      const int global[4] = {tdof[c.i], rdof[c.i], tdof[c.j], rdof[c.j]};
      for (int bi = 0; bi < 4; ++bi) {
        if (global[bi] < 0) continue;
        for (int x = 0; x < 3; ++x) {
          const int row = global[bi] + x, lr = 3 * bi + x;
          for (int bj = 0; bj < 4; ++bj) {
            if (global[bj] < 0) continue;
            for (int y = 0; y < 3; ++y) trip.emplace_back(row, global[bj] + y, K(lr, 3 * bj + y));
          }
          for (int e = 0; e < 9; ++e) (*Xi)(row, e) += K(lr, 12 + e);
        }
      }
      *A += K.bottomRightCorner<9, 9>();
      *stress += s.weight * f0 * l * n * n.transpose();
    }
    H->resize(ndof, ndof);
    H->setFromTriplets(trip.begin(), trip.end());
  };

  // Exact zero modes: the rigid translations of the bulk (normalised over the translation dofs).
  Eigen::MatrixXd known(ndof, 0);
  if (bulk && ndof > 0) {
    known.setZero(ndof, 3);
    int nt = 0;
    for (int p = 0; p < np; ++p)
      if (tdof[p] >= 0) {
        ++nt;
        for (int x = 0; x < 3; ++x) known(tdof[p] + x, x) = 1.0;
      }
    known /= std::sqrt(static_cast<double>(nt));
    r.translation_modes = 3;
  }

  for (bool with_f0 : {true, false}) {
    if (!with_f0 && !opt.unstressed) break;
    SpMat H;
    Eigen::MatrixXd Xi;
    Mat9 A;
    Eigen::Matrix3d stress;
    assemble(with_f0, &H, &Xi, &A, &stress);
    // Forcing scale: sqrt(V max A_ii max H_ii), the force of a unit strain on the stiffest dof.
    const double xi_scale = std::sqrt(r.volume * A.diagonal().cwiseAbs().maxCoeff() *
                                      (ndof > 0 ? H.diagonal().cwiseAbs().maxCoeff() : 0.0));
    const Solved s = relax(H, Xi, known, xi_scale > 0.0 ? xi_scale : 1.0, opt);
    const Tensor4 aff = to_tensor(A / r.volume), rel = to_tensor((A - s.relaxation) / r.volume);
    if (with_f0) {
      r.affine = aff, r.relaxed = rel;
      r.stress = stress / r.volume;
      r.pressure = r.stress.trace() / 3.0;
      r.unstable_modes = s.unstable;
      r.mechanisms = s.zero_modes - r.translation_modes;
      r.forcing_on_zero_modes = s.forcing;
    } else {
      r.affine_unstressed = aff, r.relaxed_unstressed = rel;
    }
    r.residual = std::max(r.residual, s.residual);
  }
  auto speed = [&](const Tensor4& t, int pol) {
    if (r.contacts_used == 0) return kNaN;  // no load-bearing network left (every particle a rattler)
    const double v2 = t.christoffel(Vec3::UnitZ())(pol, pol) / r.rho;
    return v2 >= 0.0 ? std::sqrt(v2) : kNaN;
  };
  r.V_pz = speed(r.relaxed, 2), r.V_sz = speed(r.relaxed, 0), r.V_sy = speed(r.relaxed, 1);
  r.V_pz_affine = speed(r.affine, 2), r.V_sz_affine = speed(r.affine, 0);
  return r;
}

ContactNetwork periodic_in_z(const ContactNetwork& net, const std::vector<Vec3>& centres, double box_z,
                             const ContactOf& contact_of) {
  const int np = static_cast<int>(net.particles.size());
  if (static_cast<int>(centres.size()) != np) throw InputError("periodic_in_z: one centre per particle needed");
  if (!(box_z > 0.0)) throw InputError("periodic_in_z: box_z must be > 0");
  ContactNetwork out = net;
  if (np == 0) return out;
  double zmin = centres[0].z(), zmax = zmin, amax = 0.0;
  for (int p = 0; p < np; ++p) {
    zmin = std::min(zmin, centres[p].z()), zmax = std::max(zmax, centres[p].z());
    amax = std::max(amax, net.particles[p].radius);
  }
  // Only particles within two radii of an end can touch across it (brute force over those).
  std::vector<int> top, bottom;
  for (int p = 0; p < np; ++p) {
    if (centres[p].z() >= zmax - 2.0 * amax) top.push_back(p);
    if (centres[p].z() <= zmin + 2.0 * amax) bottom.push_back(p);
  }
  auto wrap = [](double d, double box) { return d - box * std::round(d / box); };
  for (int i : top)
    for (int j : bottom) {
      if (i == j) continue;
      const Vec3 d = centres[j] - centres[i];
      const Vec3 b(wrap(d.x(), net.box_x), wrap(d.y(), net.box_y), d.z() + box_z);
      const double overlap = net.particles[i].radius + net.particles[j].radius - b.norm();
      if (!(overlap > -1e-9 * (net.particles[i].radius + net.particles[j].radius))) continue;  // touching, to round-off
      NetworkContact c = contact_of(i, j, b, overlap);
      c.i = i, c.j = j, c.branch = b;
      out.contacts.push_back(c);
    }
  return out;
}

}  // namespace granwave::theory
