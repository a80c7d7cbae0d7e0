"""crosscheck sweep damping|friction: one parameter over a range, every code, one ruler.

    crosscheck/crosscheck sweep damping  [--size small|paper] [--codes ...] [--report DIR [--resume]]
    crosscheck/crosscheck sweep friction [--size small|paper] [--modes P,S] [--codes ...] [--report DIR [--resume]]
    crosscheck/crosscheck sweep rolling  [--size small|paper] [--modes S,P] [--codes ...] [--report DIR [--resume]]

damping:  first-peak amplitude (ruler: `granwave analyze --json`) at five z/l0 positions over
          gamma_0 = 0, 0.025, 0.05, 0.1, 0.2 kg/s (seed 002 fig. 3 right), per code; relative
          differences per pair of codes; a PNG of amplitude against position, one panel per gamma_0.
friction: P and S front speeds (first peak and half peak) over kt/k = 0, 0.2, 0.5, 1, 1.5, 2 with
          mu = 0.5 (seed 002 fig. 6), per code and pair; `granwave theory --json` V_pz, V_sz (eq. 10,
          affine kt term) as the closed-form line; a PNG of speed against kt/k.
rolling:  Luding's rolling and torsion springs (issue #28) over k_r/k_t = 0.05, 0.1, 0.2, 0.5, 1, 2 with
          k_o = k_r, k_t = k, mu = 0.5, no dashpots (YADE's CohesionMoment has none) and no rolling or
          torsion limit (data/studies/crystal_rolling.toml); S and P: speeds against the lattice's
          long-wave speeds (`granwave theory --json` V_sz_lattice, V_pz_lattice), first peaks at
          z/l0 = 10, 80, 150, the 2D-FFT ridge against the lattice branch and the S zone-edge frequency.

Each point is a case derived from a template (small: tests/crosscheck/cases/crystal_small.toml,
4x4x40; paper: data/cases/crystal_p.toml / crystal_s.toml, 4x4x200) with only the swept keys
changed (sweepmath.derive_case); the derived case files are kept in the report. Every point goes
through the crosscheck harness's own steps (runners: granwave build, each code in a fresh directory,
granwave's convention twins, the ruler), so a sweep point is exactly a `crosscheck run` of that case,
and with --resume a sweep finishes point by point (and code by code) in its report directory.
Pairs are judged against [sweep.<name>] in tolerances.toml (measured values, each with its reason)
on the points where their two codes ran the same conventions; `expected_pairs` there lists pairs
reported as EXPECTED-DIFF (a documented difference, never a pass).
"""
from __future__ import annotations

import datetime as _dt
import json
import math
import os
import subprocess
import sys
import time
import tomllib

from . import conventions as CV
from . import ruler as R
from . import runners as RN
from . import sweepmath as M
from . import traces as T

GAMMAS = (0.0, 0.025, 0.05, 0.1, 0.2)
KT_OVER_K = (0.0, 0.2, 0.5, 1.0, 1.5, 2.0)
KR_OVER_KT = (0.05, 0.1, 0.2, 0.5, 1.0, 2.0)
ROLLING_KT_OVER_K = 1.0            # data/studies/crystal_rolling.toml
ROLLING_POSITIONS = {"small": (5, 15, 25), "paper": (10, 80, 150)}
SIZES = {
    # small: 4x4x40; the first peak reaches z/l0 = 25 at ~1.7e-4 s (P) and the top reflection returns
    # there after ~3.9e-4 s, so t_end = 3e-4 s keeps every position's first peak clean.
    "small": dict(template_P="tests/crosscheck/cases/crystal_small.toml", template_S="tests/crosscheck/cases/crystal_small.toml",
                  positions=(5, 10, 15, 20, 25), t_end=3e-4, layers="5:25"),
    # paper: seed 002's 4x4x200 with the seed's positions (fig. 3 right) and its fit range.
    "paper": dict(template_P="data/cases/crystal_p.toml", template_S="data/cases/crystal_s.toml",
                  positions=(10, 45, 80, 115, 150), t_end=None, layers=None),
}


def _log(msg):
    print("sweep: " + msg, file=sys.stderr, flush=True)


def make_case(template_path: str, name: str, changes: dict, out_dir: str) -> str:
    with open(template_path) as f:
        text = f.read()
    ch = {("case", "name"): name}
    ch.update(changes)
    path = os.path.join(out_dir, name + ".toml")
    with open(path, "w") as f:
        f.write("# derived by crosscheck sweep from %s\n" % os.path.relpath(template_path, RN.REPO)
                + M.derive_case(text, ch))
    return path


