// The compression path of a packing study (`[study] path = "compression"`, docs/random-packing.md "A
// compression path"): each seed's packing prepared once from a gas at the lowest pressure, then loaded
// step by step to each next pressure (FIRE on the enthalpy at the new pressure from the previous static
// packing), as Agnolin & Roux, PRE 76, 061302 (2007) and Makse, Gland, Johnson & Schwartz, PRE 70,
// 061302 (2004) obtain their pressure series. Each stage's packing is saved (packing/prepared_state.hpp)
// under the study's path directory, so an interrupted study resumes from the last saved pressure.
#pragma once
#include <string>

#include "packing/prepared_state.hpp"
#include "sweep/packing_study.hpp"

namespace granwave::sweep {

// The saved packing of the member's (width, seed) path at the member's pressure.
std::string path_stage_file(const PackingStudy& s, const PackingMember& m);

// Prepares (or reads back) every stage of the member's path up to its pressure; returns the file of
// the member's stage. Stages of one path are prepared by one thread at a time.
std::string ensure_path_stages(const PackingStudy& s, const PackingMember& m, const StudyControl* control);

}  // namespace granwave::sweep
