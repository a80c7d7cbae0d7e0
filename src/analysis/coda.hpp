// The coherent front and the coda of a layer's signal (issue 39 item 4; Somfai et al., PRE 72 021301
// (2005): in a disordered packing a coherent front is followed by a scattered coda). The front is the
// leading pulse, from its 1 % arrival for its duration (measures.hpp: to the next 1 % crossing);
// the coda is the rest of the signal until the front's reflection from the top could return
// (t_arrival + 2 (z_wall - z)/V, V the 1 % arrival speed) or the record ends. Energies are sum y^2 dt
// of the measured signal (sign-normalised, baseline removed): the coda's share against distance says
// how much of the wave has left the front, by scattering or by dispersion (a lattice's ringing tail).
#pragma once
#include <span>

namespace granwave::analysis {

struct FrontCoda {
  double front = 0.0, coda = 0.0;  // sum y^2 dt (signal^2 s); NaN when the front has not arrived
  double coda_end = 0.0;           // s: where the coda window stops
};

FrontCoda front_and_coda(std::span<const double> t, std::span<const double> y, double t_arrival, double duration,
                         double t_stop);

}  // namespace granwave::analysis