def run_point(case_path: str, casedir: str, codes, granwave, timeout, fixture, ruler_args, resume=False) -> dict:
    """One case through the harness steps (runners.run_codes: each code, then granwave's convention
    twins); returns {name: {"status", "wall_s", "detail", "attrs", "raw", ["twin_of"]}}."""
    try:
        system, _ = RN.build_system(case_path, casedir, granwave, fixture, timeout, resume)
    except Exception as e:  # noqa: BLE001 -- a point that cannot be built is a row, not a crash
        _log("%s: system not built: %s" % (os.path.basename(case_path), e))
        return {code: dict(status="failed", wall_s=None, detail="system not built: %s" % e) for code in codes}

    def log(msg):
        _log("%s: %s" % (os.path.basename(case_path), msg))

    runs = RN.run_codes(case_path, system, casedir, codes, timeout, granwave, resume, log)
    return {code: _record(r, granwave, ruler_args) for code, r in runs.items()}


def _record(r: dict, granwave, ruler_args) -> dict:
    """A sweep point's row of one run: status, time, its conventions and the ruler's JSON ("raw")."""
    rec = dict(status=r["status"], wall_s=r.get("wall_s"), detail=r.get("detail", ""))
    if r.get("twin_of"):
        rec.update(twin_of=r["twin_of"], conventions=r["conventions"])
    if r["status"] == "ok":
        try:
            rec["attrs"] = {k: v for k, v in T.read_trace(r["trace"])["attrs"].items()
                            if k in CV.GRANWAVE_RUNS}
            rec["raw"] = R.granwave_analyze(r["trace"], granwave or "granwave", extra_args=ruler_args)
            rec["pulse_field"] = rec["raw"].get("measure_field")   # the field the ruler measured
        except R.RulerError as e:
            rec["status"], rec["detail"] = "failed", "not measurable: %s" % e
    return rec


def point_pairs(case_path: str, runs: dict) -> dict:
    """{(a, b): None (judged) or the convention difference (not judged)} at one sweep point: every
    pair of codes that ran, and each twin with the codes it stands for."""
    case, _ = T.load_case(case_path)
    ok = {c: r for c, r in runs.items() if r.get("status") == "ok"}
    twins = {c: r["twin_of"] for c, r in ok.items() if r.get("twin_of")}
    out = {}
    for a, b in pairs_all([c for c in ok if c in RN.CODES], twins):
        out[(a, b)] = CV.difference(case, ok[a].get("attrs", {}), ok[b].get("attrs", {}))
    return out


def pairs_all(codes, twins) -> list:
    cs = [c for c in RN.CODES if c in codes]
    out = [(cs[i], cs[j]) for i in range(len(cs)) for j in range(i + 1, len(cs))]
    for t, members in twins.items():
        out += [(t, m) for m in members if m in cs]
    return out


def columns_of(points, codes) -> tuple:
    """(columns, pairs) of a sweep's tables: the codes, then the twins that ran at any point; every pair
    of codes, then each twin with its codes."""
    twins = {}
    for p in points:
        for c, r in p["runs"].items():
            if r.get("twin_of"):
                twins.setdefault(c, [])
                twins[c] += [m for m in r["twin_of"] if m not in twins[c]]
    return list(codes) + sorted(twins), pairs_all(codes, twins)


def judge_pairs(points, pairs, value_sets, lim, tsec, quantity):
    """Verdict rows (pair, quantity, worst, tolerance, status, note) over the sweep. value_sets(p)
    yields {code: value} dicts of one point (one per position or speed kind). A pair is judged on
    the points where both ran the same conventions; at the others it is EXPECTED-DIFF (the reason
    is in the note)."""
    rows = []
    for a, b in pairs:
        name = "%s-%s" % (a, b)
        judged, conv, why = [], [], ""
        for p in points:
            st = p.get("pairs", {}).get("%s-%s" % (a, b), "absent")
            if st == "absent":
                continue
            vals = [M.pairwise({a: v.get(a), b: v.get(b)}, [a, b]).get(name) for v in value_sets(p)]
            (conv if st else judged).extend(vals)
            why = why or (st or "")
        if not judged and not conv:
            continue
        if judged:
            w = M.worst(judged)
            wc = M.worst(conv)
            note = ("%d values with a convention difference not judged (largest %s)"
                    % (len(conv), "-" if wc is None else "%.2g" % wc)) if conv else ""
            rows.append((name, quantity, w, lim, judge(w, lim, name, tsec), note))
        else:
            rows.append((name, quantity, M.worst(conv), lim, "EXPECTED-DIFF", why[:300]))
    return rows


def theory_speeds(case_path: str, granwave: str | None):
    """(V_pz, V_sz) of `granwave theory --json` (None when granwave is missing or fails)."""
    if not granwave:
        return None, None
    try:
        p = subprocess.run([granwave, "theory", case_path, "--json"], capture_output=True, text=True, timeout=300)
        d = json.loads(p.stdout)
        return float(d["V_pz"]["value"]), float(d["V_sz"]["value"])
    except Exception:  # noqa: BLE001 -- the line is optional
        return None, None


def sweep_tolerances(tol: dict, name: str) -> dict:
    return tol.get("sweep", {}).get(name, {})


def judge(value, lim, pair, tsec):
    if pair in tsec.get("expected_pairs", []):
        return "EXPECTED-DIFF"
    if lim is None:
        return "INFO"
    if value is None:
        return "FAIL"
    return "PASS" if value <= lim else "FAIL"


