// The contact-law registry (contact/case_laws.hpp, config/contact_laws.hpp): what a law's
// description says agrees with the evaluator its model runs, for every crystal case of data/cases.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "config/case.hpp"
#include "contact/hertz_mindlin_params.hpp"
#include "config/contact_laws.hpp"
#include "crystal/dynamics.hpp"
#include "crystal/simulation.hpp"

using namespace granwave;

TEST_CASE("contact-law registry: every case's law description agrees with the model it runs", "[crystal][law]") {
  int crystals = 0;
  for (const auto& e : std::filesystem::directory_iterator("data/cases")) {
    if (e.path().extension() != ".toml") continue;
    const config::Case c = config::load_case(e.path().string());
    if (c.model != config::Model::crystal) continue;
    ++crystals;
    INFO(e.path().string());
    const config::ContactLawInfo& law = config::law_of(c.contact);
    const auto model = crystal::case_model(c.contact, c.crystal->density);
    CHECK(model->torques() == law.torques(c.contact));
    if (model->torques()) CHECK(model->lever_arm() == c.contact.friction().lever_arm);
    CHECK(crystal::contact_law_name(c.contact) == law.name);
    // The linearised contact at delta_0: the linear law's keys, Hertz's k_n = 2 E* a.
    const double delta = 2.0 * c.crystal->radius * c.crystal->overlap;
    const contact::LinearisedContact k0 = crystal::contact_at(c, delta);
    CHECK(k0.f_n == crystal::static_normal_force(c, c.crystal->radius, c.crystal->radius, delta));
    // The closed form the random packing's compression evaluates inline is the law's own, bit for bit
    // (equal and unequal radii).
    const contact::NormalForm form = law.normal_form(c.contact, c.crystal->density);
    for (const double a_j : {c.crystal->radius, 0.8 * c.crystal->radius}) {
      const contact::NormalForce nf =
          contact::with_normal(form, [&](const auto& f) { return f(c.crystal->radius, a_j, delta); });
      const contact::LinearisedContact lc = law.at(c.contact, c.crystal->density, c.crystal->radius, a_j, delta);
      CHECK(nf.f == lc.f_n);
      CHECK(nf.k == lc.kn);
    }
    if (!law.stiffness_of_overlap) {
      CHECK(k0.kn == c.contact.get<contact::LinearLudingParams>().kn);
      CHECK(k0.kt == c.contact.get<contact::LinearLudingParams>().kt);
    } else {
      const auto& hm = c.contact.get<contact::HertzMindlinCaseParams>();
      const double E_star = hm.youngs_modulus / (2.0 * (1.0 - hm.poisson_ratio * hm.poisson_ratio));
      CHECK(k0.kn == Approx(2.0 * E_star * std::sqrt(0.5 * c.crystal->radius * delta)).epsilon(1e-14));
    }
  }
  CHECK(crystals >= 15);
}

TEST_CASE("contact-law registry: every law named once and the owners of a key", "[crystal][law]") {
  const auto names = config::contact_law_names();
  REQUIRE(names.size() >= 2);
  CHECK(names.front() == "linear");  // the default of [contact] law
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t j = i + 1; j < names.size(); ++j) CHECK(names[i] != names[j]);
  CHECK(config::contact_law_owners("youngs_modulus") == "\"hertz_mindlin\"");
  CHECK(config::law_of(config::ContactLaw::linear).has_key("kt"));
  CHECK_FALSE(config::law_of(config::ContactLaw::hertz_mindlin).has_key("kt"));
}
