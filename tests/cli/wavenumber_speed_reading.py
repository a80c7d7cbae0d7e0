"""`[analysis] wavenumber_speed` and `granwave analyze --wavenumber-speed` (issue #31): which local
speed V goes into seed 002 sec. 3.4's k = (2/l0) arccos(V/V(k->0)).

The case (crystal_small's P wave) asks for the stress's first peaks: `analyze` must take the reading
from the trace's case text, `--wavenumber-speed displacement_peak` must override it, k_speed must be
the chosen local speed in every layer (the stress's: local_speed; the displacement's: the five-layer
formula on displacement_peak_time) and k_from_speed its group-speed inversion. A bad value, and the
flag on a chain trace, exit 2.

usage: wavenumber_speed_reading.py GRANWAVE CASE CHAIN_CASE WORKDIR
"""
import json
import math
import os
import sys

from reading_option import check_each_greater, check_refusals, check_text_says, fail, run


def five_layer_speeds(t, l0):
    """The local speed of trace_analysis.hpp: slowness = (1,2,2,1)/6-weighted mean of four delays."""
    w = (1 / 6, 2 / 6, 2 / 6, 1 / 6)
    v = [None] * len(t)
    for i in range(2, len(t) - 2):
        window = t[i - 2:i + 3]
        if any(x is None for x in window):
            continue
        s = sum(wj * (window[j + 1] - window[j]) for j, wj in enumerate(w))
        if s > 0:
            v[i] = l0 / s
    return v


def check_k(a, expected_speeds):
    L = a["layers"]
    l0, vk0 = a["l0"]["value"], a["v_k0"]["value"]
    n = 0
    for want, vk, k in zip(expected_speeds, L["k_speed"]["values"], L["k_from_speed"]["values"]):
        if want is None:
            if vk is not None:
                fail("k_speed %r where the chosen signal gives none" % vk)
            continue
        # Recomputed from the JSON's 10-digit peak times: their rounding (5e-11 of t < 2e-4 s) over a
        # weighted delay of ~7e-6 s is < 1e-9.
        if not math.isclose(vk, want, rel_tol=1e-8):
            fail("k_speed %r != the chosen local speed %r" % (vk, want))
        if vk < vk0:
            n += 1
            # The JSON's 10 digits of V and V(k->0), amplified ~7x by arccos near 1: 1e-8.
            if not math.isclose(k, 2 / l0 * math.acos(vk / vk0), rel_tol=1e-8):
                fail("k_from_speed %r != (2/l0) arccos(%r/%r)" % (k, vk, vk0))
        elif k is not None:
            fail("k_from_speed %r for V = %r above V(k->0) = %r" % (k, vk, vk0))
    if n < 5:
        fail("only %d layers with k" % n)


def main():
    gw, case, chain_case, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    trace = os.path.join(work, "p.h5")
    r = run(gw, "run", case, "-o", trace, "--quiet")
    if r.returncode != 0:
        fail("run exited %d: %s" % (r.returncode, r.stderr))

    a = json.loads(run(gw, "analyze", trace, "--json").stdout)
    got = (a["wavenumber_speed_reading"], a["wavenumber_speed_reading_source"], a["wavenumber_speed_field"])
    if got != ("first_peak", "case_toml", "layer_stress_zz"):
        fail("analyze took %r, expected the case's first_peak on layer_stress_zz" % (got,))
    check_k(a, a["layers"]["local_speed"]["values"])
    if any("k_speed" not in row for row in a["wavelength_at"]) or not a["wavelength_at"]:
        fail("wavelength_at lacks k_speed: %r" % a["wavelength_at"])

    o = json.loads(run(gw, "analyze", trace, "--json", "--wavenumber-speed", "displacement_peak").stdout)
    got = (o["wavenumber_speed_reading"], o["wavenumber_speed_reading_source"], o["wavenumber_speed_field"])
    if got != ("displacement_peak", "option", "layer_displacement_z"):
        fail("--wavenumber-speed displacement_peak gave %r" % (got,))
    check_k(o, five_layer_speeds(o["layers"]["displacement_peak_time"]["values"], o["l0"]["value"]))
    # The displacement's first peak trails the stress's (the end of the velocity pulse).
    check_each_greater(o["layers"]["peak_time"]["values"], o["layers"]["displacement_peak_time"]["values"],
                       "displacement peak %r not after the stress peak %r")
    check_text_says(gw, trace, 'wavenumber_speed = "first_peak", from the case', "which V it used for k")

    check_refusals(gw, trace, chain_case, work, "--wavenumber-speed", "half_peak", "first_peak")
    print("ok")


if __name__ == "__main__":
    main()