def _sweep_point(a, report_dir, name, template, ch, size, codes, granwave, ruler_args):
    """(case path, results) of one point: the template with the changes `ch` (and the size's t_end), run by
    every code in its own directory (resumable)."""
    if size["t_end"]:
        ch[("integrator", "t_end")] = size["t_end"]
    casedir = RN.work_dir(os.path.join(report_dir, name), a.resume)
    cp = make_case(template, name, ch, casedir)
    return cp, run_point(cp, casedir, codes, granwave, a.timeout, a.fixture_system, ruler_args, a.resume)


def _report_head(tol, sweep, quantity, title, text):
    """(tolerance section, limit, why, the report's first lines) of a sweep."""
    tsec = sweep_tolerances(tol, sweep)
    return tsec, tsec.get(quantity), tsec.get(quantity + "_why", "no tolerance set"), [title, "", text, ""]


# ------------------------------------------------------------------------------------------ damping
def damping(a, report_dir, granwave, tol) -> int:
    size = SIZES[a.size]
    gammas = _parse_values(a.values, "--values") or list(GAMMAS)
    codes = RN.parse_codes(a.codes)
    ruler_args = ["--layers", size["layers"]] if size["layers"] else []
    points = []
    for g in gammas:
        name = "sweep_damping_%s_g%s" % (a.size, ("%g" % g).replace(".", "p"))
        # normal_tension: "clip", the one convention with a dashpot every code has (SCHEMA.md; LAMMPS: limit_damping)
        ch = {("contact", "gamma_n"): g, ("contact", "kt"): 0.0, ("contact", "normal_tension"): "clip",
              ("excitation", "mode"): "P"}
        cp, res = _sweep_point(a, report_dir, name, RN.repo_path(size["template_P"]), ch, size, codes,
                               granwave, ruler_args)
        peaks = {c: (M.peaks_at(M.layer_table(r["raw"]), size["positions"]) if "raw" in r else {})
                 for c, r in res.items()}
        points.append(dict(gamma=g, case=cp, runs={c: {k: v for k, v in r.items() if k != "raw"} for c, r in res.items()},
                           peaks=peaks, pairs={"%s-%s" % k: v for k, v in point_pairs(cp, res).items()}))
    tsec, lim, why, md = _report_head(
        tol, "damping", "peak_rel", "# crosscheck sweep damping (%s)" % a.size,
        "First-peak amplitude of sigma_zz - sigma_zz(0) (Pa) at z/l0 = %s, P step, kt = 0, over gamma_0 "
        "(kg/s); ruler `granwave analyze --json`%s. d(a-b) = |a - b| / max(|a|, |b|)."
        % (", ".join(map(str, size["positions"])), (" " + " ".join(ruler_args)) if ruler_args else ""))

    cols, pairs = columns_of(points, codes)

    def rows(pts):
        for p in pts:
            for z in size["positions"]:
                yield "%g" % p["gamma"], "%g" % z, {c: p["peaks"].get(c, {}).get(z) for c in cols}

    md += M.sweep_table(points, cols, "gamma_0", "z/l0", rows, pairs) + [""]
    # decay relative to gamma_0 = 0, per code
    if 0.0 in gammas:
        md += ["Amplitude relative to gamma_0 = 0 at the same position (per code):", "",
               "| gamma_0 | z/l0 | " + " | ".join(codes) + " |", "|" + "---|" * (2 + len(codes))]
        ref = next(p for p in points if p["gamma"] == 0.0)
        for p in points:
            for z in size["positions"]:
                vals = []
                for c in codes:
                    v, r0 = p["peaks"].get(c, {}).get(z), ref["peaks"].get(c, {}).get(z)
                    vals.append("%.4f" % (v / r0) if (v is not None and r0) else "-")
                md.append("| %g | %g | %s |" % (p["gamma"], z, " | ".join(vals)))
        md.append("")
    verdict = judge_pairs(points, pairs, lambda p: [{c: p["peaks"].get(c, {}).get(z) for c in cols}
                                                     for z in size["positions"]],
                          lim, tsec, "peak_rel (max over the sweep)")
    verdict += _run_failures(points, cols)
    status = _verdict_md(md, verdict, why, tsec)
    _timings_md(md, points, cols)
    png = os.path.join(report_dir, "damping.png")
    _plot_damping(points, codes, size["positions"], png)
    md += ["![damping](damping.png)", ""]
    _write(report_dir, "sweep_damping", md, dict(sweep="damping", size=a.size, positions=size["positions"], codes=codes,
                                                 points=points, verdict=verdict))
    return status


def _sweep_setup(a, defaults):
    """(size, values, modes, codes, ruler_args) of a sweep over `defaults` (or --values)."""
    size = SIZES[a.size]
    values = _parse_values(a.values, "--values") or list(defaults)
    modes = [m.strip() for m in a.modes.split(",") if m.strip()]
    ruler_args = ["--layers", size["layers"]] if size["layers"] else []
    return size, values, modes, RN.parse_codes(a.codes), ruler_args


