"""Contact-law conventions a trace records (root attributes, data/SCHEMA.md §3) and what follows for
the comparison: a pair of traces that ran different conventions where they matter for the case is
a convention difference (EXPECTED-DIFF, never judged), and granwave, which can run every one of
them, runs the case again with the other code's conventions (a "twin", `granwave~<code>`) so that
the code is still judged against granwave.

Defaults of a trace without the attribute: the case's value (traces.contact_params).
"""
from __future__ import annotations

from . import laws as L
from . import sweepmath as M
from . import traces as T
from .codefacts import resistance_on, rolling_on

TWIN_SEP = "~"


def tangential(c: dict) -> bool:
    return L.law_of(c).tangential(c)


def dashpot(c: dict) -> bool:
    return L.law_of(c).dashpot(c)


# (attribute, when it matters for the case's contact parameters, why the codes differ)
CONVENTIONS = (
    ("contact_law", lambda c: True,
     "The traces ran different contact laws (linear spring-dashpot or Hertz-Mindlin): not comparable."),
    ("lever_arm", tangential,
     "Seed 002 eq. (4) takes the radius a (granwave's default, LAMMPS' gran/hooke/history and gran/hertz/history); "
     "YADE and LIGGGHTS always take the contact point a - delta/2 (S speeds then differ by 1e-5 .. 2e-4); LAMMPS' "
     "pair granular takes a in the surface velocity and a - delta/2 in the torque "
     "(\"radius_velocity_contact_point_torque\"), which granwave does not run. granwave runs the other two: "
     "[contact] lever_arm."),
    ("normal_tension", dashpot,
     "YADE's damped laws (ViscEl; Mindlin with betan) clip a pulling dashpot and cannot run \"allow\"; LAMMPS' "
     "gran/hooke/history cannot clip. The difference shows where contacts open under a dashpot. granwave runs "
     "either: [contact] normal_tension."),
    ("coulomb_normal",
     lambda c: tangential(c) and dashpot(c) and c["normal_tension"] == "allow",
     "granwave's default Coulomb limit is mu max(f_n, 0); LIGGGHTS, YADE and LAMMPS take mu |f_n|: they differ "
     "where a dashpot makes f_n pull. granwave runs either: [contact] coulomb_normal."),
    ("tangential_history",
     lambda c: L.law_of(c).CHOOSES_TANGENTIAL_HISTORY and tangential(c),
     "Hertz-Mindlin's tangential spring k_t(delta) = 8 G* sqrt(R* delta) changes with the overlap: LIGGGHTS and "
     "LAMMPS' mindlin keep the displacement (f_t = -k_t(delta) xi, \"displacement\"), YADE's Mindlin law and "
     "LAMMPS' mindlin/force the force (incremental, \"force\"), LAMMPS' mindlin_rescale scales xi by "
     "a/a_prev on unloading (\"displacement_rescale\"), measured by crosscheck/probe_hertz_mindlin.py. "
     "granwave runs each: [contact] tangential_history."),
    # Luding's rolling and torsion resistance (issue #28; MAPPING.md "Rolling and torsion resistance")
    ("rolling_lever", resistance_on,
     "The lever a' = arm_i arm_j/(arm_i + arm_j) of the rolling and torsion springs: YADE, LIGGGHTS and LAMMPS take "
     "the radii (R*), granwave by default the tangential lever arm's arms, a - delta/2 with lever_arm = "
     "\"contact_point\" (the angular springs then differ by about delta/a'). granwave runs either: [contact] "
     "rolling_lever."),
    ("rolling_history", rolling_on,
     "The rolling spring: granwave and LAMMPS' sds turn it into the current tangent plane keeping its length "
     "(\"rotated\"); LIGGGHTS' rolling_friction luding keeps its torque history fixed in space (\"fixed\"; after a "
     "rigid turn phi its torque misses the turned one by 2 sin(phi/2), measured). granwave runs either: [contact] "
     "rolling_history."),
)

# The values granwave can run (a twin is made only from these); a trace recording another value is
# reported as a convention difference and not judged against granwave.
GRANWAVE_RUNS = dict(lever_arm=("radius", "contact_point"), normal_tension=("allow", "clip"),
                     coulomb_normal=("compressive", "magnitude"),
                     tangential_history=("displacement", "displacement_rescale", "force"),
                     rolling_lever=("lever_arm", "radii"), rolling_history=("rotated", "fixed"))


