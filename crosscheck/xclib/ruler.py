"""The ruler: the measures of DESIGN.md §2.4 applied to one trace file, identically for every code.

`measure(trace_path, trace)` is the one function the harness calls. Today it uses `python_ruler`
(a transcription of DESIGN §2.4, the same definitions as src/analysis/measures.hpp); when
`granwave analyze TRACES --json` exists and prints the keys below, `granwave_ruler` takes over
(set `RULER = "granwave"` or pass --ruler granwave). Keys returned:

chain:   {"kind": "chain", "contacts": {j: {"peak": F, "peak_time": t, "half_arrival": t}},
          "front_speed": contacts/s, "front_speed_err": ..., "front_range": [j0, j1], "striker_peak": F}
crystal: {"kind": "crystal", "component": "zz"|"zx", "layers": {k: {"peak": ..., "peak_time": ...,
          "half_arrival": ...}}, "speed_peak": m/s, "speed_half": m/s, (+ _err), "speed_range": [k0, k1]}
"""
from __future__ import annotations

import json
import shutil
import subprocess

import numpy as np

RULER = "python"


# ------------------------------------------------------------------ DESIGN §2.4, in numpy
def first_peak(t, y, frac=0.3):
    y = np.asarray(y, float)
    t = np.asarray(t, float)
    if y.size < 3:
        return None
    ymax = float(np.max(y))
    if ymax <= 0:
        return None
    above = np.nonzero(y >= frac * ymax)[0]
    k = int(above[0])
    while k + 1 < y.size and y[k + 1] >= y[k]:
        k += 1
    if k == 0 or k == y.size - 1:
        return dict(time=float(t[k]), value=float(y[k]), index=k)
    y0, y1, y2 = y[k - 1], y[k], y[k + 1]
    den = y0 - 2 * y1 + y2
    s = 0.5 * (y0 - y2) / den if den != 0 else 0.0
    h = t[k + 1] - t[k]
    return dict(time=float(t[k] + s * h), value=float(y1 - 0.25 * (y0 - y2) * s), index=k)


def first_crossing(t, y, level, start=0):
    y = np.asarray(y, float)
    for k in range(max(start, 1), y.size):
        if y[k - 1] < level <= y[k]:
            return float(t[k - 1] + (level - y[k - 1]) / (y[k] - y[k - 1]) * (t[k] - t[k - 1]))
    return None


def fit_line(x, y):
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    n = x.size
    if n < 2:
        return None
    A = np.vstack([x, np.ones(n)]).T
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    slope, icpt = float(coef[0]), float(coef[1])
    err = 0.0
    if n > 2:
        res = y - (slope * x + icpt)
        s2 = float(res @ res) / (n - 2)
        sxx = float(np.sum((x - x.mean()) ** 2))
        err = (s2 / sxx) ** 0.5 if sxx > 0 else 0.0
    return slope, err


def signal_measures(t, y):
    p = first_peak(t, y)
    if p is None or p["index"] >= len(y) - 2:
        return None          # no peak inside the window (the front has not arrived and passed yet)
    return dict(peak=p["value"], peak_time=p["time"], half_arrival=first_crossing(t, y, 0.5 * p["value"]))


def python_ruler(trace: dict) -> dict:
    t = trace["time"]
    if "/chain/contact_force" in trace:
        cf = trace["/chain/contact_force"]
        n = cf.shape[1]
        contacts = {}
        for j in range(n):
            m = signal_measures(t, cf[:, j] - cf[0, j])
            if m:
                contacts[j] = m
        sa = trace.get("system_attrs", {})
        nbb = n - (0 if str(sa.get("wall", "free")) == "free" else 1)
        j0, j1 = 5, max(6, nbb - 6)
        js = [j for j in range(j0, j1 + 1) if j in contacts]
        fit = fit_line([contacts[j]["peak_time"] for j in js], js) if len(js) >= 3 else None
        return dict(kind="chain", contacts=contacts, striker_peak=contacts.get(0, {}).get("peak"),
                    front_speed=fit[0] if fit else None, front_speed_err=fit[1] if fit else None,
                    front_range=[j0, j1])
    # crystal
    sa = trace.get("system_attrs", {})
    comp = "zz"
    try:
        import tomllib
        ex = tomllib.loads(trace["attrs"].get("case_toml", "")).get("excitation", {})
        comp = "zx" if ex.get("mode", "P") == "S" else "zz"
    except Exception:
        pass
    s = trace["/crystal/layer_stress_" + comp]
    s = s - s[0]
    if comp == "zx":
        # a shear front may arrive with either sign: orient each layer by its first large excursion
        for k in range(s.shape[1]):
            a = np.abs(s[:, k])
            if a.max() > 0:
                first = int(np.nonzero(a >= 0.3 * a.max())[0][0])
                if s[first, k] < 0:
                    s[:, k] = -s[:, k]
    z = trace["/crystal/layer_z"]
    nf = int(sa.get("fixed_layers", 2))
    nl = s.shape[1]
    layers = {}
    for k in range(nf, nl - nf):
        m = signal_measures(t, s[:, k])
        if m:
            layers[k] = m
    # speeds over layers 10 .. the last free layer but 5 (reflections from the top end)
    k0, k1 = nf + 10 - 1 if nl > 40 else nf + 3, nl - nf - 6
    ks = [k for k in range(k0, k1 + 1) if k in layers and layers[k]["half_arrival"] is not None]
    out = dict(kind="crystal", component=comp, layers=layers, speed_range=[k0, k1])
    for key, name in (("peak_time", "speed_peak"), ("half_arrival", "speed_half")):
        fit = fit_line([layers[k][key] for k in ks], [z[k] for k in ks]) if len(ks) >= 3 else None
        out[name] = fit[0] if fit else None
        out[name + "_err"] = fit[1] if fit else None
    return out


def granwave_ruler(trace_path: str, granwave: str = "granwave", timeout: float = 120) -> dict | None:
    """`granwave analyze TRACES --json`, raw; None when unavailable or failing."""
    exe = shutil.which(granwave) or (granwave if "/" in granwave else None)
    if not exe:
        return None
    try:
        p = subprocess.run([exe, "analyze", trace_path, "--json"], capture_output=True, text=True, timeout=timeout)
    except Exception:
        return None
    if p.returncode != 0:
        return None
    try:
        return json.loads(p.stdout)
    except json.JSONDecodeError:
        return None


def measure(trace_path: str, trace: dict, ruler: str | None = None, granwave: str = "granwave") -> dict:
    """The one ruler the harness uses. The Python transcription gives the compared numbers; the
    raw `granwave analyze --json` output is attached under "granwave_analyze" when it runs, and
    replaces them when ruler == "granwave" and its JSON carries the keys documented above."""
    res = python_ruler(trace)
    raw = granwave_ruler(trace_path, granwave)
    if raw is not None:
        res["granwave_analyze"] = raw
        if (ruler or RULER) == "granwave" and isinstance(raw, dict) and raw.get("kind") == res["kind"]:
            res.update({k: v for k, v in raw.items() if k in res})
            res["ruler"] = "granwave analyze"
    res.setdefault("ruler", "python transcription of DESIGN §2.4")
    return res
