// `granwave figures packing`: the figures and summary.md of a finished packing study file
// (packing_study.hpp): log-log K and G against p with the p^(1/3) line (Makse et al., PRE 70,
// 061302 (2004)), Z and z* against p, V_p and V_s against p, every packing a point.
#pragma once
#include <ostream>
#include <string>

namespace granwave::sweep {

// Reads the study file at `study_h5` (kind = "packing_study"; InputError otherwise) - or, for a
// study still running, its OUT.parts directory (the members committed so far; summary.md says how
// many) - writes
// packing_members.csv, packing_table.csv and summary.md to out_dir, then draws the PNGs with
// /usr/bin/python3 (python/granwave/packing_figures.py) unless `draw` is false.
int packing_figures(const std::string& study_h5, const std::string& out_dir, std::ostream& log, bool draw = true);

}  // namespace granwave::sweep
