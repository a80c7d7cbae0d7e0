// The pieces of `granwave theory --json` that theory.cpp and theory_relaxed.cpp both write: a
// quantity {"value", "unit"}, a series {"unit", "values"} and a rank-4 tensor as nested arrays.
#pragma once
#include <vector>

#include "core/json.hpp"
#include "theory/stiffness.hpp"

namespace granwave::cli {

inline Json quantity(double v, const char* unit) { return {{"value", v}, {"unit", unit}}; }

inline Json values(const std::vector<double>& v, const char* unit) { return {{"unit", unit}, {"values", v}}; }

// T[a][b][g][f] in Pa; `index_order` says what the four indices are.
inline Json tensor_json(const theory::Tensor4& T, const char* index_order) {
  Json values = Json::array();
  for (int a = 0; a < 3; ++a) {
    Json A = Json::array();
    for (int b = 0; b < 3; ++b) {
      Json B = Json::array();
      for (int g = 0; g < 3; ++g) {
        Json G = Json::array();
        for (int f = 0; f < 3; ++f) G.push_back(T(a, b, g, f));
        B.push_back(G);
      }
      A.push_back(B);
    }
    values.push_back(A);
  }
  return {{"unit", "Pa"}, {"index_order", index_order}, {"values", values}};
}

}  // namespace granwave::cli
