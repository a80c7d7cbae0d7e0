"""The rolling probe's two spheres and parameters (granwave's k_r, k_o, mu_r, mu_o and the maps to each code),
and its LIGGGHTS and LAMMPS decks: rendered, run in a fresh directory, the dumped torques read back
(crosscheck/probe_rolling.py measures with them)."""
from __future__ import annotations

import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from xclib import driver as DRV  # noqa: E402
from xclib import runners as RN  # noqa: E402

A_I, A_J, DELTA, RHO = 1.0e-3, 1.5e-3, 1.0e-6, 2000.0
A_RED = A_I * A_J / (A_I + A_J)                  # a' = R*
KN = 1e5                                          # N/m, f_n = KN DELTA = 0.1 N
FN = KN * DELTA
DT, W = 1e-6, 10.0                                # s, rad/s: 1e-5 rad per step
K_R = K_O = 2e4                                   # granwave k_r, k_o (N/m)
MU_R = MU_O = 0.1
C_ROT = 1e-7                                      # gamma a'^2 (N m s): dashpot torque 1e-6 N m at W
V_N = 0.1                                         # m/s, virtual approach in the damped decks
GAMMA_N = 0.5                                     # N s/m, LAMMPS' normal dashpot there (0.05 N)
E_LIGGGHTS = 0.5                                  # LIGGGHTS luding restitution in its damped decks
OMEGA_FRAME, FRAME_STEPS, LOAD_STEPS = 1000.0, 500, 40
OPEN_STEPS = 3                                    # steps with the contact open
Z_J = A_I + A_J - DELTA
MASS_I, MASS_J = RHO * 4 / 3 * math.pi * A_I ** 3, RHO * 4 / 3 * math.pi * A_J ** 3
K_ANG = K_R * A_RED ** 2                          # granwave's angular stiffness (N m/rad)
M_LIM = MU_R * FN * A_RED                         # granwave's limit torque (N m)

PHASES = {   # deck -> [(name, steps, w_i, w_j)]: the spins of each phase
    "roll": [("A", 150, (W, 0, 0), (0, 0, 0)), ("B", 250, (-W, 0, 0), (0, 0, 0)), ("C", 0, (0, 0, 0), (0, 0, 0))],
    "roll_j": [("A", 20, (0, 0, 0), (-W, 0, 0))],
    "damped": [("A", 250, (W, 0, 0), (0, 0, 0)), ("B", 400, (-W, 0, 0), (0, 0, 0))],
    "frame": [("A", LOAD_STEPS, (W, 0, 0), (0, 0, 0)), ("R", FRAME_STEPS, None, None)],
    "torsion": [("A", 150, (0, 0, W), (0, 0, 0)), ("B", 250, (0, 0, -W), (0, 0, 0))],
    "combined": [("A", 200, (W, 0, W), (0, 0, 0))],
    "epsd2": [("A", 60, (W, 0, 0), (0, 0, 0))],
    "torsion_set": [("A", 150, (0, 0, W), (0, 0, 0)), ("B", 250, (0, 0, -W), (0, 0, 0))],
    "torsion_stop": [("A", 150, (0, 0, W), (0, 0, 0)), ("S", 5, (0, 0, 0), (0, 0, 0))],
    "marshall": [("A", 80, (0, 0, 100 * W), (0, 0, 0))],
}
AXIS = {"torsion_set": 2, "torsion_stop": 2, "roll": 0, "roll_j": 0, "damped": 0, "frame": 0, "torsion": 2, "combined": 0, "epsd2": 0, "marshall": 2}


def _head(code, factor=None):
    if code == "lammps":
        head = DRV.lammps_two_spheres(1)
    else:
        head = ("units si\natom_style granular\natom_modify map array\nboundary f f f\nnewton off\n"
                "communicate single vel yes\nregion box block -0.02 0.02 -0.02 0.02 -0.02 0.02 units box\ncreate_box 1 box\n")
    return head + """create_atoms 1 single 0 0 0 units box
create_atoms 1 single 0 0 %r units box
set atom 1 diameter %r density %r
set atom 2 diameter %r density %r
group one id 1
group two id 2
neighbor 2e-4 bin
neigh_modify delay 0%s
timestep %r
""" % (Z_J, 2 * A_I, RHO, 2 * A_J, RHO, "" if factor is None else " contact_distance_factor %r" % factor, DT)


def _liggghts_gamma_t(e):
    """model luding's gamma_n = gamma_t = sqrt(4 m* kn / (1 + (pi/ln e)^2))."""
    if e >= 1.0:
        return 0.0
    m_star = MASS_I * MASS_J / (MASS_I + MASS_J)
    return math.sqrt(4 * m_star * KN / (1 + (math.pi / math.log(e)) ** 2))