def _template(size, mode):
    """(template path, its kn) of a mode's point."""
    tmpl = RN.repo_path(size["template_" + mode])
    with open(tmpl, "rb") as f:
        return tmpl, float(tomllib.load(f)["contact"]["kn"])


# ----------------------------------------------------------------------------------------- friction
def friction(a, report_dir, granwave, tol) -> int:
    size, kts, modes, codes, ruler_args = _sweep_setup(a, KT_OVER_K)
    points = []
    for mode in modes:
        for r in kts:
            name = "sweep_friction_%s_%s_kt%s" % (a.size, mode, ("%g" % r).replace(".", "p"))
            tmpl, kn = _template(size, mode)
            # lever_arm: the contact point, the convention YADE and LIGGGHTS can run (SCHEMA.md); LAMMPS'
            # gran/hooke/history takes the radius and is judged against granwave run with it (a twin).
            ch = {("contact", "kt"): r * kn, ("contact", "gamma_n"): 0.0, ("contact", "mu_static"): 0.5,
                  ("contact", "mu_dynamic"): 0.5, ("contact", "lever_arm"): "contact_point", ("excitation", "mode"): mode}
            cp, res = _sweep_point(a, report_dir, name, tmpl, ch, size, codes, granwave, ruler_args)
            vp, vs = theory_speeds(cp, granwave)
            speeds = {}
            for c, rr in res.items():
                if "raw" in rr:
                    t = R.translate(rr["raw"])
                    speeds[c] = dict(peak=t["speed_peak"], peak_err=t["speed_peak_err"], half=t["speed_half"],
                                     half_err=t["speed_half_err"], range=t["speed_range"])
            points.append(dict(mode=mode, kt_over_k=r, case=cp, theory=vp if mode == "P" else vs,
                               runs={c: {k: v for k, v in rr.items() if k != "raw"} for c, rr in res.items()},
                               speeds=speeds, pairs={"%s-%s" % k: v for k, v in point_pairs(cp, res).items()}))
    tsec, lim, why, md = _report_head(
        tol, "friction", "speed_rel", "# crosscheck sweep friction (%s)" % a.size,
        "Front speeds (m/s; ruler `granwave analyze --json`%s: least squares over the first-peak and the "
        "half-peak arrival times) over kt/k with mu = 0.5, gamma = 0; theory = `granwave theory --json` "
        "(eq. 10 with the affine kt term: V_pz for P, V_sz for S). d(a-b) = |a - b| / max(|a|, |b|)."
        % ((" " + " ".join(ruler_args)) if ruler_args else ""))
    cols, pairs = columns_of(points, codes)
    for which, lab in (("peak", "first-peak speed"), ("half", "half-peak speed")):
        def rows(pts, which=which):
            for p in pts:
                yield "%s %g" % (p["mode"], p["kt_over_k"]), _fmtv(p["theory"]), \
                    {c: p["speeds"].get(c, {}).get(which) for c in cols}
        md += ["### %s" % lab, ""] + M.sweep_table(points, cols, "mode kt/k", "theory", rows, pairs) + [""]
    verdict = []
    for which in ("peak", "half"):
        verdict += judge_pairs(points, pairs, lambda p, which=which: [{c: p["speeds"].get(c, {}).get(which) for c in cols}],
                               lim, tsec, "speed_rel %s (max over the sweep)" % which)
    verdict += _run_failures(points, cols)
    status = _verdict_md(md, verdict, why, tsec)
    _timings_md(md, points, cols)
    png = os.path.join(report_dir, "friction.png")
    _plot_friction(points, codes, modes, png)
    md += ["![friction](friction.png)", ""]
    _write(report_dir, "sweep_friction", md, dict(sweep="friction", size=a.size, codes=codes, points=points,
                                                  verdict=verdict))
    return status


# ------------------------------------------------------------------------------------------ rolling
def lattice_theory(case_path: str, granwave: str | None) -> dict:
    """`granwave theory --json` of a point: the lattice's long-wave speeds (rotations and prestress
    included), its rolling and twisting springs, and the zone-edge frequency of the S (u_x) and P (u_z)
    translation. {} when granwave is missing or the lattice is not available."""
    if not granwave:
        return {}
    try:
        p = subprocess.run([granwave, "theory", case_path, "--json"], capture_output=True, text=True, timeout=300)
        d = json.loads(p.stdout)
        lat = d["lattice"]
        if not lat.get("available"):
            return {}
        out = dict(V_pz=float(d["V_pz_lattice"]["value"]), V_sz=float(d["V_sz_lattice"]["value"]),
                   k_roll=float(lat["k_roll"]["value"]), k_twist=float(lat["k_twist"]["value"]))
        # At k = pi/l0 the translation and the turn decouple: the wave's zone-edge mode is the family's
        # branch (S: u_x with theta_y; P: u_z with theta_z) that ends in a translation, acoustic or not.
        for fam, dofs in (("u_x", ("u_x", "theta_y")), ("u_z", ("u_z", "theta_z"))):
            ends = [(b["translation"][-1], float(b["omega"]["values"][-1])) for b in d["dispersion"]["branches"]
                    if b["dominant"] in dofs]
            if ends:
                out["zone_edge_" + fam] = max(ends)[1]
        for b in d["dispersion"]["branches"]:   # the acoustic S branch's end: the turn's mode while it is below
            if b["dominant"] == "u_x" and b["kind"] == "acoustic":
                out["zone_edge_acoustic_u_x"] = float(b["omega"]["values"][-1])
        return out
    except Exception:  # noqa: BLE001 -- the theory is optional
        return {}


