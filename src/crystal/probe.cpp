// The static probe (crystal/probe.hpp): strain, FIRE relaxation under the full law, the stress change.
#include "crystal/probe.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "crystal/fire.hpp"

namespace granwave::crystal {

const char* probe_strain_name(ProbeStrain s) {
  switch (s) {
    case ProbeStrain::zz: return "zz";
    case ProbeStrain::zx: return "zx";
    case ProbeStrain::xx: return "xx";
    case ProbeStrain::yy: return "yy";
    case ProbeStrain::yx: return "yx";
  }
  return "?";
}

ProbeStrain parse_probe_strain(const std::string& s) {
  for (ProbeStrain p : {ProbeStrain::zz, ProbeStrain::zx, ProbeStrain::xx, ProbeStrain::yy, ProbeStrain::yx})
    if (s == probe_strain_name(p)) return p;
  if (s == "xy" || s == "xz" || s == "yz")
    throw InputError("--strain " + s + ": not offered (gradient " + s.substr(0, 1) + ", displacement " + s.substr(1) +
                     " needs a shift of the +" + s.substr(0, 1) +
                     " images; the sheared box shifts the +y images in x, which is yx); allowed: zz, zx, xx, yy, yx");
  throw InputError("--strain " + s + ": allowed: zz, zx, xx, yy, yx (gradient direction, then displacement direction)");
}

std::pair<int, int> probe_strain_indices(ProbeStrain s) {
  switch (s) {
    case ProbeStrain::zz: return {2, 2};
    case ProbeStrain::zx: return {2, 0};
    case ProbeStrain::xx: return {0, 0};
    case ProbeStrain::yy: return {1, 1};
    case ProbeStrain::yx: return {1, 0};
  }
  return {2, 2};
}

// A named type (not in the anonymous namespace below): StaticProbe::Strained holds one.
struct StressSum {
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero(), S = Eigen::Matrix3d::Zero();  // sum w B f_j, sum w b f_j
  int touching = 0, sliding = 0;
  double max_slip = 0.0;
};

namespace {

// The largest force (and torque / radius) on a mobile particle.
double largest_force(const Dynamics& d) {
  double worst = 0.0;
  for (std::size_t p = 0; p < d.size(); ++p) {
    if (!d.mobile[p]) continue;
    worst = std::max(worst, std::hypot(d.fx[p], d.fy[p], d.fz[p]));
    if (d.torques()) worst = std::max(worst, std::hypot(d.tx[p], d.ty[p], d.tz[p]) / d.radius[p]);
  }
  return worst;
}

// FIRE (Bitzek et al., PRL 97, 170201 (2006)) on translations and rotations (angular velocity scaled
// by the radius, torque divided by it, so both are m/s and N) until every mobile particle's force is
// below f_tol. Velocities are zero afterwards; the forces are those of the final positions.
long fire(Dynamics& d, double t_c, double f_tol, long max_steps, double* residual) {
  Fire fire(t_c);
  const std::size_t n = d.size();
  const bool rot = d.torques();
  auto stop = [&] {
    for (auto* v : {&d.vx, &d.vy, &d.vz, &d.wx, &d.wy, &d.wz}) std::fill(v->begin(), v->end(), 0.0);
  };
  for (long s = 0; s < max_steps; ++s) {
    const double f = largest_force(d);
    if (f <= f_tol) {
      *residual = f;
      stop();
      d.compute_forces_of_state();  // the dashpots see the velocities gone
      return s;
    }
    double power = 0.0, v2 = 0.0, f2 = 0.0;
    for (std::size_t p = 0; p < n; ++p) {
      if (!d.mobile[p]) continue;
      power += d.fx[p] * d.vx[p] + d.fy[p] * d.vy[p] + d.fz[p] * d.vz[p];
      v2 += d.vx[p] * d.vx[p] + d.vy[p] * d.vy[p] + d.vz[p] * d.vz[p];
      f2 += d.fx[p] * d.fx[p] + d.fy[p] * d.fy[p] + d.fz[p] * d.fz[p];
      if (rot) {
        const double a = d.radius[p];
        power += d.tx[p] * d.wx[p] + d.ty[p] * d.wy[p] + d.tz[p] * d.wz[p];
        v2 += a * a * (d.wx[p] * d.wx[p] + d.wy[p] * d.wy[p] + d.wz[p] * d.wz[p]);
        f2 += (d.tx[p] * d.tx[p] + d.ty[p] * d.ty[p] + d.tz[p] * d.tz[p]) / (a * a);
      }
    }
    const Fire::Mix mix = fire.next(power, v2, f2);
    if (mix.moving) {
      for (std::size_t p = 0; p < n; ++p) {
        if (!d.mobile[p]) continue;
        d.vx[p] = mix.keep * d.vx[p] + mix.scale * d.fx[p];
        d.vy[p] = mix.keep * d.vy[p] + mix.scale * d.fy[p];
        d.vz[p] = mix.keep * d.vz[p] + mix.scale * d.fz[p];
        if (rot) {  // a w' = keep a w + scale T/a
          const double a2 = d.radius[p] * d.radius[p];
          d.wx[p] = mix.keep * d.wx[p] + mix.scale * d.tx[p] / a2;
          d.wy[p] = mix.keep * d.wy[p] + mix.scale * d.ty[p] / a2;
          d.wz[p] = mix.keep * d.wz[p] + mix.scale * d.tz[p] / a2;
        }
      }
    } else {
      stop();
    }
    d.set_dt(fire.dt);
    d.step();
  }
  throw RunError("probe: FIRE did not bring every free particle's force below " + std::to_string(f_tol) + " N within " +
                 std::to_string(max_steps) + " steps (largest " + std::to_string(largest_force(d)) + " N)");
}

// U = e eps^T x of the strain on every particle and on the periodic images' offsets (the box: xx, yy
// stretch it, yx shears it), made as velocities over one force evaluation so that the tangential
// springs stretch by the affine relative displacement, across the box's faces too (the images move
// with the box's rates, ImageMotion); then at rest.
void apply_affine(Dynamics& d, ProbeStrain s, double e, double z_origin) {
  const auto [g, f] = probe_strain_indices(s);
  const double dt = d.dt();
  // An image offset (sx box_x + sy shift_x, sy box_y, 0) moves by e times its g component along f.
  const double box_x = d.packing().box_x, box_y = d.packing().box_y;
  ImageMotion moving = d.images();
  double new_x = box_x, new_y = box_y;
  if (s == ProbeStrain::xx) {
    new_x = box_x + e * box_x;
    moving.rate_x = e * box_x / dt;
    moving.rate_shift = e * moving.shift_x / dt;  // 0 from the unsheared reference
    moving.shift_x += e * moving.shift_x;
  } else if (s == ProbeStrain::yy) {
    new_y = box_y + e * box_y;
    moving.rate_y = e * box_y / dt;
  } else if (s == ProbeStrain::yx) {
    moving.shift_x += e * box_y;
    moving.rate_shift = e * box_y / dt;
  }
  d.set_box(new_x, new_y, moving);
  SpreadVector<double>* pos[3] = {&d.x, &d.y, &d.z};
  SpreadVector<double>* vel[3] = {&d.vx, &d.vy, &d.vz};
  for (std::size_t p = 0; p < d.size(); ++p) {
    const double xg = (*pos[g])[p] - (g == 2 ? z_origin : 0.0);
    const double u = e * xg;
    (*pos[f])[p] += u;
    for (int a = 0; a < 3; ++a) (*vel[a])[p] = a == f ? u / dt : 0.0;
    d.wx[p] = d.wy[p] = d.wz[p] = 0.0;
  }
  d.compute_forces();  // springs advance by the relative tangential velocity times dt
  moving.rate_x = moving.rate_y = moving.rate_shift = 0.0;
  d.set_box(new_x, new_y, moving);
  for (auto* v : {&d.vx, &d.vy, &d.vz}) std::fill(v->begin(), v->end(), 0.0);
  d.compute_forces_of_state();
}

// Over the touching contacts of d: all, or (pairs_only) those of two particles not mobile in `held`.
// X, Y, Z: the unstrained positions (B); bx, by: the unstrained box (not sheared); b from d's box.
void add_stress(StressSum& out, const Dynamics& d, const SpreadVector<double>& X, const SpreadVector<double>& Y,
                const SpreadVector<double>& Z, double bx, double by, const SpreadVector<std::uint8_t>* held,
                const Packing& pk, double mu) {
  d.forces_to_list();
  const ContactList& cl = d.contacts;
  const double box_x = d.packing().box_x, box_y = d.packing().box_y, shift_x = d.images().shift_x;
  for (std::size_t c = 0; c < cl.size(); ++c) {
    if (!(cl.delta[c] > 0.0)) continue;
    const int i = cl.i[c], j = cl.j[c];
    if (held && ((*held)[i] || (*held)[j])) continue;  // held = mobile flags of the free dynamics: skip unless both fixed
    double w = 1.0;
    if (!pk.from_file() && pk.layer[i] == pk.layer[j] && (pk.layer[i] == 0 || pk.layer[i] == pk.layers - 1)) w = 0.5;
    const Eigen::Vector3d B(X[j] + cl.image_x[c] * bx - X[i], Y[j] + cl.image_y[c] * by - Y[i], Z[j] - Z[i]);
    const Eigen::Vector3d b(d.x[j] + cl.image_x[c] * box_x + cl.image_y[c] * shift_x - d.x[i], d.y[j] + cl.image_y[c] * box_y - d.y[i],
                            d.z[j] - d.z[i]);
    const Eigen::Vector3d f_i(cl.f_x[c], cl.f_y[c], cl.f_z[c]);  // on i; on j: -f_i
    out.P += w * B * f_i.transpose();
    out.S += w * b * f_i.transpose();
    ++out.touching;
    const Eigen::Vector3d n = b.normalized();
    const double fn = f_i.dot(n), ft = (f_i - fn * n).norm();
    if (mu > 0.0 && fn != 0.0) {
      const double slip = ft / (mu * std::abs(fn));
      out.max_slip = std::max(out.max_slip, slip);
      out.sliding += slip >= 1.0 - 1e-9 ? 1 : 0;
    }
  }
}

}  // namespace

struct StaticProbe::Strained {
  StressSum sum;
  long steps = 0;
  double residual = 0.0;
};

StaticProbe::StaticProbe(const config::Case& c, const Packing& pk, const theory::ContactNetwork& net, double volume,
                         const ProbeOptions& opt)
    : pk_(pk), opt_(opt), volume_(volume) {
  if (!(opt.amplitude > 0.0 && opt.amplitude <= 1e-3)) throw InputError("--amplitude must be in (0, 1e-3]");
  if (!(opt.tolerance > 0.0 && opt.tolerance < 1.0)) throw InputError("--tolerance must be in (0, 1)");
  if (!(volume > 0.0)) throw InputError("probe: the slab's volume must be > 0");
  model_ = case_model(c.contact, c.crystal->density);
  tangential = model_->torques();
  mu_ = c.contact.friction().mu_static;
  // The force scale of the strain and the stiffest contact's time.
  double k_sum = 0.0, l_sum = 0.0, k_max = 0.0;
  for (const auto& nc : net.contacts) {
    const double k = nc.k_of(net.k);
    k_sum += k, l_sum += nc.branch.norm();
    k_max = std::max({k_max, k, nc.kt_of(net.kt)});
  }
  if (net.contacts.empty() || !(k_max > 0.0)) throw InputError("probe: the packing has no stiff contacts");
  const double nc = static_cast<double>(net.contacts.size());
  force_scale = opt.amplitude * (k_sum / nc) * (l_sum / nc);
  const double m_min = *std::min_element(pk.mass.begin(), pk.mass.end());
  t_c_ = std::numbers::pi * std::sqrt(0.5 * m_min / k_max);
  base_ = std::make_unique<Dynamics>(pk_, model_, 0.02 * t_c_);
  base_steps = fire(*base_, t_c_, opt.tolerance * force_scale, opt.max_steps, &base_residual);
  base_residual /= force_scale;
  Packing all = pk_;
  std::fill(all.fixed.begin(), all.fixed.end(), 0);
  pairs_ = std::make_unique<Dynamics>(all, model_, 0.02 * t_c_);
  StressSum s0;
  add_stress(s0, *base_, base_->x, base_->y, base_->z, pk_.box_x, pk_.box_y, nullptr, pk_, mu_);
  add_stress(s0, *pairs_, pairs_->x, pairs_->y, pairs_->z, pk_.box_x, pk_.box_y, &base_->mobile, pk_, mu_);
  P0 = s0.P / volume_;
}

StaticProbe::Strained StaticProbe::strained(ProbeStrain s, double e) const {
  // From the relaxed state with its springs: the free particles' dynamics and the list of every
  // pair (the held slabs' own contacts), both strained affinely, the free particles then relaxed.
  Strained out;
  Dynamics d = *base_, q = *pairs_;
  apply_affine(d, s, e, pk_.bin_origin);
  apply_affine(q, s, e, pk_.bin_origin);
  out.steps = fire(d, t_c_, opt_.tolerance * force_scale, opt_.max_steps, &out.residual);
  add_stress(out.sum, d, base_->x, base_->y, base_->z, pk_.box_x, pk_.box_y, nullptr, pk_, mu_);
  add_stress(out.sum, q, pairs_->x, pairs_->y, pairs_->z, pk_.box_x, pk_.box_y, &base_->mobile, pk_, mu_);
  out.residual /= force_scale;
  return out;
}

ProbeResult StaticProbe::run(ProbeStrain s) const {
  const double e = opt_.amplitude;
  const Strained plus = strained(s, e), minus = strained(s, -e);
  ProbeResult r;
  r.strain = s;
  r.dP = (plus.sum.P - minus.sum.P) / (2.0 * e * volume_);
  // Cauchy: sigma = S / (V (1 + tr eps)); tr eps = +-e for zz, xx, yy, 0 for zx, yx.
  const auto [g, f] = probe_strain_indices(s);
  const double tr = g == f ? e : 0.0;
  r.dsigma = (plus.sum.S / (1.0 + tr) - minus.sum.S / (1.0 - tr)) / (2.0 * e * volume_);
  r.steps_plus = plus.steps, r.steps_minus = minus.steps;
  r.residual = std::max(plus.residual, minus.residual);
  r.max_slip = std::max(plus.sum.max_slip, minus.sum.max_slip);
  r.sliding = std::max(plus.sum.sliding, minus.sum.sliding);
  StressSum base;
  add_stress(base, *base_, base_->x, base_->y, base_->z, pk_.box_x, pk_.box_y, nullptr, pk_, mu_);
  add_stress(base, *pairs_, pairs_->x, pairs_->y, pairs_->z, pk_.box_x, pk_.box_y, &base_->mobile, pk_, mu_);
  r.contacts_changed = std::max(std::abs(plus.sum.touching - base.touching), std::abs(minus.sum.touching - base.touching));
  return r;
}

}  // namespace granwave::crystal
