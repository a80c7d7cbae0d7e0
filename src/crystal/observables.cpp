// The table of the crystal's observables (crystal/observables.hpp): its entries, and what is read
// from it. The only translation unit that lists them; granwave_testobservable builds it again with
// GRANWAVE_TEST_OBSERVABLE, which adds the test-only observable of tests/observables/.
#include "crystal/observables.hpp"

#include <set>

#include "config/case.hpp"
#include "core/error.hpp"
#include "crystal/observers.hpp"
#ifdef GRANWAVE_TEST_OBSERVABLE
#include "observables/test_layer_spin.hpp"  // tests/observables/: the test-only observable
#endif

namespace granwave::crystal {

const std::vector<Observer>& observers() {
  using enum Shape;
  static const std::vector<Observer> table = {
      {{{"/crystal", "layer_stress_zz", "layer_stress_zz", per_layer, "Pa",
         "the layer's contact stress -(1/(l_x l_y l0)) sum (x_c - x_p) f_z over the ends of its contacts "
         "(compression positive, prestress included, contact point mid-overlap, fixed pairs excluded)"},
        {"/crystal", "layer_stress_zx", "layer_stress_zx", per_layer, "Pa", "the same with f_x"}},
       sample_layer_stress},
      {{{"/crystal", "layer_displacement_z", "layer_displacement_z", per_layer, "m",
         "mean of z - z0 over the layer's particles"},
        {"/crystal", "layer_displacement_x", "layer_displacement_x", per_layer, "m",
         "mean of x - x0 over the layer's particles"},
        {"/crystal", "layer_velocity_z", "layer_velocity_z", per_layer, "m/s", "mean of v_z over the layer's particles"},
        {"/crystal", "layer_velocity_x", "layer_velocity_x", per_layer, "m/s", "mean of v_x over the layer's particles"}},
       sample_layer_motion},
      {{{"/crystal", "coordination", "coordination", series, "1",
         "touching contacts per non-fixed particle (contacts with fixed ones count), over the crystal"}},
       sample_coordination},
      {{{"/energy", "kinetic", "energy", series, "J", "sum of (1/2) m v^2 + (1/2) I w^2 over the integrated particles"},
        {"/energy", "potential", "energy", series, "J", "elastic energy stored in the contacts (the law's)"},
        {"/energy", "dissipated", "energy", series, "J", "cumulative energy lost by dashpots, sliding and opening contacts"},
        {"/energy", "work_in", "energy", series, "J", "cumulative work of the driven particles on the rest"},
        {"/energy", "verlet_correction", "energy", series, "J",
         "dt^2/8 sum(|F|^2/m + |T|^2/I): velocity Verlet conserves kinetic + potential - this for linear forces"}},
       sample_energies},
#ifdef GRANWAVE_TEST_OBSERVABLE
      test_layer_spin(),
#endif
  };
  return table;
}

const std::vector<Observable>& observables() {
  static const std::vector<Observable> flat = [] {
    std::vector<Observable> v;
    for (const Observer& o : observers()) v.insert(v.end(), o.observables.begin(), o.observables.end());
    return v;
  }();
  return flat;
}

std::vector<std::string> output_fields() {
  std::vector<std::string> names;
  std::set<std::string> seen;
  for (const Observable& o : observables())
    if (seen.insert(o.field).second) names.push_back(o.field);
  return names;
}

bool selected(const config::Case& c, const Observable& o) {
  if (c.output.fields.empty()) return true;
  for (const auto& f : c.output.fields)
    if (f == o.field) return true;
  return false;
}

void check_output_fields(const config::Case& c) {
  const std::vector<std::string> allowed = output_fields();
  for (const auto& f : c.output.fields) {
    bool known = false;
    for (const auto& a : allowed) known = known || a == f;
    if (known) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw InputError(c.path + ": output.fields: unknown field \"" + f + "\" (allowed: " + list + ")");
  }
}

}  // namespace granwave::crystal
