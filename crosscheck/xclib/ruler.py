"""The ruler: `granwave analyze TRACES --json`, the one implementation of the measures of
docs/design.md §2.4 (src/analysis/measures.hpp), applied identically to every code's trace file.

There is deliberately no second (Python) copy of the measures: a crosscheck that measured each code
with its own ruler could hide a difference of definition. `measure()` runs the analyzer and
translates its JSON (schema "granwave-analyze/1") into the few numbers the harness compares:

chain:   {"kind": "chain", "contacts": {j: {"peak": F, "peak_time": t, "half_arrival": t}},
          "front_speed": contacts/s, "front_speed_err": ..., "front_range": [j0, j1], "striker_peak": F}
crystal: {"kind": "crystal", "component": "zz"|"zx", "layers": {k: {"peak": ..., "peak_time": ...,
          "half_arrival": ...}}, "speed_peak": m/s, "speed_half": m/s, (+ _err), "speed_range": [z0, z1] (z/l0)}
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess


class RulerError(RuntimeError):
    """granwave analyze is missing, failed, or printed something that is not its JSON."""


def granwave_analyze(trace_path: str, granwave: str = "granwave", timeout: float = 300, extra_args=()) -> dict:
    """extra_args: analyze options (e.g. ["--layers", "5:25"]) -- the same for every code's trace."""
    exe = shutil.which(granwave) or (granwave if "/" in granwave and os.path.exists(granwave) else None)
    if not exe:
        raise RulerError("granwave executable not found (%s): the ruler is `granwave analyze --json`" % granwave)
    p = subprocess.run([exe, "analyze", trace_path, "--json", *extra_args], capture_output=True, text=True,
                       timeout=timeout)
    if p.returncode != 0:
        raise RulerError("granwave analyze failed (exit %d): %s" % (p.returncode, p.stderr.strip()[-300:]))
    try:
        raw = json.loads(p.stdout)
    except json.JSONDecodeError as e:
        raise RulerError("granwave analyze printed no JSON: %s" % e) from e
    if raw.get("schema") != "granwave-analyze/1":
        raise RulerError("unexpected analyze schema %r" % raw.get("schema"))
    return raw


def _value(x):
    return None if x is None else x.get("value")


def _error(x):
    return None if x is None else x.get("error")


def _columns(table: dict, index_key: str, arrived_key: str = "arrived") -> dict:
    """Per-row dicts {index: {peak, peak_time, half_arrival}} of the rows whose front arrived."""
    out = {}
    for i, idx in enumerate(table[index_key]):
        if not table[arrived_key][i]:
            continue
        out[int(idx)] = dict(peak=table["peak_value"]["values"][i], peak_time=table["peak_time"]["values"][i],
                             half_arrival=table["half_peak_time"]["values"][i])
    return out


def translate(raw: dict) -> dict:
    """The harness's view of one `granwave analyze --json` document."""
    if raw["model"] == "chain":
        contacts = _columns(raw["contacts"], "contact")
        v = raw.get("v_first_peak_contacts")
        return dict(kind="chain", contacts=contacts, striker_peak=contacts.get(0, {}).get("peak"),
                    front_speed=_value(v), front_speed_err=_error(v),
                    front_range=raw.get("fit_range", {}).get("contacts"), ruler="granwave analyze")
    layers = _columns(raw["layers"], "layer")
    field = raw.get("measure_field", "")
    comp = "zx" if field.endswith("_zx") or field.endswith("velocity_x") else "zz"
    fr = raw.get("fit_range", {})
    return dict(kind="crystal", component=comp, field=field, layers=layers,
                speed_peak=_value(raw.get("v_first_peak")), speed_peak_err=_error(raw.get("v_first_peak")),
                speed_half=_value(raw.get("v_half_peak")), speed_half_err=_error(raw.get("v_half_peak")),
                speed_range=fr.get("z_over_l0"), speed_range_note=fr.get("note", ""), ruler="granwave analyze")


def measure(trace_path: str, granwave: str = "granwave", pulse_field: str = "auto", fit_range=None) -> dict:
    """The one ruler the harness uses (raises RulerError when it cannot measure). pulse_field: the
    field of a crystal's per-layer measures (analyze --pulse-field: auto, stress or velocity); fit_range:
    (lo, hi) z/l0 of the speed fits (analyze --layers; a packing file's free bins, judge.fit_range), or
    None for analyze's own (the seed's z/l0 = 10 .. 150)."""
    extra = () if pulse_field == "auto" else ("--pulse-field", pulse_field)
    if fit_range is not None:
        extra += ("--layers", "%.17g:%.17g" % tuple(fit_range))
    raw = granwave_analyze(trace_path, granwave, extra_args=extra)
    res = translate(raw)
    res["granwave_analyze"] = raw
    return res
