"""Judging an impact case (crosscheck --suite contact): each code's rebound against the closed forms
(Hertz, Coulomb's rigid-body rebound well inside gross sliding, T7's kept spins), psi2 against Mindlin's
compliance (Maw, Barber & Fawcett), and each code against granwave or granwave's convention twin; the rows
carry their tolerance (tolerances.toml [default.impact]) and status."""
from __future__ import annotations

from . import conventions as CV
from . import runners as RN

# (quantity, the analyze key, the closed form's key path, how the deviation is taken, unit)
HERTZ = (("peak_force", "peak_force", ("hertz", "peak_force"), "rel", "N"),
         ("peak_overlap", "peak_overlap", ("hertz", "peak_overlap"), "rel", "m"),
         ("contact_time", "contact_time", ("hertz", "contact_time"), "rel", "s"))
RESTITUTION = (("normal_restitution", "normal_restitution", ("restitution",), "abs", ""),)
OBLIQUE = (("tangential_restitution", "tangential_restitution", ("oblique", "tangential_restitution"), "abs", ""),
           ("contact_point_restitution", "contact_point_restitution", ("oblique", "contact_point_restitution"), "abs", ""),
           ("rebound_angle", "rebound_angle_deg", ("oblique", "rebound_angle_deg"), "abs", "deg"),
           ("spin_after", "spin_after", ("oblique", "spin_after"), "rel", "rad/s"))
COMPARED = HERTZ + RESTITUTION + OBLIQUE   # code against granwave: every measure


def get_path(d: dict, path):
    """d[path[0]][path[1]]..., None where a key is missing (a closed form the theory did not give)."""
    for k in path:
        if d is None:
            return None
        d = d.get(k)
    return d


def oblique(th: dict) -> bool:
    """A tangential motion at the contact (T4-T7): the closed form has Coulomb's rebound."""
    o = th.get("oblique") or {}
    return o.get("tangential_restitution") is not None or o.get("contact_point_restitution") is not None


def gross_sliding(th: dict) -> bool:
    """Coulomb's rigid-body rebound is judged well inside gross sliding only: rigid-body sliding and
    psi1 >= 2 (4 chi - 1), twice Maw, Barber & Fawcett's boundary of sliding throughout an elastic impact.
    Measured (crosscheck --suite contact): nearer the boundary every code, granwave included, leaves the
    rigid-body value by up to 3.6 deg (T6, T7 65 deg: psi1 = 4.3, the dashpot holds the contact at first
    touch), and the contact-point arm's delta/(2R) of the spin grows to 0.23 deg where the rebound angle
    is near 0 (T5 65 deg)."""
    o = th.get("oblique") or {}
    return bool(o.get("sliding")) and o.get("mbf_psi1", 0.0) >= 2.0 * (4.0 * o.get("mbf_chi", 0.0) - 1.0)


def psi(rb: dict, th: dict):
    """(psi1, psi2) of a measured rebound in Maw, Barber & Fawcett's variables: kappa v_ct/(mu v_n), v_n the
    incident normal speed (`granwave theory`'s mbf_kappa; data/impact/README.md)."""
    o = th.get("oblique") or {}
    if "compliance" not in o or not rb.get("in") or not rb.get("out"):
        return None, None
    k = o["mbf_kappa"] / (o["mu"] * rb["in"]["vn"])
    return k * rb["in"]["vct"], k * rb["out"]["vct"]


# The theory's own resolution in psi2 (tests/unit/theory_mbf.cpp: default against a finer integration).
THEORY_RESOLUTION = 2e-4


def mbf_coincide(th: dict, history: str) -> bool:
    """Maw, Barber & Fawcett's Mindlin-Deresiewicz rebound and a simplified Mindlin law coincide past both
    their gross-sliding boundaries (4 chi - 1, and 4 chi - 2/3 for the displacement histories) when the
    normal history is (nearly) elastic; a strong dashpot holds the contact at first touch, which the
    compliances resolve differently (T6, e = 0.5: 0.012 in psi2 for the displacement law at 80 deg), so the
    two theories must also agree to the theory's resolution."""
    o = th["oblique"]
    c = o["compliance"]
    past = o["mbf_psi1"] > max(c["mindlin_deresiewicz"]["sliding_boundary"], c[history]["sliding_boundary"])
    return past and abs(c["mindlin_deresiewicz"]["psi2"] - c[history]["psi2"]) <= THEORY_RESOLUTION


def mbf_rows(code: str, rb: dict, th: dict, case: dict, tol: dict, attrs: dict) -> list:
    """psi2 against the theory of the code's own tangential history (judged everywhere) and against Maw,
    Barber & Fawcett's Mindlin-Deresiewicz curve (judged where the two models coincide, else its size reported).
    The theory takes the radius as lever arm: a code with the contact point's (R - delta/2) differs by that
    convention (EXPECTED-DIFF, its size reported) and is judged against granwave's twin with its arm."""
    o = th.get("oblique") or {}
    history = attrs.get("tangential_history", "displacement")
    p1, p2 = psi(rb, th)
    if p2 is None or history not in o["compliance"]:
        return []
    name = case["case"]["name"]
    arm = attrs.get("lever_arm", "radius")
    other_arm = None if arm == "radius" else (
        "EXPECTED-DIFF", "the theory's lever arm is R; this code's is the contact point's R - delta/2 (delta/(2R) = "
        "%.2g): judged against granwave's twin with that arm instead" % (th["hertz"]["peak_overlap"] / (
            2.0 * th["effective_radius"])))
    rows = []
    own = o["compliance"][history]["psi2"]
    lim, why = _tol(tol, name, "theory_psi2_law")
    st, why = _status(abs(p2 - own), lim, why, other_arm)
    rows.append(dict(code=code, reference="Mindlin law (%s)" % history, quantity="psi2", measured=p2, expected=own,
                     how="abs", unit="", dev=abs(p2 - own), tol=lim, status=st, why=why))
    md = o["compliance"]["mindlin_deresiewicz"]["psi2"]
    lim, why = _tol(tol, name, "theory_psi2_mbf")
    st, why = _status(abs(p2 - md), lim, why, other_arm if mbf_coincide(th, history) else (
        "INFO", "MBF's Mindlin-Deresiewicz curve and the %s law differ here (psi1 = %.4g; boundaries 4 chi - 1 = %.4g, "
        "the law's %.4g; or a dashpot's stick at first touch): the simplified law keeps no slip-annulus memory; "
        "the difference is the law's, reported" % (history, o["mbf_psi1"], o["mbf_sliding_boundary"],
                                                   o["compliance"][history]["sliding_boundary"])))
    rows.append(dict(code=code, reference="MBF (Mindlin-Deresiewicz)", quantity="psi2", measured=p2, expected=md,
                     how="abs", unit="", dev=abs(p2 - md), tol=lim, status=st, why=why))
    return rows


