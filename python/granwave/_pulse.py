"""What a pulse measures against the relaxed theory (issue 39 item 4): one table from the dicts of
`analyze --json` and `theory --json`, with their labels, and the differences in per cent."""

_SPEED = {"P": "V_pz", "S": "V_sz"}


def _percent(v, ref):
    if v is None or ref is None or not (ref > 0) or v != v:
        return float("nan")
    return 100.0 * (v - ref) / ref


def pulse_table(analysis, theory):
    """The speeds a pulse shows and the speeds the theory predicts, side by side.

    analysis: `granwave.analyze(trace)` (or a run's `.analysis`); theory: `granwave.theory(case)` of
    the case that made the trace. Returns a dict:

      mode, speed ("V_pz" for P, "V_sz" for S: the theory's speed along z compared)
      theory: {slab, bulk, slab_affine, bulk_affine, eq10}: m/s (NaN where the theory has none)
      measured: rows {label, travel_layers, duration (s), value, error (m/s), z_over_l0,
                      percent {slab, bulk}}: the raw step's first peaks, each smoothed pulse T
                      (`pulse_fronts`), the small-k slope (its `resolution` too) and the sine fit v_k0
      front_and_coda: analysis["front_and_coda"] as it is (z_over_l0, energies, coda_fraction)

    Labels are the JSON's: "v_first_peak", "pulse_fronts[T = m]" (m the pulse's length in layer
    delays), "small_k_slope", "v_k0". A refused pulse keeps its `error` and NaN speeds."""
    nan = float("nan")
    mode = analysis.get("mode", "P")
    key = _SPEED[mode]
    rel = theory.get("relaxed") or {}

    def val(d, *path):
        for p in path:
            if not isinstance(d, dict) or p not in d:
                return nan
            d = d[p]
        return d if isinstance(d, (int, float)) else nan

    th = {"slab": val(rel, "slab", key, "value"), "bulk": val(rel, "bulk", key, "value"),
          "slab_affine": val(rel, "slab", key + "_affine", "value"),
          "bulk_affine": val(rel, "bulk", key + "_affine", "value"),
          "eq10": val(theory, key, "value") if isinstance(theory.get(key), dict) else theory.get(key, nan)}

    def row(label, value, error, **extra):
        r = {"label": label, "value": value, "error": error,
             "percent": {"slab": _percent(value, th["slab"]), "bulk": _percent(value, th["bulk"])}}
        r.update(extra)
        return r

    fp = analysis["v_first_peak"]
    rows = [row("v_first_peak", fp["value"], fp["error"], travel_layers=0, duration=0.0, z_over_l0=fp["z_over_l0"])]
    for f in analysis.get("pulse_fronts", {}).get("durations", []):
        label = "pulse_fronts[T = %g]" % f["travel_layers"]
        extra = {"travel_layers": f["travel_layers"], "duration": f["duration"]["value"]}
        if "error" in f:
            rows.append(row(label, nan, nan, z_over_l0=None, refused=f["error"], **extra))
        else:
            v = f["v_first_peak"]
            rows.append(row(label, v["value"], v["error"], z_over_l0=v["z_over_l0"], **extra))
    s = analysis.get("small_k_slope", {})
    rows.append(row("small_k_slope", val(s, "value"), val(s, "error"), resolution=val(s, "resolution", "value"),
                    n=s.get("n")))
    rows.append(row("v_k0", val(analysis, "v_k0", "value"), val(analysis, "v_k0", "error")))
    return {"mode": mode, "speed": key, "theory": th, "measured": rows,
            "front_and_coda": analysis.get("front_and_coda")}
