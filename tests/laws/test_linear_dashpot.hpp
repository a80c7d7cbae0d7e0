// The test-only third contact law (issue #26): a linear normal spring-dashpot and a viscous
// tangential dashpot, f^t = -gamma_t v_t, no spring, no friction, no history. It exists to show
// that a law is added through its description alone (contact/case_law.hpp): compiled only into
// granwave_testlaw (GRANWAVE_TEST_LAW, CMakeLists.txt), whose registry lists it, and run by
// tests/cli/law_registry.py through `granwave_testlaw check/run/theory`.
#pragma once
#include <array>
#include <sstream>
#include <string>

#include "contact/case_law.hpp"
#include "contact/hooke.hpp"
#include "contact/law.hpp"
#include "contact/linear_luding_case.hpp"
#include "contact/linear_spring_dashpot.hpp"
#include "contact/tangential_spring.hpp"

namespace granwave::contact {

// Rates = false: the same law for a jump of positions (no dashpots).
template <bool Rates>
struct TestLinearDashpotLaw {
  LinearSpringDashpotParams normal;
  double gamma_t = 0.0;
  LeverArm arm = LeverArm::radius;
  double shift = 0.0;

  struct History {};
  static constexpr bool torques = true;

  TestLinearDashpotLaw(const LinearSpringDashpotParams& n, double gamma_t_, LeverArm lever_arm)
      : normal(n), gamma_t(Rates ? gamma_t_ : 0.0), arm(lever_arm), shift(arm_shift(lever_arm)) {
    normal.validate();
    if (!Rates) normal.gamma_n = 0.0;
  }

  Response evaluate(const Contact& c, History&) const {
    const double f_n = normal_force(normal, c.delta, c.delta_dot);
    const double arm_i = c.a_i - shift * c.delta, arm_j = c.a_j - shift * c.delta;
    const Vec3 vt = tangential_velocity(c.dv + arm_i * c.n.cross(c.w_i) + arm_j * c.n.cross(c.w_j), c.n);
    const Vec3 ft = -gamma_t * vt;
    // Dissipated: the normal dashpot's (or a clipped pull's) work and the tangential dashpot's power.
    const double loss = (f_n - normal.kn * c.delta) * c.delta_dot * c.dt + gamma_t * vt.squaredNorm() * c.dt;
    return {f_n * c.n + ft, c.n.cross(ft), loss};
  }
  double opening_loss(const History&) const { return 0.0; }
  void add_stored_energy(double& e, double delta, const History&) const { e += normal_energy(normal, delta); }
  LeverArm lever_arm() const { return arm; }
  bool dissipates() const { return Rates; }
  TestLinearDashpotLaw<false> without_rates() const { return {normal, 0.0, arm}; }
};

// Its parameters: the linear law's kn and gamma_n, a tangential dashpot, and friction's conventions
// (normal_tension and lever_arm act; the friction coefficients are read and unused).
struct TestLinearDashpotParams {
  static constexpr ContactLaw law = ContactLaw::test_linear_dashpot;
  double kn = 0.0, gamma_n = 0.0, gamma_t = 0.0;
  Friction friction;

  static constexpr std::array<KeySpec, 3> keys{LinearLudingParams::own_keys[0], LinearLudingParams::own_keys[2],
                                               LinearLudingParams::own_keys[3]};
  std::array<double*, 3> fields() { return {&kn, &gamma_n, &gamma_t}; }  // keys' order

  template <class Reader, class Table>
  static TestLinearDashpotParams read(const Reader& r, const Table& t) {
    TestLinearDashpotParams p;
    read_numbers(r, t, keys, p.fields());
    p.friction = Friction::read(r, t);
    return p;
  }
  double* number(std::string_view key) { return number_field(keys, fields(), key); }
};

struct TestLinearDashpotCase {
  using Params = TestLinearDashpotParams;
  static constexpr ContactLaw law = Params::law;
  static constexpr const char* name = "test_linear_dashpot";
  static constexpr auto keys = names_of(Params::keys);
  static constexpr const char* refusal_note = " (this case's law is \"test_linear_dashpot\")";
  static constexpr const char* summary = "linear spring-dashpot and a viscous tangential dashpot (tests only)";

  template <class Reader, class Table>
  static Params read(const Reader& r, const Table& t) { return Params::read(r, t); }
  template <class Reader, class Table>
  static void check_case(const Reader&, const Table&, const Params&, double) {}

  static bool torques(const Params& p) { return p.gamma_t > 0.0; }
  static const char* history_name(const Params&) { return "none"; }

  // A dashpot has no stiffness: k_t = 0, its damping gamma_t.
  static constexpr bool stiffness_of_overlap = false;
  static constexpr bool hertz_normal = false;
  static constexpr const char* prestress_formula = "2 sqrt(2) k delta / d'^2";
  static constexpr const char* linearisation_note = "the linear spring k; the tangential dashpot adds no stiffness";
  static LinearisedContact at(const Params& p, double, double, double, double delta) {
    return {p.kn * delta, p.kn, 0.0, p.gamma_n, p.gamma_t};
  }
  static NormalForm normal_form(const Params& p, double) { return {NormalForm::Kind::linear, p.kn}; }
  // The spring alone, as the linear law relaxes (its Hooke form), named as this law.
  static Relaxation relaxation(const Params& p, double, double, double m_min, double) {
    Params spring;
    spring.kn = p.kn;
    return {spring, contact_time({p.kn, 0.0, false}, 0.5 * m_min)};
  }
  template <class Make>
  static auto model(const Params& p, double, const Make& make) {
    const LinearSpringDashpotParams n{p.kn, p.gamma_n, p.friction.clip()};
    if (torques(p)) return make(TestLinearDashpotLaw<true>(n, p.gamma_t, p.friction.lever_arm));
    return with_flags([&]<bool Dashpot>() { return make(HookeLaw<Dashpot>(n)); }, n.gamma_n > 0.0);
  }

  static GuardKeys guard_keys() {
    return {"contact.kn", "contact.gamma_n", "contact.kn, contact.gamma_n, contact.gamma_t, crystal.polydispersity",
            "contact.kn, crystal.overlap, crystal.radius", "contact.kn"};
  }
  // The spring's: the linear law's first guard and (no) stability note.
  static ScaleCheck scale(const Params& p, double, double, double m) {
    return {"k/m", p.kn / m, "contact.kn, crystal.radius, crystal.density"};
  }
  static std::string stability_note(double delta_max) { return LinearLudingCase::stability_note(delta_max); }
  static std::string check_line(const Params& p, const LinearisedContact&) {
    std::ostringstream o;
    o << "  contact law test_linear_dashpot: k = " << p.kn << " N/m, gamma_n = " << p.gamma_n
      << " kg/s, tangential dashpot gamma_t = " << p.gamma_t << " kg/s (no spring, no friction)\n";
    return o.str();
  }
  static std::string tangential_line(const Params&) { return ""; }
};

}  // namespace granwave::contact
