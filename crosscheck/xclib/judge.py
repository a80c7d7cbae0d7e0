"""Judging one case of `crosscheck run`: every pair of codes (and each convention twin with the codes it
stands for) compared on their traces and on the ruler's measures, against crosscheck/tolerances.toml."""
from __future__ import annotations

import numpy as np

from . import compare as C
from . import conventions as CV
from . import traces as T
from .runners import CODES, tolerance


def expected_disagreement(tol: dict, case_name: str, pair: str | None = None) -> str | None:
    """The documented reason when this case (or, with `expected_pairs` in its table, this pair of
    codes in it) is an expected disagreement; None otherwise."""
    t = tol.get("case", {}).get(case_name, {})
    why = t.get("expected_disagreement")
    if why is None:
        return None
    pairs = t.get("expected_pairs")
    if pairs is not None and pair is not None and pair not in pairs:
        return None
    return why


def stress_path(case: dict) -> str:
    """The crystal's judged stress: sigma_zx for an S wave, sigma_zz for a P wave."""
    return "/crystal/layer_stress_" + ("zx" if case.get("excitation", {}).get("mode", "P") == "S" else "zz")


def pulse_field(case: dict, *traces) -> str:
    """The field two (or more) crystal traces are compared on: the layer stress, or the layer velocity
    when one of them does not record the stress (LIGGGHTS with rolling resistance: its root attribute
    `layer_stress` says why). Chain traces: "stress" (the contact force)."""
    if any("/crystal/layer_z" in t and stress_path(case) not in t for t in traces):
        return "velocity"
    return "stress"


def layer_choice(trace: dict, nlayers: int) -> list[int]:
    """The layers (bins) of a crystal trace compared pair by pair (compare.choose_layers): with the FCC's
    fixed layers, or between a packing file's source and top slabs (the trace's /system roles)."""
    sa = trace.get("system_attrs", {})
    z = trace["/crystal/layer_z"]
    gen = str(sa.get("generator", "fcc"))
    nf = int(sa.get("fixed_layers", 2))
    if gen == "fcc":
        return C.choose_layers(z, float(sa["l0"]), nlayers, nf)
    system = {"attrs": sa, "layer": trace["layer"], "fixed": trace.get("fixed", np.zeros(len(trace["layer"]), int))}
    if "role" in trace:
        system["role"] = trace["role"]
    fr = T.free_layer_range(trace["layer"], T.roles(system), nlayers, gen, nf)
    return C.choose_layers(z, float(sa.get("bin_width", sa["l0"])), nlayers, nf, free_range=fr)


def fit_range(trace: dict):
    """The z/l0 range of the ruler's speed fits: None for the FCC (analyze's own, z/l0 = 10 .. 150); for a
    packing file's bins, those between the slabs (xclib.traces.free_layer_range), the same for every code
    (they share the system). A packing's few bins seldom reach z/l0 = 10."""
    sa = trace.get("system_attrs", {})
    gen = str(sa.get("generator", "fcc"))
    if gen == "fcc" or "/crystal/layer_z" not in trace or "layer" not in trace:
        return None
    system = {"attrs": sa, "layer": trace["layer"], "fixed": trace.get("fixed", np.zeros(len(trace["layer"]), int))}
    if "role" in trace:
        system["role"] = trace["role"]
    z = trace["/crystal/layer_z"]
    lo, hi = T.free_layer_range(trace["layer"], T.roles(system), len(z), gen, int(sa.get("fixed_layers", 0)))
    h = float(sa.get("bin_width", sa["l0"]))
    return (z[lo] / h, z[hi - 1] / h) if hi - lo >= 3 else None


def traces_for(trace: dict, case: dict, field: str = "stress"):
    """The compared signals: {label: (times, values)} baseline-subtracted. field: "stress" or
    "velocity" (crystal; pulse_field)."""
    t = trace["time"]
    out = {}
    if "/chain/contact_force" in trace:
        cf = trace["/chain/contact_force"]
        has_wall = str(trace.get("system_attrs", {}).get("wall", "free")) != "free"
        for j in C.choose_contacts(cf.shape[1], has_wall):
            out["contact %d force" % j] = (t, cf[:, j] - cf[0, j])
    else:
        S = case.get("excitation", {}).get("mode", "P") == "S"
        if field == "velocity":
            path, name = "/crystal/layer_velocity_" + ("x" if S else "z"), "v_" + ("x" if S else "z")
        else:
            path, name = stress_path(case), "sigma_" + ("zx" if S else "zz")
        if path not in trace:
            return out
        s = trace[path]
        sa = trace.get("system_attrs", {})
        l0 = float(sa["l0"])
        z = trace["/crystal/layer_z"]
        for k in layer_choice(trace, s.shape[1]):
            out["%s z/l0=%.0f" % (name, z[k] / l0)] = (t, s[:, k] - s[0, k])
    return out


def convention_difference(case: dict, trace_a: dict, trace_b: dict) -> str | None:
    """The conventions two traces (read_trace dicts) record differently where they matter for the
    case, as a reason (conventions.difference); None if they ran the same law."""
    return CV.difference(case, trace_a.get("attrs", {}), trace_b.get("attrs", {}))


def pairs_of(codes, twins=None) -> list:
    """Every pair of the codes (in CODES order), then each convention twin with the codes it stands for."""
    cs = [c for c in CODES if c in codes]
    out = [(cs[a], cs[b]) for a in range(len(cs)) for b in range(a + 1, len(cs))]
    for name, members in (twins or {}).items():
        out += [(name, m) for m in members if m in codes]
    return out


