// What a pulse's front measures against its duration (issue 39 item 4): the trace's own source
// history smoothed by a Hann window of duration T, for several T, and the front speeds of each.
// In the linear regime the response to the source's motion convolved with a kernel is the trace
// convolved with it, so one run gives the fronts of every longer pulse: a displacement step becomes
// a step rising over T (its velocity a Hann pulse of duration T). Longer pulses carry less of the
// short waves, and their fronts run towards the long-wave speed from the side of the dispersion
// (slower in a lattice whose group velocity falls with k).
#pragma once
#include <string>
#include <vector>

#include "analysis/trace_analysis.hpp"

namespace granwave::analysis {

// Durations T = m l0 / V_first_peak(raw) for m in travel_layers (default 4, 8, 16, 32).
std::vector<PulseFront> pulse_fronts(const CrystalTrace& trace, const CrystalAnalysisOptions& options,
                                     const CrystalAnalysis& raw, const std::vector<double>& travel_layers = {4, 8, 16, 32});

// a.pulse_fronts = pulse_fronts(trace, options, a) (what `analyze` and `run` report).
void add_pulse_fronts(const CrystalTrace& trace, const CrystalAnalysisOptions& options, CrystalAnalysis& a);

// The trace's description (CrystalTraceHeader) with the one series its fronts are measured on
// (pulse_series: by default the layer stress of its mode, or on a packing's bins the layer velocity)
// convolved in time with the Hann window of duration T (unit sum; the values before t = 0 taken as the
// first sample's); no other series.
CrystalTrace smoothed(const CrystalTrace& trace, double duration, const CrystalAnalysisOptions& options = {});

}  // namespace granwave::analysis