def ridge_of(raw: dict) -> dict:
    """The ruler's 2D-FFT ridge against the case's lattice branch (`long_wave` of `granwave analyze
    --json`) and the ridge's frequency in the last wavenumber bin (k = pi/l0, the zone edge)."""
    lw, d = raw.get("long_wave", {}), raw.get("dispersion", {})
    rg = lw.get("ridge", {})
    om = d.get("omega_max", {}).get("values") or [None]
    return dict(model=lw.get("model"), v_k0=lw.get("value"), scale=rg.get("scale", {}).get("value"),
                columns=rg.get("columns"), with_ridge=rg.get("with_ridge"), within_one_bin=rg.get("within_one_bin"),
                median_offset_bins=rg.get("median_offset_bins"), zone_edge=om[-1],
                domega=d.get("domega", {}).get("value"))


def rolling(a, report_dir, granwave, tol) -> int:
    size, ratios, modes, codes, ruler_args = _sweep_setup(a, KR_OVER_KT)
    # LIGGGHTS' resisted deck records no sigma_zx (pair dumps would turn its rolling spring; MAPPING.md): with it
    # in the sweep, every code's S points are measured on the layer velocity, so that all are measured on one field
    on_velocity = "liggghts" in codes and "S" in modes
    positions = ROLLING_POSITIONS[a.size]
    points = []
    for mode in modes:
        for r in ratios:
            name = "sweep_rolling_%s_%s_kr%s" % (a.size, mode, ("%g" % r).replace(".", "p"))
            tmpl, kn = _template(size, mode)
            kt = ROLLING_KT_OVER_K * kn
            # k_o = k_r (data/studies/crystal_rolling.toml); no dashpot and no limit anywhere (YADE's
            # CohesionMoment has no rolling or twist dashpot); lever_arm: the contact point, as the friction sweep.
            ch = {("contact", "kt"): kt, ("contact", "kr"): r * kt, ("contact", "ko"): r * kt,
                  ("contact", "gamma_n"): 0.0, ("contact", "gamma_t"): 0.0, ("contact", "gamma_r"): 0.0,
                  ("contact", "gamma_o"): 0.0, ("contact", "mu_static"): 0.5, ("contact", "mu_dynamic"): 0.5,
                  ("contact", "lever_arm"): "contact_point", ("excitation", "mode"): mode}
            # YADE's angular springs take the radii: its twin granwave~yade runs rolling_lever = "radii"
            cp, res = _sweep_point(a, report_dir, name, tmpl, ch, size, codes, granwave,
                                   ruler_args + (["--pulse-field", "velocity"] if on_velocity and mode == "S" else []))
            th = lattice_theory(cp, granwave)
            speeds, peaks, ridges = {}, {}, {}
            for c, rr in res.items():
                if "raw" in rr:
                    t = R.translate(rr["raw"])
                    speeds[c] = dict(peak=t["speed_peak"], half=t["speed_half"], range=t["speed_range"])
                    peaks[c] = M.peaks_at(M.layer_table(rr["raw"]), positions)
                    ridges[c] = ridge_of(rr["raw"])
            points.append(dict(mode=mode, kr_over_kt=r, case=cp, theory=th,
                               runs={c: {k: v for k, v in rr.items() if k != "raw"} for c, rr in res.items()},
                               speeds=speeds, peaks=peaks, ridges=ridges,
                               pairs={"%s-%s" % k: v for k, v in point_pairs(cp, res).items()}))
    tsec = sweep_tolerances(tol, "rolling")
    md = ["# crosscheck sweep rolling (%s)" % a.size, "",
          "Luding's rolling and torsion springs over k_r/k_t with k_o = k_r, k_t = k, mu = 0.5, no dashpots and no "
          "rolling or torsion limit (nothing slips), lever_arm = \"contact_point\". Ruler `granwave analyze --json`%s%s; "
          "theory `granwave theory --json` (Bloch waves along z with rotations and the prestress: V_sz_lattice, "
          "V_pz_lattice, the zone-edge frequency of the S / P translation). d(a-b) = |a - b| / max(|a|, |b|)."
          % ((" " + " ".join(ruler_args)) if ruler_args else "",
             " (S points `--pulse-field velocity`: LIGGGHTS' trace has no sigma_zx)" if on_velocity else ""), ""]
    cols, pairs = columns_of(points, codes)

    def theory_v(p):
        return p["theory"].get("V_sz" if p["mode"] == "S" else "V_pz")

    for which, lab in (("peak", "first-peak speed (m/s)"), ("half", "half-peak speed (m/s)")):
        def rows(pts, which=which):
            for p in pts:
                yield "%s %g" % (p["mode"], p["kr_over_kt"]), _fmtv(theory_v(p)), \
                    {c: p["speeds"].get(c, {}).get(which) for c in cols}
        md += ["### %s" % lab, ""] + M.sweep_table(points, cols, "mode kr/kt", "theory", rows, pairs) + [""]
    md += ["### half-peak speed against the lattice's long-wave speed", "",
           "| mode kr/kt | theory (m/s) | " + " | ".join("%s (rel.)" % c for c in cols) + " |",
           "|" + "---|" * (2 + len(cols))]
    for p in points:
        v = theory_v(p)
        md.append("| %s %g | %s | %s |" % (p["mode"], p["kr_over_kt"], _fmtv(v), " | ".join(
            "%+.2e" % (p["speeds"][c]["half"] / v - 1) if (v and p["speeds"].get(c, {}).get("half")) else "-"
            for c in cols)))
    md.append("")

    def peak_rows(pts):
        for p in pts:
            for z in positions:
                yield "%s %g" % (p["mode"], p["kr_over_kt"]), "%g" % z, {c: p["peaks"].get(c, {}).get(z) for c in cols}
    md += ["### first-peak amplitude (%s) at z/l0 = %s" % ("S: layer velocity, m/s; P: Pa" if on_velocity else "Pa",
                                                           ", ".join(map(str, positions))), ""]
    md += M.sweep_table(points, cols, "mode kr/kt", "z/l0", peak_rows, pairs) + [""]
    md += ["### 2D-FFT ridge against the lattice branch, and the zone edge", "",
           "Per code: ridge columns within one frequency bin of the branch / columns with a ridge (the ruler's "
           "`long_wave.ridge`, S only: the P branch is a sine), the median offset in bins, the scale s of "
           "omega_ridge = s omega_branch; the zone edge: seed 002's power-weighted omega_max in the last "
           "wavenumber column (k = pi/l0) against the lattice's zone-edge translation (there the translation and "
           "the turn decouple), in bins of domega. Below k_r/k_t ~ 0.5 a line in the gap between the branches, "
           "the same at every k (a mode held at the fixed layers), pulls the weighted average down; the peak "
           "nearest the translation is compared in tests/physics/sweep_crystal_rolling.cpp.", "",
           "| mode kr/kt | k_roll (N m/rad) | zone-edge translation (1/s) | " + " | ".join(
               "%s: within/with, median, s, zone edge (bins off)" % c for c in cols) + " |",
           "|" + "---|" * (3 + len(cols))]
    for p in points:
        th = p["theory"]
        ze = th.get("zone_edge_u_x" if p["mode"] == "S" else "zone_edge_u_z")
        cells = []
        for c in cols:
            g = p["ridges"].get(c)
            if not g or g.get("within_one_bin") is None:
                cells.append("-" if not g else "%s model" % g.get("model"))
                continue
            off = (g["zone_edge"] - ze) / g["domega"] if (ze and g.get("zone_edge") and g.get("domega")) else None
            cells.append("%d/%d, %.2f, %.5f, %.0f (%s)" % (g["within_one_bin"], g["with_ridge"], g["median_offset_bins"],
                                                          g["scale"], g["zone_edge"], "-" if off is None else "%+.2f" % off))
        md.append("| %s %g | %s | %s | %s |" % (p["mode"], p["kr_over_kt"], _fmtv(th.get("k_roll")), _fmtv(ze),
                                              " | ".join(cells)))
    md.append("")
    verdict = []
    for which in ("peak", "half"):
        verdict += judge_pairs(points, pairs, lambda p, which=which: [{c: p["speeds"].get(c, {}).get(which) for c in cols}],
                               tsec.get("speed_rel"), tsec, "speed_rel %s (max over the sweep)" % which)
    verdict += judge_pairs(points, pairs, lambda p: [{c: p["peaks"].get(c, {}).get(z) for c in cols} for z in positions],
                           tsec.get("peak_rel"), tsec, "peak_rel (max over the sweep)")
    verdict += _run_failures(points, cols)
    why = " ".join("%s: %s" % (q, tsec.get(q + "_why", "no tolerance set")) for q in ("speed_rel", "peak_rel"))
    status = _verdict_md(md, verdict, why, tsec)
    _timings_md(md, points, cols)
    png = os.path.join(report_dir, "rolling.png")
    _plot_rolling(points, codes, modes, positions, png, on_velocity)
    md += ["![rolling](rolling.png)", ""]
    _write(report_dir, "sweep_rolling", md, dict(sweep="rolling", size=a.size, codes=codes, positions=positions,
                                                 points=points, verdict=verdict))
    return status