def rolling_rows(code: str, rb: dict, th: dict, case: dict, tol: dict) -> list:
    """T7: spins whose contact points move together come out unchanged (no tangential force)."""
    r = th.get("rolling")
    if not r:
        return []
    rows = []
    for q, key in (("spin_after", "spin_after"), ("spin_after", "spin2_after")):
        v, ref = rb.get(key), r.get(key)
        d = deviation(v, ref, "rel")
        lim, why = _tol(tol, case["case"]["name"], "theory_spin_after")
        st, why = _status(d, lim, why)
        rows.append(dict(code=code, reference="closed form", quantity=key, measured=v, expected=ref, how="rel",
                         unit="rad/s", dev=d, tol=lim, status=st, why=why))
    return rows


def deviation(a, b, how: str):
    if a is None or b is None:
        return None
    if how == "rel":
        return abs(a - b) / abs(b) if b != 0 else abs(a - b)
    return abs(a - b)


def _tol(tol: dict, case_name: str, key: str):
    return RN.tolerance(tol, "impact", case_name, key)


def _status(d, lim, why, override=None):
    """(status, reason) of a deviation d against tolerance lim; override: (status, reason) that applies."""
    if override:
        return override
    if lim is None:
        return "INFO", why
    if d is None:
        return "FAIL", why
    return ("PASS" if d <= lim else "FAIL"), why


def theory_rows(code: str, rb: dict, th: dict, case: dict, tol: dict, attrs: dict | None = None) -> list:
    """The code's deviations from the closed forms that apply to this case; attrs: its trace's attributes
    (tangential_history: whose Mindlin law's rebound it is judged against; lever_arm)."""
    rows = []
    elastic = float(case.get("contact", {}).get("restitution", 1.0)) == 1.0 and float(
        case.get("contact", {}).get("damping_ratio", 0.0)) == 0.0
    quantities = (HERTZ if elastic and not oblique(th) else ()) + RESTITUTION + (OBLIQUE if oblique(th) else ())
    for q, key, path, how, unit in quantities:
        v, ref = rb.get(key), get_path(th, path)
        if ref is None:
            continue        # no closed form of this measure here (T6, T7: no centre velocity along the wall)
        d = deviation(v, ref, how)
        lim, why = _tol(tol, case["case"]["name"], "theory_" + q)
        stick = q in dict((o[0], 1) for o in OBLIQUE) and not gross_sliding(th)
        st, why = _status(d, lim, why, ("INFO", "not well inside gross sliding (psi1 < 2 (4 chi - 1)): Coulomb's "
                                            "rigid-body value does not hold where Mindlin's compliance (and a dashpot's "
                                            "stick at first touch) acts; judged by psi2 against Mindlin's compliance")
                          if stick else None)
        rows.append(dict(code=code, reference="closed form", quantity=q, measured=v, expected=ref, how=how, unit=unit,
                         dev=d, tol=lim, status=st, why=why))
    return rows + rolling_rows(code, rb, th, case, tol) + mbf_rows(code, rb, th, case, tol, attrs or {})


def code_rows(code: str, ref_name: str, rb: dict, rb_ref: dict, case: dict, tol: dict, convention: str | None) -> list:
    rows = []
    for q, key, _, how, unit in COMPARED:
        v, ref = rb.get(key), rb_ref.get(key)
        if v is None and ref is None:
            continue
        d = deviation(v, ref, how)
        lim, why = _tol(tol, case["case"]["name"], "code_" + q)
        st, why = _status(d, lim, why, ("EXPECTED-DIFF", convention) if convention else None)
        rows.append(dict(code=code, reference=ref_name, quantity=q, measured=v, expected=ref, how=how, unit=unit,
                         dev=d, tol=lim, status=st, why=why))
    return rows


def judge_case(case: dict, th: dict, runs: dict, rebounds: dict, attrs: dict, tol: dict) -> list:
    rows = []
    for code, rb in rebounds.items():
        rows += theory_rows(code, rb, th, case, tol, attrs.get(code, {}))
    if "granwave" not in rebounds:
        return rows
    twin_of = {m: name for name, r in runs.items() for m in (r.get("twin_of") or []) if name in rebounds}
    for code, rb in rebounds.items():
        if code == "granwave" or CV.TWIN_SEP in code:
            continue
        conv = CV.difference(case, attrs.get(code, {}), attrs.get("granwave", {}))
        rows += code_rows(code, "granwave", rb, rebounds["granwave"], case, tol, conv)
        if code in twin_of:
            rows += code_rows(code, twin_of[code], rb, rebounds[twin_of[code]], case, tol, None)
    return rows
