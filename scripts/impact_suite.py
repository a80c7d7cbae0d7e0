#!/usr/bin/python3
"""Runs impact cases (data/impact, data/SCHEMA.md §7) with granwave and prints, per case, the measured
rebound next to `granwave theory`'s closed forms: peaks and contact time against elastic Hertz (the
judge where e = 1), restitution against the case's, the oblique rebound against Coulomb's rigid-body
values (the judge in the sliding regime only), and Maw, Barber & Fawcett's psi1, psi2 (measured, the case's
Mindlin law, Mindlin-Deresiewicz; data/impact/README.md).
usage: /usr/bin/python3 scripts/impact_suite.py GRANWAVE [CASE.toml | DIR ...] [--json OUT]"""
import glob
import json
import os
import subprocess
import sys
import tempfile


def cases(args):
    out = []
    for a in args:
        out += sorted(glob.glob(os.path.join(a, "**", "*.toml"), recursive=True)) if os.path.isdir(a) else [a]
    return out


def run(gw, case, tmp):
    trace = os.path.join(tmp, os.path.basename(case) + ".h5")
    r = json.loads(subprocess.run([gw, "run", case, "-o", trace, "--json", "--quiet"], check=True,
                                  capture_output=True, text=True).stdout)
    t = json.loads(subprocess.run([gw, "theory", case, "--json"], check=True, capture_output=True, text=True).stdout)
    os.remove(trace)
    return r["analysis"]["rebound"], t


def rel(a, b):
    return "" if a is None or b is None or b == 0 else f"{a / b - 1:+.2e}"


def psi_columns(m, ob):
    """psi1, psi2 measured, psi2 of the case's Mindlin law and of Mindlin-Deresiewicz (blank without friction)."""
    if "compliance" not in ob:
        return ""
    k = ob["mbf_kappa"] / (ob["mu"] * m["in"]["vn"])
    law = ob["compliance"][ob["law_tangential_history"]]["psi2"]
    return (f"{ob['mbf_psi1']:8.4f} {k * m['out']['vct']:8.4f} {law:8.4f}"
            f" {ob['compliance']['mindlin_deresiewicz']['psi2']:8.4f}")


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    out = sys.argv[sys.argv.index("--json") + 1] if "--json" in sys.argv else None
    if out:
        args.remove(out)
    gw, targets = args[0], args[1:] or [os.path.join(os.path.dirname(__file__), "..", "data", "impact")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases(targets):
            m, t = run(gw, case, tmp)
            rows.append({"case": os.path.basename(case)[:-5], "measured": m, "theory": t})
    print(f"{'case':28s} {'Fmax/Fhertz-1':>13s} {'dmax/dhertz-1':>13s} {'tc/thertz-1':>11s} {'e_n':>8s} {'e_n th':>8s}"
          f" {'e_t':>8s} {'e_t th':>8s} {'reb':>8s} {'reb th':>8s} {'spin':>9s} {'spin th':>9s}"
          f" {'psi1':>8s} {'psi2':>8s} {'psi2 law':>8s} {'psi2 MD':>8s}")
    for r in rows:
        m, t = r["measured"], r["theory"]
        h = t.get("hertz", {})
        ob = t.get("oblique", {})
        f = lambda x: "" if x is None else f"{x:8.4f}"
        g = lambda x: "" if x is None else f"{x:9.3f}"
        print(f"{r['case']:28s} {rel(m['peak_force'], h.get('peak_force')):>13s} {rel(m['peak_overlap'], h.get('peak_overlap')):>13s}"
              f" {rel(m['contact_time'], h.get('contact_time')):>11s} {f(m['normal_restitution']):>8s} {f(t.get('restitution')):>8s}"
              f" {f(m['tangential_restitution']):>8s} {f(ob.get('tangential_restitution')):>8s} {f(m['rebound_angle_deg']):>8s}"
              f" {f(ob.get('rebound_angle_deg')):>8s} {g(m['spin_after']):>9s} {g(ob.get('spin_after', t.get('rolling', {}).get('spin_after'))):>9s}"
              f" {psi_columns(m, ob)}")
    if out:
        with open(out, "w") as fh:
            json.dump(rows, fh, indent=1)


if __name__ == "__main__":
    main()
