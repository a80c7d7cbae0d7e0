#!/usr/bin/python3
"""A packing file's system relaxed in LAMMPS, then run still and with a pulse in YADE, LIGGGHTS and LAMMPS.

    /usr/bin/python3 crosscheck/probe_packing_relaxed.py CASE.toml [CASE.toml ...] --work DIR

Until granwave relaxes a `lattice = "file"` packing itself (issue 38 item 4), this measures what the other
codes do on a static one: xclib.sysbuild cuts the first case's packing into slabs and bins, LAMMPS relaxes
the free particles under the case's normal law (`min_style fire` on the crosscheck's own deck, slabs held,
`pair granular hooke` frictionless: linear laws only), the centres are written back and re-binned (bins from
the relaxed centres), and the three drivers run (1) the first case with amplitude 0 (the quiescent run:
largest particle-mean velocity of any bin, and largest layer stress change) and (2) every case as given
(pairwise max |diff| / peak of the judged stress, xclib.judge). Prints one line per measure.
"""
import argparse
import os
import re
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "lammps_inputs"))
from xclib import compare as C  # noqa: E402
from xclib import judge as J  # noqa: E402
from xclib import sysbuild  # noqa: E402
from xclib import traces as T  # noqa: E402
import lammps_case as LM  # noqa: E402

RELAX = """neigh_modify    delay 0 every 1 check yes
group           held type 2 3
fix             hold held setforce 0.0 0.0 0.0
variable        fn atom sqrt(fx*fx+fy*fy+fz*fz)
compute         fm free reduce max v_fn
thermo_style    custom step ke c_fm fnorm
thermo          500
timestep        %r
min_style       fire
min_modify      integrator eulerimplicit tmax 10.0
minimize        0.0 %r 200000 2000000
write_dump      all custom relaxed.dump id x y z modify sort id format float %%.17g
"""


def relaxed_system(case_path: str, work: str, ftol: float) -> str:
    case, _ = T.load_case(case_path)
    c = dict(case, contact=dict(kn=case["contact"]["kn"], kt=0.0, gamma_n=0.0, gamma_t=0.0))
    s0 = os.path.join(work, "system0.h5")
    sysbuild.build(case, s0, os.path.dirname(os.path.abspath(case_path)))
    deck_dir = os.path.join(work, "relax")
    os.makedirs(deck_dir)
    LM.render(c, T.read_system(s0), deck_dir)
    head = open(os.path.join(deck_dir, "in.case")).read().split("timestep")[0]
    head = "\n".join(ln for ln in head.splitlines() if not ln.startswith("neigh_modify"))
    dt = T.timestep(case, T.read_system(s0))
    with open(os.path.join(deck_dir, "in.relax"), "w") as f:
        f.write(head + "\n" + RELAX % (dt, ftol))
    subprocess.run(["lmp", "-in", "in.relax", "-log", "log.relax"], cwd=deck_dir, check=True, stdout=subprocess.DEVNULL)
    lines = open(os.path.join(deck_dir, "relaxed.dump")).read().splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS"))
    a = np.array([[float(v) for v in ln.split()] for ln in lines[k + 1:]])
    pos = np.empty((len(a), 3))
    pos[a[:, 0].astype(int) - 1] = a[:, 1:4]
    out = os.path.join(work, "system_relaxed.h5")
    with h5py.File(s0, "r") as f0, h5py.File(out, "w", libver=T.LIBVER) as f:
        for key, v in f0.attrs.items():
            f.attrs[key] = v
        h, z0, nl = f0.attrs["bin_width"], f0.attrs["bin_origin"], int(f0.attrs["layers"])
        layer = np.clip(np.floor((pos[:, 2] - z0) / h), 0, nl - 1).astype(np.int64)
        order = np.argsort(layer, kind="stable")
        for key in f0:
            d = {"position": pos, "layer": layer}.get(key, f0[key][()])
            f[key] = d if key == "material_names" else d[order]
        f.attrs["relaxed"] = 1
    log = open(os.path.join(deck_dir, "log.relax")).read()
    fm = [ln.split() for ln in log.splitlines() if ln.strip() and ln.split()[0].isdigit() and len(ln.split()) == 4]
    print("relaxation (LAMMPS fire): %s steps, largest force on a free particle %s -> %s N" % (fm[-1][0], fm[0][2], fm[-1][2]))
    return out


def run_three(case_path: str, system: str, work: str, stem: str) -> dict:
    out = {}
    for code, cmd in (("yade", ["yade", "-n", "-x", os.path.join(ROOT, "yade_scripts", "run_case.py")]),
                      ("liggghts", [sys.executable, os.path.join(ROOT, "liggghts_inputs", "liggghts_case.py")]),
                      ("lammps", [sys.executable, os.path.join(ROOT, "lammps_inputs", "lammps_case.py")])):
        tr = os.path.join(work, "%s.%s.h5" % (stem, code))
        with open(tr + ".log", "w") as lo:
            subprocess.run(cmd + [case_path, system, tr], stdout=lo, stderr=subprocess.STDOUT, check=True)
        out[code] = T.read_trace(tr)
    return out


def main(argv) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("cases", nargs="+")
    ap.add_argument("--work", required=True)
    ap.add_argument("--ftol", type=float, default=1e-12, help="FIRE's force tolerance (N)")
    a = ap.parse_args(argv)
    os.makedirs(a.work)
    system = relaxed_system(a.cases[0], a.work, a.ftol)
    text = open(a.cases[0]).read()
    case0, _ = T.load_case(a.cases[0])
    quiet = os.path.join(a.work, "quiescent.toml")
    with open(quiet, "w") as f:   # the first case with amplitude 0, its packing path made absolute
        pk = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(a.cases[0])), case0["packing"]["file"]))
        f.write(re.sub(r"(?m)^amplitude\s*=.*$", "amplitude = 0.0", text.replace(case0["packing"]["file"], pk)))
    for code, tr in run_three(quiet, system, a.work, "quiescent").items():
        v = max(np.abs(tr["/crystal/layer_velocity_" + ax]).max() for ax in "xz")
        ds = np.abs(tr["/crystal/layer_stress_zz"] - tr["/crystal/layer_stress_zz"][0]).max()
        print("quiescent %s: largest bin velocity %.3g m/s, largest bin sigma_zz change %.3g Pa (of %.4g)"
              % (code, v, ds, np.abs(tr["/crystal/layer_stress_zz"][0]).max()))
    for cp in a.cases:
        case, _ = T.load_case(cp)
        trs = run_three(os.path.abspath(cp), system, a.work, os.path.splitext(os.path.basename(cp))[0])
        for ca, cb in (("yade", "liggghts"), ("yade", "lammps"), ("liggghts", "lammps")):
            sa, sb = J.traces_for(trs[ca], case), J.traces_for(trs[cb], case)
            for label in sa:
                ia, ib = C.common_grid(sa[label][0], sb[label][0])
                m = C.trace_metrics(sa[label][1][ia], sb[label][1][ib])
                print("%s %s-%s %s: max/peak %.3g (peak %.4g)" % (case["case"]["name"], ca, cb, label, m["max_rel"],
                                                                   m["peak"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