MODELS = ("crystal", "impact")   # the models whose traces record their conventions


def _params(case: dict) -> dict:
    c = T.contact_params(case)
    c.update({k: float(c[k]) for k in ("kt", "gamma_t", "gamma_n", "damping_ratio") if k in c})  # the law's own
    c["contact_law"] = c["law"]
    if case.get("case", {}).get("model") == "impact":
        # an impact's dashpot is set by `restitution` (SCHEMA §7.1); mu = 0 or a head-on impact without
        # spin: no tangential force at all
        if float(c.get("restitution", 1.0)) < 1.0:
            c["damping_ratio"] = max(c.get("damping_ratio", 0.0), 1.0)
        from .impact import tangential_motion
        if float(c["mu_static"]) == 0.0 or not tangential_motion(case):
            c["tangential"] = "none"
    return c


def _value(key: str, attrs: dict, c: dict):
    """The trace's value of a convention (the case's without the attribute), one name per law: a rolling
    lever on the arms of lever_arm = "radius" is the radii's."""
    v = attrs.get(key, c[key])
    if key == "rolling_lever" and v == "lever_arm" and attrs.get("lever_arm", c["lever_arm"]) == "radius":
        return "radii"
    return v


def _matters(case: dict, *attrs: dict) -> list:
    """The conventions that matter for the case run as these traces ran it: the Coulomb rule under
    tension matters when one of them let the dashpot pull (normal_tension recorded "allow")."""
    c = _params(case)
    if any(a.get("normal_tension", c["normal_tension"]) == "allow" for a in attrs):
        c["normal_tension"] = "allow"
    return [(key, why) for key, matters, why in CONVENTIONS if matters(c)]


def recorded(case: dict, attrs: dict) -> dict:
    """{attribute: value} of the conventions that matter for this case as this trace ran it."""
    if case.get("case", {}).get("model") not in MODELS:
        return {}
    c = _params(case)
    return {key: _value(key, attrs, c) for key, _ in _matters(case, attrs)}


def difference(case: dict, attrs_a: dict, attrs_b: dict) -> str | None:
    """The conventions two traces record differently where they matter for this case (no tolerance
    may cover one), as a reason; None if the two runs used the same conventions. A trace without
    the attribute ran the case's value."""
    if case.get("case", {}).get("model") not in MODELS:
        return None
    c = _params(case)
    out = []
    for key, why in _matters(case, attrs_a, attrs_b):
        va, vb = _value(key, attrs_a, c), _value(key, attrs_b, c)
        if va != vb:
            out.append("%s convention: the traces say %s = %s and %s. %s" % (key.replace("_", "-"), key, va, vb, why))
    return " ".join(out) or None


def twins(case: dict, attrs: dict) -> list:
    """[(name, codes, changes)]: one granwave twin per distinct set of conventions that differs from
    granwave's trace; `changes` are the [contact] values to run, `codes` the codes that recorded them."""
    if "granwave" not in attrs:
        return []
    base = recorded(case, attrs["granwave"])
    out = []
    for code, a in attrs.items():
        if code == "granwave" or TWIN_SEP in code:
            continue
        rec = recorded(case, a)
        if rec == base or rec.get("contact_law") != base.get("contact_law"):
            continue        # the same conventions, or another law: nothing granwave could run for it
        rec = {k: v for k, v in rec.items() if k != "contact_law"}
        if any(v not in GRANWAVE_RUNS.get(k, (v,)) for k, v in rec.items()):
            continue        # a convention granwave does not run: that pair stays a reported difference
        for entry in out:
            if entry[2] == rec:
                entry[1].append(code)
                break
        else:
            out.append(["granwave" + TWIN_SEP + code, [code], rec])
    return [tuple(e) for e in out]


def derive(case_text: str, changes: dict, case_path: str | None = None) -> str:
    """The case text with [contact] KEY = value for each convention; with case_path, a text that will be
    written to another directory (its packing file made absolute: sweepmath.moved_case)."""
    ch = {("contact", k): v for k, v in changes.items()}
    return M.moved_case(case_text, ch, case_path) if case_path else M.derive_case(case_text, ch)