def compare_case(case, case_name, model, traces: dict, measures: dict, tol: dict, twins: dict | None = None,
                 velocity_measures: dict | None = None):
    """Rows: dict(pair, quantity, what, value, tol, status, why). `twins` maps a convention twin
    (`granwave~lammps`, a key of traces) to the codes it is compared with. A crystal pair is judged on
    the layer stress, or on the layer velocity when one of the two traces does not record the stress
    (pulse_field); `measures` are the stress measures, `velocity_measures` those on the velocity."""
    rows = []
    velocity_measures = velocity_measures or {}
    codes = [c for c in CODES if c in traces] + [t for t in (twins or {}) if t in traces]
    cur = {"pair": None, "convention": None}

    def judge(value, q):
        lim, why = tolerance(tol, model, case_name, q)
        if cur.get("field"):
            why = "%s; %s" % (cur["field"], why)
        expected = expected_disagreement(tol, case_name, cur["pair"]) or cur["convention"]
        if expected:
            return lim, "EXPECTED-DIFF", expected
        if lim is None:
            return lim, "INFO", why
        if value is None or not np.isfinite(value):
            return lim, "FAIL", "not measurable in one of the codes; " + why
        return lim, ("PASS" if value <= lim else "FAIL"), why

    def peak_rows(what, a, b, unit):
        """The first peak of one contact or layer in the pair being compared: its size and its time."""
        v = C.rel_diff(a["peak"], b["peak"])
        lim, st, why = judge(v, "peak_rel")
        rows.append(dict(pair=pair, quantity="peak_rel", what="%s first peak" % what, value=v, tol=lim, status=st,
                         why=why, extra="%.6g %s / %.6g %s" % (a["peak"], unit, b["peak"], unit)))
        d = abs(a["peak_time"] - b["peak_time"])
        lim, st, why = judge(d, "arrival_abs")
        rows.append(dict(pair=pair, quantity="arrival_abs", what="%s first-peak time" % what, value=d, tol=lim,
                         status=st, why=why, extra="%.7g s / %.7g s" % (a["peak_time"], b["peak_time"])))

    for c in codes:
        if c not in measures and not (c in velocity_measures and pulse_field(case, traces[c]) == "velocity"):
            rows.append(dict(pair=c, quantity="ruler", what="granwave analyze --json", value=None, tol=None,
                             status="FAIL", why="the ruler could not measure this trace: first peaks, arrival "
                             "times and speeds are not compared (see the code's detail)"))
    for ca, cb in pairs_of([c for c in codes if c in CODES], {t: m for t, m in (twins or {}).items() if t in traces}):
        pair = "%s-%s" % (ca, cb)
        cur["pair"] = pair
        cur["convention"] = convention_difference(case, traces[ca], traces[cb])
        field = pulse_field(case, traces[ca], traces[cb])
        cur["field"] = None
        if field == "velocity":
            why = next((str(t["attrs"].get("layer_stress", "")) for t in (traces[ca], traces[cb])
                        if stress_path(case) not in t), "")
            cur["field"] = "judged on the layer velocity, one trace has no %s (%s)" % (
                stress_path(case).rsplit("/", 1)[1], why or "not recorded")
        sa, sb = traces_for(traces[ca], case, field), traces_for(traces[cb], case, field)
        for label in sa:
            if label not in sb:
                continue
            ta, ya = sa[label]
            tb, yb = sb[label]
            ia, ib = C.common_grid(ta, tb)
            if len(ia) < 3:
                rows.append(dict(pair=pair, quantity="trace", what=label, value=None, tol=None, status="FAIL",
                                 why="no common sample times (different output intervals?)"))
                continue
            m = C.trace_metrics(ya[ia], yb[ib])
            for q, key in (("trace_max_rel", "max_rel"), ("trace_l2_rel", "l2_rel")):
                lim, st, why = judge(m[key], q)
                rows.append(dict(pair=pair, quantity=q, what=label, value=m[key], tol=lim, status=st, why=why,
                                 extra="max |diff| = %.3g, peak = %.4g" % (m["max_abs"], m["peak"])))
        pick = velocity_measures if field == "velocity" else measures
        ma, mb = pick.get(ca), pick.get(cb)
        if not ma or not mb:
            continue
        if model == "chain":
            ka, kb = ma["contacts"], mb["contacts"]
            for j in sorted(set(ka) & set(kb)):
                if j not in C.choose_contacts(len(traces[ca]["/chain/contact_force"][0]),
                                              str(traces[ca].get("system_attrs", {}).get("wall", "free")) != "free"):
                    continue
                peak_rows("contact %d" % j, ka[j], kb[j], "N")
            spd = [("front_speed", "front speed (contacts/s, first-peak times)")]
        else:
            la, lb = ma["layers"], mb["layers"]
            spd = [("speed_peak", "front speed from first-peak times (m/s)"),
                   ("speed_half", "front speed from half-peak crossings (m/s)")]
            for k in layer_choice(traces[ca], len(traces[ca]["/crystal/layer_z"])):
                if k in la and k in lb:
                    peak_rows("layer %d" % k, la[k], lb[k], "m/s" if field == "velocity" else "Pa")
        for key, what in spd:
            va, vb = ma.get(key), mb.get(key)
            v = C.rel_diff(va, vb) if (va is not None and vb is not None) else None
            lim, st, why = judge(v, "speed_rel")
            rows.append(dict(pair=pair, quantity="speed_rel", what=what, value=v, tol=lim, status=st, why=why,
                             extra="%s / %s" % (("%.6g" % va) if va else "-", ("%.6g" % vb) if vb else "-")))
    return rows
