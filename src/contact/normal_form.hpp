// The static normal force of a case's law as a closed form, f(delta) and its tangent k = df/ddelta
// for two spheres of radii a_i, a_j: what the random packing's compression (packing/compression.cpp)
// evaluates inline for every contact and step. Each law's description says which form is its own
// (normal_form, contact/case_law.hpp); the forms are the laws' own formulas, operation for operation.
#pragma once
#include <cmath>

#include "contact/law.hpp"

namespace granwave::contact {

struct NormalForm {
  enum class Kind { linear, hertz } kind = Kind::linear;
  double modulus = 0.0;  // linear: the spring k (N/m); hertz: E* (Pa)
};

// A contact's static normal force (N) and its tangent stiffness (N/m).
struct NormalForce {
  double f = 0.0, k = 0.0;
};

// f = k delta (contact/hooke.hpp, linear_luding.hpp).
struct LinearNormal {
  double k;
  NormalForce operator()(double, double, double delta) const { return {k * delta, k}; }
};

// f = (4/3) E* a delta, k = 2 E* a, a = sqrt(R* delta) (contact/hertz_mindlin.hpp's hertz_mindlin_at).
struct HertzNormal {
  double e_star;
  NormalForce operator()(double a_i, double a_j, double delta) const {
    const double a = std::sqrt(reduced_radius(a_i, a_j) * delta);
    return {4.0 / 3.0 * e_star * a * delta, 2.0 * e_star * a};
  }
};

// The tangential spring of the case's law beside its normal form (a frictional preparation,
// packing/friction_pairs.hpp): k_t at the contact's normal state, constant (Luding's linear k_t) or
// proportional to k_n (Mindlin's k_t = 8 G* a = (4 G*/E*) k_n, both from the contact radius a).
struct TangentialForm {
  bool proportional = false;  // k_t = value k_n (Mindlin); else k_t = value (N/m)
  double value = 0.0;
  double operator()(const NormalForce& n) const { return proportional ? value * n.k : value; }
};

// f(form) with the form's evaluator.
template <class F>
decltype(auto) with_normal(const NormalForm& form, F&& f) {
  if (form.kind == NormalForm::Kind::hertz) return f(HertzNormal{form.modulus});
  return f(LinearNormal{form.modulus});
}

}  // namespace granwave::contact