def liggghts_inertia():
    """rolling_friction luding's I_r = 1.4 (m_i a_i^2)(m_j a_j^2)/(m_i a_i^2 + m_j a_j^2)."""
    p, q = MASS_I * A_I ** 2, MASS_J * A_J ** 2
    return 1.4 * p * q / (p + q)


def liggghts_params(damped):
    """The luding keys that the research's maps give for granwave's k_r, mu_r, gamma_r."""
    e = E_LIGGGHTS if damped else 1.0
    c_stiff = K_ANG / (KN * A_RED ** 2)           # kr = kt coeffRollingStiffness R*^2, kt = LoadingStiffness
    gt = _liggghts_gamma_t(e)
    c_visc = C_ROT / (gt * 2 * math.sqrt(liggghts_inertia() * K_ANG)) if damped else 0.0
    return dict(e=e, coeffRollingStiffness=c_stiff, coefficientRollingFriction=MU_R,
                coefficientRollingViscousDamping=c_visc, gamma_t=gt)


def _liggghts_pair(deck):
    damped = deck in ("damped", "damped_on")
    p = liggghts_params(damped)
    rolling = "epsd2" if deck == "epsd2" else "luding" + (" torsion on" if deck.endswith("_on") else "")
    props = [("LoadingStiffness", KN), ("UnloadingStiffness", 1.0), ("coefficientAdhesionStiffness", 0.0),
             ("coefficientPlasticityDepth", 0.1), ("pullOffForce", 0.0), ("coefficientRestitution", p["e"]),
             ("coefficientFriction", 0.0), ("FluidViscosity", 1.0), ("FrictionViscosity", 1.0),
             ("coeffFrictionStiffness", 1.0), ("coefficientRollingFriction", MU_R),
             ("coefficientRollingViscousDamping", p["coefficientRollingViscousDamping"]),
             ("coeffRollingStiffness", p["coeffRollingStiffness"])]
    lines = ["fix p%d all property/global %s peratomtypepair 1 %r" % (k, n, v) for k, (n, v) in enumerate(props)]
    return "\n".join(lines) + "\npair_style gran model luding tangential tan_luding rolling_friction %s\npair_coeff * *\n" % rolling


def lammps_params():
    return dict(k_roll=K_R, gamma_roll=C_ROT / A_RED ** 2, mu_roll=MU_R,
                k_twist=K_O * A_RED ** 2, gamma_twist=C_ROT, mu_twist=MU_O * A_RED)


def _lammps_pair(deck):
    p = lammps_params()
    damped = deck == "damped"
    if deck == "marshall":
        tw, tang = "twisting marshall", "tangential linear_history %r 0 0.5" % KN
    else:
        tw = "twisting sds %r %r %r" % (p["k_twist"], p["gamma_twist"] if damped else 0.0, p["mu_twist"])
        tang = "tangential linear_nohistory 0 0"
    return "pair_style granular\npair_coeff * * hooke %r %r %s rolling sds %r %r %r %s damping velocity\n" % (
        KN, GAMMA_N if damped else 0.0, tang, p["k_roll"], p["gamma_roll"] if damped else 0.0, p["mu_roll"], tw)


_OMEGA = {"lammps": lambda k, w: "set atom %d omega %r %r %r\n" % ((k,) + tuple(w)),
          "liggghts": lambda k, w: "set atom %d omegax %r omegay %r omegaz %r\n" % ((k,) + tuple(w))}
_DUMP = {"lammps": "dump_modify d1 format float %.17g sort id\n",
         "liggghts": 'dump_modify d1 sort id format "%d' + " %.17g" * 15 + '"\n'}