# ------------------------------------------------------------------------------------------ output
def _fmtv(v):
    return "-" if v is None else "%.5g" % v


def _run_failures(points, codes):
    """A code that failed, crashed or timed out at any point where it ran is a FAIL row (the sweep
    cannot pass). A twin runs only where conventions differ: its absence elsewhere is not a failure."""
    rows = []
    for c in codes:
        bad = [p for p in points if p["runs"].get(c, {}).get("status", "absent" if RN.TWIN_SEP in c else "missing")
               not in ("ok", "absent")]
        if bad:
            r = bad[0]["runs"].get(c, {})
            rows.append((c, "runs not ok: %d of %d (%s)" % (len(bad), len(points), r.get("status", "missing")),
                         None, None, "FAIL", (r.get("detail") or "")[:200]))
    return rows


def _verdict_md(md, verdict, why, tsec) -> int:
    md += ["## Verdict (pairs of codes)", "", "| pair | quantity | worst | tolerance | status | note |",
           "|---|---|---|---|---|---|"]
    for pair, q, w, lim, st, note in verdict:
        md.append("| %s | %s | %s | %s | %s | %s |" % (pair, q, "-" if w is None else "%.3g" % w,
                                                      "-" if lim is None else "%.3g" % lim, st, note.replace("|", "/")))
    md += ["", "Tolerance: %s" % why]
    if tsec.get("expected_pairs"):
        md += ["", "EXPECTED-DIFF pairs: %s" % tsec.get("expected_pairs_why", "")]
    md += ["", "A pair whose two codes ran different contact-law conventions at a point (the traces' lever_arm, "
           "normal_tension, coulomb_normal, tangential_history, rolling_lever, rolling_history) is not judged there; granwave then runs that point again with the other "
           "code's conventions (`granwave~<code>`), which is judged against it."]
    md.append("")
    return 1 if any(v[4] == "FAIL" for v in verdict) else 0


