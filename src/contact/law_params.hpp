// The case's contact parameters: the chosen law's own parameter type (its description's Params:
// contact/linear_luding_params.hpp, contact/hertz_mindlin_params.hpp, tests/laws/), held by value
// without the holder knowing the laws, in the manner of HOOMD-blue's per-evaluator param_type.
// What every law embeds (Friction, and RollingTorsionKeys where it has them) is reachable without
// naming the law; anything else of a law is asked of its description through the registry, or
// read with get<Params>() by code that is that law's own.
#pragma once
#include <any>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "contact/friction.hpp"
#include "contact/law_id.hpp"
#include "contact/linear_luding_params.hpp"
#include "contact/rolling_torsion_keys.hpp"

namespace granwave::contact {

class LawParams {
 public:
  LawParams() : LawParams(LinearLudingParams{}) {}  // the default law with its defaults
  template <class P>
  LawParams(P p) : access_(&access_of<P>), params_(std::move(p)) {}  // NOLINT: implicit, c.contact = params

  ContactLaw law() const { return access_->law; }

  template <class P>
  const P* find() const { return std::any_cast<P>(&params_); }
  template <class P>
  P* find() { return std::any_cast<P>(&params_); }
  template <class P>
  const P& get() const {
    if (const P* p = find<P>()) return *p;
    throw std::logic_error("contact parameters: another law's asked of this case's");
  }
  template <class P>
  P& get() { return const_cast<P&>(std::as_const(*this).get<P>()); }

  const Friction& friction() const { return *access_->friction(const_cast<std::any&>(params_)); }
  Friction& friction() { return *access_->friction(params_); }
  // The law's rolling and torsion keys (all off for a law without them).
  const RollingTorsionKeys& rolling() const {
    static const RollingTorsionKeys off;
    const RollingTorsionKeys* k = access_->rolling(const_cast<std::any&>(params_));
    return k ? *k : off;
  }
  RollingTorsionKeys* rolling_keys() { return access_->rolling(params_); }
  // A number key of the law by its case-file name (studies vary them); nullopt if the law has none.
  std::optional<double> number(std::string_view key) const {
    if (const double* v = access_->number(const_cast<std::any&>(params_), key)) return *v;
    return std::nullopt;
  }
  void set_number(std::string_view key, double value) {
    double* v = access_->number(params_, key);
    if (!v) throw std::logic_error("contact parameters: the law has no key " + std::string(key));
    *v = value;
  }

 private:
  struct Access {
    ContactLaw law;
    Friction* (*friction)(std::any&);
    RollingTorsionKeys* (*rolling)(std::any&);
    double* (*number)(std::any&, std::string_view);
  };
  template <class P>
  static constexpr Access access_of{
      P::law, [](std::any& a) { return &std::any_cast<P&>(a).friction; },
      [](std::any& a) -> RollingTorsionKeys* {
        if constexpr (requires(P& p) { p.rolling; })
          return &std::any_cast<P&>(a).rolling;
        else
          return nullptr;
      },
      [](std::any& a, std::string_view key) { return std::any_cast<P&>(a).number(key); }};

  const Access* access_;
  std::any params_;
};

}  // namespace granwave::contact
