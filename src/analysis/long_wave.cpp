// The long-wave speed of a measured dispersion and its branch model (analysis/long_wave.hpp).
#include "analysis/long_wave.hpp"

#include <algorithm>
#include <cmath>

namespace granwave::analysis {

LongWaveFit fit_long_wave(const DispersionResult& d, char mode, const std::optional<LatticeBranches>& lattice,
                          const std::string& no_lattice) {
  LongWaveFit f;
  f.value = d.v_k0;
  f.error = d.v_k0_error;
  if (!lattice) {
    f.reason = no_lattice;
    return f;
  }
  const theory::LatticeDispersion& L = lattice->dispersion;
  const int dof = mode == 'S' ? 0 : 2;  // u_x, u_z (theory::kLatticeDof)
  const auto it = std::find(L.dominant.begin(), L.dominant.end(), dof);
  if (it == L.dominant.end()) {
    f.reason = std::string("the case's lattice has no branch of ") + theory::kLatticeDof[dof];
    return f;
  }
  const int b = static_cast<int>(it - L.dominant.begin());
  const auto& br = L.branches[b];
  f.branch = theory::kLatticeDof[dof];
  f.v_lattice = mode == 'S' ? lattice->v_s : lattice->v_p;
  const double omega_edge = br.back().omega;  // k = pi/l0
  double dev = 0.0;
  for (std::size_t i = 0; i < L.k.size(); ++i)
    dev = std::max(dev, std::abs(br[i].omega - omega_edge * std::abs(std::sin(0.5 * L.k[i] * L.period))));
  f.sine_deviation = dev / omega_edge;
  if (f.sine_deviation <= kSineTolerance) {
    f.reason = "the case's lattice branch " + f.branch + " is this sine: no rotations driven";
    return f;
  }
  f.model = "lattice_branch";
  f.reason = "the case's lattice branch " + f.branch + " drives rotations: not a sine";
  f.value = f.error = kNaN;
  if (d.spectrum.empty()) return f;
  const theory::RidgeComparison r = theory::compare_ridge(d.spectrum, d.k_axis, d.omega_axis, L, b, +1);
  f.columns = r.columns;
  f.with_ridge = r.with_ridge;
  f.within_one_bin = r.within_one_bin;
  f.median_offset_bins = r.median_offset_bins;
  const std::size_t n = r.k.size();
  if (n < 3) return f;
  // Least squares omega_ridge = s omega_branch; the standard error from the residuals.
  double sbb = 0.0, srb = 0.0;
  for (std::size_t i = 0; i < n; ++i) sbb += r.omega_branch[i] * r.omega_branch[i], srb += r.omega_ridge[i] * r.omega_branch[i];
  f.scale = srb / sbb;
  double ss = 0.0;
  for (std::size_t i = 0; i < n; ++i) ss += std::pow(r.omega_ridge[i] - f.scale * r.omega_branch[i], 2);
  f.scale_error = std::sqrt(ss / static_cast<double>(n - 1) / sbb);
  f.value = f.scale * f.v_lattice;
  f.error = f.scale_error * f.v_lattice;
  return f;
}

}  // namespace granwave::analysis