def _timings_md(md, points, codes):
    tot = {c: sum((p["runs"].get(c, {}).get("wall_s") or 0.0) for p in points) for c in codes}
    md += ["Wall time over the sweep (s): " + ", ".join("%s %.1f" % (c, tot[c]) for c in codes), ""]


def _write(report_dir, stem, md, data):
    with open(os.path.join(report_dir, stem + ".md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(report_dir, stem + ".json"), "w") as f:
        json.dump(data, f, indent=1, default=str)


STYLES = {"granwave": ("k", "-", "o"), "yade": ("tab:orange", "--", "s"), "liggghts": ("tab:blue", ":", "^"),
          "lammps": ("tab:red", "-.", "v")}


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _plot_damping(points, codes, positions, path):
    plt = _plt()
    n = len(points)
    fig, axes = plt.subplots(1, n, figsize=(3.2 * n, 3.4), sharey=True, squeeze=False)
    for ax, p in zip(axes[0], points):
        for c in codes:
            col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
            ys = [p["peaks"].get(c, {}).get(z) for z in positions]
            xs = [z for z, y in zip(positions, ys) if y is not None]
            ax.plot(xs, [y for y in ys if y is not None], color=col, ls=ls, marker=mk, ms=5, label=c)
        ax.set_title("gamma_0 = %g kg/s" % p["gamma"], fontsize=9)
        ax.set_xlabel("z / l0")
    axes[0][0].set_ylabel("first-peak sigma_zz - sigma_zz(0) (Pa)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _plot_speeds(ax, pts, codes, xkey, theory_of, theory_label):
    """First-peak (filled) and half-peak (open) speeds of each code against p[xkey], and the theory's line."""
    x = [p[xkey] for p in pts]
    for c in codes:
        col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
        for which, mfc in (("peak", col), ("half", "none")):
            ys = [p["speeds"].get(c, {}).get(which) for p in pts]
            xx = [xi for xi, y in zip(x, ys) if y is not None]
            ax.plot(xx, [y for y in ys if y is not None], color=col, ls=ls, marker=mk, mfc=mfc, ms=6,
                    label="%s (%s)" % (c, "first peak" if which == "peak" else "half peak"))
    th = [(p[xkey], theory_of(p)) for p in pts if theory_of(p) is not None]
    if th:
        ax.plot([t[0] for t in th], [t[1] for t in th], color="tab:green", lw=2, alpha=0.6, label=theory_label)
    ax.set_ylabel("front speed (m/s)")


def _plot_friction(points, codes, modes, path):
    plt = _plt()
    fig, axes = plt.subplots(1, len(modes), figsize=(5.5 * len(modes), 4), squeeze=False)
    for ax, mode in zip(axes[0], modes):
        _plot_speeds(ax, [p for p in points if p["mode"] == mode], codes, "kt_over_k", lambda p: p["theory"],
                     "granwave theory (eq. 10, affine kt)")
        ax.set_title("%s wave" % mode)
        ax.set_xlabel("kt / k")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _plot_rolling(points, codes, modes, positions, path, on_velocity=False):
    """Speeds against k_r/k_t (per mode, with the lattice's long-wave speed), S first peaks against k_r/k_t
    per position (of the layer velocity when `on_velocity`), and the S ridge's zone-edge frequency against
    the branch's."""
    plt = _plt()
    fig, axes = plt.subplots(1, len(modes) + 2, figsize=(4.6 * (len(modes) + 2), 4), squeeze=False)
    axes = axes[0]
    for ax, mode in zip(axes, modes):
        key = "V_sz" if mode == "S" else "V_pz"
        _plot_speeds(ax, [p for p in points if p["mode"] == mode], codes, "kr_over_kt", lambda p: p["theory"].get(key),
                     "lattice long-wave speed")
        ax.set_xscale("log")
        ax.set_title("%s wave" % mode)
        ax.set_xlabel("k_r / k_t")
        ax.legend(fontsize=6)
    mode = "S" if "S" in modes else modes[0]
    pts = [p for p in points if p["mode"] == mode]
    x = [p["kr_over_kt"] for p in pts]
    ax = axes[len(modes)]
    for c in codes:
        col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
        for z in positions:
            ys = [p["peaks"].get(c, {}).get(z) for p in pts]
            xx = [xi for xi, y in zip(x, ys) if y is not None]
            ax.plot(xx, [abs(y) for y in ys if y is not None], color=col, ls=ls, marker=mk, ms=5,
                    label="%s z/l0 = %g" % (c, z))
    ax.set_xscale("log")
    ax.set_title("%s first peak" % mode)
    ax.set_xlabel("k_r / k_t")
    ax.set_ylabel("|first peak| (%s)" % ("layer velocity, m/s" if on_velocity and mode == "S" else "Pa"))
    ax.legend(fontsize=6)
    ax = axes[len(modes) + 1]
    key = "zone_edge_u_x" if mode == "S" else "zone_edge_u_z"
    th = [(p["kr_over_kt"], p["theory"].get(key)) for p in pts if p["theory"].get(key)]
    if th:
        ax.plot([t[0] for t in th], [t[1] for t in th], color="tab:green", lw=2, alpha=0.6,
                label="lattice: zone-edge translation")
    ac = [(p["kr_over_kt"], p["theory"].get("zone_edge_acoustic_u_x")) for p in pts
          if mode == "S" and p["theory"].get("zone_edge_acoustic_u_x")]
    if ac:
        ax.plot([t[0] for t in ac], [t[1] for t in ac], color="tab:purple", lw=1.5, ls="--", alpha=0.7,
                label="lattice: acoustic S branch at pi/l0")
    for c in codes:
        col, ls, mk = STYLES.get(c, ("gray", "-", "x"))
        ys = [p["ridges"].get(c, {}).get("zone_edge") for p in pts]
        xx = [xi for xi, y in zip(x, ys) if y is not None]
        ax.plot(xx, [y for y in ys if y is not None], color=col, ls=ls, marker=mk, ms=5, label=c)
    ax.set_xscale("log")
    ax.set_title("%s ridge at k = pi/l0" % mode)
    ax.set_xlabel("k_r / k_t")
    ax.set_ylabel("omega (1/s)")
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def _parse_values(text: str, option: str):
    """Comma-separated finite numbers >= 0, or None (the defaults); ValueError names the option."""
    if not text:
        return None
    out = []
    for x in text.split(","):
        try:
            v = float(x)
        except ValueError:
            raise ValueError("%s: '%s' is not a number (allowed: comma-separated numbers >= 0)" % (option, x)) from None
        if not math.isfinite(v) or v < 0:
            raise ValueError("%s: %s is outside the allowed range (finite, >= 0)" % (option, x))
        out.append(v)
    return out


def main_sweep(a) -> int:
    try:
        _parse_values(a.values, "--values")
        modes = [m.strip() for m in a.modes.split(",") if m.strip()]
        if not modes or any(m not in ("P", "S") for m in modes):
            raise ValueError("--modes: '%s' (allowed: P, S or P,S)" % a.modes)
        RN.parse_codes(a.codes)
    except ValueError as e:
        print("crosscheck sweep: %s" % e, file=sys.stderr)
        return 2
    resume = getattr(a, "resume", False)
    if resume and not a.report:
        print("crosscheck sweep: --resume needs --report DIR (the sweep's directory)", file=sys.stderr)
        return 2
    a.resume = resume
    tol = RN.load_tolerances(a.tolerances)
    started = _dt.datetime.now().strftime("%Y%m%d-%H%M%S")
    report_dir = RN.work_dir(os.path.abspath(a.report or ("crosscheck-sweep-%s-%s-%s" % (a.name, a.size, started))),
                             resume)
    granwave = RN.find_granwave(a.granwave)
    t = time.time()
    st = dict(damping=damping, friction=friction, rolling=rolling)[a.name](a, report_dir, granwave, tol)
    print("report: %s" % os.path.join(report_dir, "sweep_%s.md" % a.name))
    print("wall: %.1f s" % (time.time() - t))
    print("VERDICT: %s" % ("FAIL" if st else "PASS"))
    return st
