// Helpers of the packing-study physics tests (sweep_packing_*.cpp): a study text that must be refused
// with an InputError naming a key.
#pragma once
#include <catch2/catch.hpp>

#include <string>

#include "core/error.hpp"
#include "sweep/packing_study.hpp"

namespace packing_study_test {

// TEXT, read as a study file in data/studies (its case paths relative to that folder), is refused
// with an InputError whose message names KEY.
inline void check_refused(const std::string& text, const std::string& key) {
  try {
    granwave::sweep::parse_packing_study(text, std::string(GRANWAVE_SOURCE_DIR) + "/data/studies/bad.toml");
  } catch (const granwave::InputError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find(key) != std::string::npos);
    return;
  }
  FAIL("accepted: " << text);
}

}  // namespace packing_study_test
