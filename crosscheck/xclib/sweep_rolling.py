"""crosscheck sweep rolling: Luding's rolling and torsion springs over k_r/k_t (issue #28), speeds against
the lattice's long-wave speeds, first peaks, and the 2D-FFT ridge against the lattice branch and its zone edge."""
from __future__ import annotations

import json
import os
import subprocess

from . import ruler as R
from . import sweepmath as M
from .sweep_judge import judge_pairs, run_failures, sweep_tolerances
from .sweep_plots import plot_rolling
from .sweep_point import columns_of, point_pairs, sweep_point, sweep_setup, template
from .sweep_report import fmtv, timings_md, verdict_md, write_report

KR_OVER_KT = (0.05, 0.1, 0.2, 0.5, 1.0, 2.0)
ROLLING_KT_OVER_K = 1.0            # data/studies/crystal_rolling.toml
ROLLING_POSITIONS = {"small": (5, 15, 25), "paper": (10, 80, 150)}


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
    size, ratios, modes, codes, ruler_args = sweep_setup(a, KR_OVER_KT)
    # LIGGGHTS' resisted deck records no sigma_zx (pair dumps would turn its rolling spring; MAPPING.md): with it
    # in the sweep, every code's S points are measured on the layer velocity, so that all are measured on one field
    on_velocity = "liggghts" in codes and "S" in modes
    positions = ROLLING_POSITIONS[a.size]
    points = []
    for mode in modes:
        for r in ratios:
            name = "sweep_rolling_%s_%s_kr%s" % (a.size, mode, ("%g" % r).replace(".", "p"))
            tmpl, kn = template(size, mode)
            kt = ROLLING_KT_OVER_K * kn
            # k_o = k_r (data/studies/crystal_rolling.toml); no dashpot and no limit anywhere (YADE's
            # CohesionMoment has no rolling or twist dashpot); lever_arm: the contact point, as the friction sweep.
            ch = {("contact", "kt"): kt, ("contact", "kr"): r * kt, ("contact", "ko"): r * kt,
                  ("contact", "gamma_n"): 0.0, ("contact", "gamma_t"): 0.0, ("contact", "gamma_r"): 0.0,
                  ("contact", "gamma_o"): 0.0, ("contact", "mu_static"): 0.5, ("contact", "mu_dynamic"): 0.5,
                  ("contact", "lever_arm"): "contact_point", ("excitation", "mode"): mode}
            # YADE's angular springs take the radii: its twin granwave~yade runs rolling_lever = "radii"
            cp, res = sweep_point(a, report_dir, name, tmpl, ch, size, codes, granwave,
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
                yield "%s %g" % (p["mode"], p["kr_over_kt"]), fmtv(theory_v(p)), \
                    {c: p["speeds"].get(c, {}).get(which) for c in cols}
        md += ["### %s" % lab, ""] + M.sweep_table(points, cols, "mode kr/kt", "theory", rows, pairs) + [""]
    md += ["### half-peak speed against the lattice's long-wave speed", "",
           "| mode kr/kt | theory (m/s) | " + " | ".join("%s (rel.)" % c for c in cols) + " |",
           "|" + "---|" * (2 + len(cols))]
    for p in points:
        v = theory_v(p)
        md.append("| %s %g | %s | %s |" % (p["mode"], p["kr_over_kt"], fmtv(v), " | ".join(
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
        md.append("| %s %g | %s | %s | %s |" % (p["mode"], p["kr_over_kt"], fmtv(th.get("k_roll")), fmtv(ze),
                                              " | ".join(cells)))
    md.append("")
    verdict = []
    for which in ("peak", "half"):
        verdict += judge_pairs(points, pairs, lambda p, which=which: [{c: p["speeds"].get(c, {}).get(which) for c in cols}],
                               tsec.get("speed_rel"), tsec, "speed_rel %s (max over the sweep)" % which)
    verdict += judge_pairs(points, pairs, lambda p: [{c: p["peaks"].get(c, {}).get(z) for c in cols} for z in positions],
                           tsec.get("peak_rel"), tsec, "peak_rel (max over the sweep)")
    verdict += run_failures(points, cols)
    why = " ".join("%s: %s" % (q, tsec.get(q + "_why", "no tolerance set")) for q in ("speed_rel", "peak_rel"))
    status = verdict_md(md, verdict, why, tsec)
    timings_md(md, points, cols)
    png = os.path.join(report_dir, "rolling.png")
    plot_rolling(points, codes, modes, positions, png, on_velocity)
    md += ["![rolling](rolling.png)", ""]
    write_report(report_dir, "sweep_rolling", md,
                 dict(sweep="rolling", size=a.size, codes=codes, positions=positions, points=points, verdict=verdict))
    return status
