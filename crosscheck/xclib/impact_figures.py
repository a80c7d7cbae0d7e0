"""The impact cases' figures, like Chung & Ooi's: force against overlap (T1, T2), restitution out against
in (T3), tangential restitution, rebound angle, spin and psi2 against the incident angle (T4-T7)."""
from __future__ import annotations

import math
import os

import numpy as np

from .impact_judge import OBLIQUE, get_path, psi
from .impact_report import test_of

CODE_STYLE = {"granwave": ("k", "-", "o"), "yade": ("tab:blue", "--", "s"), "liggghts": ("tab:orange", ":", "^"),
              "lammps": ("tab:green", "-.", "v")}


def _angle(res) -> float:
    """The incident angle of the contact point, atan(v_ct/v_n) (deg), from granwave's (or any) rebound:
    T4, T5 the centre's, T6, T7 the spin's."""
    rb = res["rebounds"].get("granwave") or next(iter(res["rebounds"].values()), {})
    i = rb.get("in", {})
    return math.degrees(math.atan2(abs(i.get("vct", 0.0)), i.get("vn", 1.0)))


def psi_panel(ax, rs) -> None:
    """psi2 against psi1: Mindlin-Deresiewicz (MBF) and the simplified laws at the cases' psi1, the codes' points."""
    rs = sorted([r for r in rs if "compliance" in (r["theory"].get("oblique") or {})],
                key=lambda r: r["theory"]["oblique"]["mbf_psi1"])
    if not rs:
        ax.axis("off")
        ax.text(0.5, 0.5, "psi2: no sliding at the contact", ha="center", transform=ax.transAxes)
        return
    p1 = [r["theory"]["oblique"]["mbf_psi1"] for r in rs]
    for hist, ls in (("mindlin_deresiewicz", "-"), ("force", "--"), ("displacement", ":")):
        ax.plot(p1, [r["theory"]["oblique"]["compliance"][hist]["psi2"] for r in rs], color="0.5", ls=ls,
                lw=2, label="MBF (Mindlin-Deresiewicz)" if hist == "mindlin_deresiewicz" else "Mindlin law, %s" % hist)
    for code in CODE_STYLE:
        pts = [psi(r["rebounds"][code], r["theory"]) for r in rs if code in r["rebounds"]]
        pts = [p for p in pts if p[1] is not None]
        if pts:
            c, _, mk = CODE_STYLE[code]
            ax.plot(*zip(*pts), mk, color=c, mfc="none", ms=5, label=code)
    ax.set_xlabel("psi1 = kappa v_ct/(mu v_n)")
    ax.set_ylabel("psi2 = kappa v'_ct/(mu v_n)")
    h, lab = ax.get_legend_handles_labels()
    uniq = dict(zip(lab, h))
    ax.legend(uniq.values(), uniq.keys(), fontsize=7)


def figures(report_dir: str, results) -> list:
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import h5py
    except Exception:  # noqa: BLE001 -- no figures without matplotlib
        return []
    out = []
    by_test = {}
    for res in results:
        if not res.get("error"):
            by_test.setdefault(test_of(res["case_name"]), []).append(res)
    for t in ("T1", "T2"):
        for res in by_test.get(t, []):
            fig, ax = plt.subplots(figsize=(5, 4))
            th = res["theory"]
            d = np.linspace(0, th["hertz"]["peak_overlap"], 200)
            ax.plot(d * 1e6, 4.0 / 3.0 * th["effective_modulus"] * np.sqrt(th["effective_radius"]) * d ** 1.5 / 1e3,
                    color="0.6", lw=4, label="Hertz")
            for code, tr in res["traces"].items():
                if code not in CODE_STYLE:
                    continue
                with h5py.File(tr, "r") as f:
                    ov, fn = f["/impact/overlap"][()], f["/impact/contact_force_normal"][()]
                m = ov > 0
                c, ls, _ = CODE_STYLE[code]
                ax.plot(ov[m] * 1e6, fn[m] / 1e3, color=c, ls=ls, label=code)
            ax.set_xlabel("overlap (um)")
            ax.set_ylabel("normal force (kN)")
            ax.set_title("%s: %s" % (t, res["case_name"]))
            ax.legend()
            p = os.path.join(report_dir, "fig_%s.png" % res["case_name"])
            fig.tight_layout()
            fig.savefig(p, dpi=90)
            plt.close(fig)
            out.append(p)
    if by_test.get("T3"):
        fig, ax = plt.subplots(figsize=(5, 4))
        ax.plot([0, 1], [0, 1], color="0.6", lw=3, label="e out = e in")
        for res in by_test["T3"]:
            e_in = float(res["case"]["contact"].get("restitution", 1.0))
            for code, rb in res["rebounds"].items():
                if code in CODE_STYLE:
                    c, _, mk = CODE_STYLE[code]
                    ax.plot([e_in], [rb["normal_restitution"]], mk, color=c, mfc="none", label=code)
        h, lab = ax.get_legend_handles_labels()
        uniq = dict(zip(lab, h))
        ax.legend(uniq.values(), uniq.keys())
        ax.set_xlabel("restitution in (case)")
        ax.set_ylabel("restitution out (measured)")
        ax.set_title("T3")
        p = os.path.join(report_dir, "fig_T3.png")
        fig.tight_layout()
        fig.savefig(p, dpi=90)
        plt.close(fig)
        out.append(p)
    for t in ("T4", "T5", "T6", "T7"):
        rs = by_test.get(t, [])
        if not rs:
            continue
        fig, axs = plt.subplots(1, 5, figsize=(21, 4))
        psi_panel(axs[4], rs)
        for ax, (q, key, path, _, unit) in zip(axs, OBLIQUE):
            groups = {}
            for res in rs:
                mat = res["case_name"].rsplit("_", 1)[0]
                groups.setdefault(mat, []).append(res)
            if all(get_path(r["theory"], path) is None for r in rs):
                ax.axis("off")
                ax.text(0.5, 0.5, "%s: no closed form here\n(no centre velocity along the wall)" % q.replace("_", " "),
                        ha="center", transform=ax.transAxes)
                continue
            for m, (mat, g) in enumerate(groups.items()):
                g = sorted(g, key=_angle)
                ang = [_angle(r) for r in g]
                ax.plot(ang, [get_path(r["theory"], path) for r in g], color="0.6", lw=2, ls=("-", "--", ":")[m % 3],
                        label="Coulomb rigid body, %s" % mat)
                for code in CODE_STYLE:
                    pts = [(a, r["rebounds"][code].get(key)) for a, r in zip(ang, g)
                           if code in r["rebounds"] and r["rebounds"][code].get(key) is not None]
                    if pts:
                        c, _, mk = CODE_STYLE[code]
                        ax.plot(*zip(*pts), mk, color=c, mfc="none" if m == 0 else c, ms=5, label="%s, %s" % (code, mat))
            ax.set_xlabel("incident angle of the contact point, atan(v_ct/v_n) (deg)")
            ax.set_ylabel("%s%s" % (q.replace("_", " "), " (%s)" % unit if unit else ""))
            h, lab = ax.get_legend_handles_labels()
            uniq = dict(zip(lab, h))
            ax.legend(uniq.values(), uniq.keys(), fontsize=7)
        fig.suptitle(t)
        p = os.path.join(report_dir, "fig_%s.png" % t)
        fig.tight_layout()
        fig.savefig(p, dpi=90)
        plt.close(fig)
        out.append(p)
    return out