def render(code, deck):
    """The deck's text and its phase list [(name, frames)]: every `run N` dumps N + 1 frames (its setup)."""
    base = deck.replace("_cdf", "").replace("_on", "") if deck != "combined_on" else "combined"
    pair = _lammps_pair(deck) if code == "lammps" else _liggghts_pair(deck)
    out = [_head(code, 1.01 if deck.endswith("_cdf") else None), pair,
           "dump d1 all custom 1 atoms.dump id x y z vx vy vz fx fy fz tqx tqy tqz omegax omegay omegaz\n",
           _DUMP[code]]
    if base == "damped":   # virtual approach: sphere j's velocity feeds the normal dashpot, nothing moves
        out.append("set atom 2 vz %r\n" % -V_N)
    phases, spun = [], []
    for name, steps, wi, wj in PHASES[base]:
        out += ["unfix %s\n" % f for f in spun]
        spun = []
        if name == "C":    # in one run, no spin: sphere j jumps out to a gap of delta in one step (the springs are
            # not limited by a vanishing f_n on the way), stays there OPEN_STEPS steps, jumps back, 5 steps at rest
            s0 = sum(n - 1 for _, n in phases)
            v = 2 * DELTA / DT
            out += [_OMEGA[code](1, (0, 0, 0)),
                    'variable vz equal "(step<=%d)*%r-(step>%d)*(step<=%d)*%r"\n' % (s0 + 1, v, s0 + 1 + OPEN_STEPS,
                                                                              s0 + 2 + OPEN_STEPS, v),
                    "fix op two move variable NULL NULL NULL NULL NULL v_vz\nrun %d\nunfix op\n" % (OPEN_STEPS + 7)]
            phases += [("C_back", OPEN_STEPS + 8)]
            continue
        if name == "R":    # rigid rotation about y through the contact point
            out += [_OMEGA[code](1, (0, 0, 0)), _OMEGA[code](2, (0, 0, 0)),
                    "fix mv all move rotate 0 0 %r 0 1 0 %r\nrun %d\n" % (A_I - DELTA / 2, 2 * math.pi / OMEGA_FRAME, steps)]
            phases.append((name, steps + 1))
            continue
        for k, (grp, w, z) in enumerate((("one", wi, 0.0), ("two", wj, Z_J)), 1):
            if deck == "torsion_set":    # `set omega` between runs: the new spin is in the run's setup
                out.append(_OMEGA[code](k, w))
            elif any(w):     # fix move spins the sphere from the run's first step on, not in its setup
                ww = math.sqrt(sum(c * c for c in w))
                out.append("fix s%d %s move rotate 0 0 %r %r %r %r %r\n" % ((k, grp, z) + tuple(c / ww for c in w) +
                                                                           (2 * math.pi / ww,)))
                spun.append("s%d" % k)
            else:
                out.append(_OMEGA[code](k, (0, 0, 0)))
        out.append("run %d\n" % steps)
        phases.append((name, steps + 1))
    return "".join(out), phases


def _frames(path):
    """{step: the first frame dumped at that step}: a run's setup frame repeats the previous run's last step
    (LIGGGHTS writes it, LAMMPS not)."""
    out = {}
    for fr in open(path).read().split("ITEM: TIMESTEP\n")[1:]:
        ls = fr.splitlines()
        n = int(ls[2])
        out.setdefault(int(ls[0]), np.array([[float(x) for x in ln.split()] for ln in ls[-n:]]))
    return out


def run_deck(exe, code, deck, work):
    """Runs one deck in its own fresh directory; {phase: rows (steps x 2 x 16)}, the steps of each run after
    its setup."""
    d = RN.fresh_dir(os.path.join(work, "%s_%s" % (code, deck)))
    text, phases = render(code, deck)
    with open(os.path.join(d, "in.probe"), "w") as f:
        f.write(text)
    cmd = [exe, "-in", "in.probe"] + (["-log", "none", "-nocite", "-screen", "none"] if code == "lammps" else [])
    status, rc, _, out = RN.run_cmd(cmd, d, 60, "stderr.txt")
    if status != "ok" or "ERROR" in out:
        raise RuntimeError("%s failed on deck %s (%s): %s" % (code, deck, status, out[-600:]))
    fr = _frames(os.path.join(d, "atoms.dump"))
    res, s = {}, 0
    for name, n in phases:
        res[name] = np.array([fr[k] for k in range(s + 1, s + n)])
        s += n - 1
    if s != max(fr):
        raise RuntimeError("%s deck %s: %d steps, %d expected" % (code, deck, max(fr), s))
    return res


def contact_torque(rows):
    """(M_i, M_j): each sphere's torque less the moment of its contact force about its centre (contact-point arm
    a - delta/2, as all three codes put it): the rolling/torsion law's torques. rows: frames x 2 x 16."""
    x, f, tq = rows[:, :, 1:4], rows[:, :, 7:10], rows[:, :, 10:13]
    d = x[:, 1] - x[:, 0]
    r = np.linalg.norm(d, axis=1)[:, None]
    n = d / r
    delta = A_I + A_J - r
    mi = tq[:, 0] - np.cross((A_I - delta / 2) * n, f[:, 0])
    mj = tq[:, 1] - np.cross(-(A_J - delta / 2) * n, f[:, 1])
    return mi, mj
