#!/usr/bin/python3
"""LAMMPS driver for granwave cases: render (case + system -> deck + data file), run, convert.

    /usr/bin/python3 lammps_inputs/lammps_case.py CASE.toml SYSTEM.h5 OUT.h5 [--workdir DIR]
                     [--timeout S] [--render-only] [--lmp lmp] [--keep-dumps]

Same layout as liggghts_inputs/: the deck templates are lammps_inputs/templates/*.in.tmpl and every
parameter mapping and convention is in liggghts_inputs/MAPPING.md (LAMMPS section), each measured.
The environment variable XC_LMP names the LAMMPS executable when --lmp is not given (default `lmp`,
Debian's LAMMPS 29 Sep 2021 with GRANULAR). Prints one line "XC_SUMMARY {json}" at the end.
Exit: 0 done, 1 LAMMPS failed (or its dumps are unreadable), 2 a case LAMMPS cannot run exactly
(said on stderr, nothing written), 124 LAMMPS timed out, 127 LAMMPS not found.

Time convention: LAMMPS integrates velocity Verlet and writes its dumps after a whole step, so
positions, velocities and the contact forces of `compute pair/local` (recomputed from the dumped
state by the pair style's single()) belong to step*dt: synchronous, as LIGGGHTS. With a normal
dashpot the recomputed force sees v(t) where the step used v(t - dt/2): the converter puts it back
(xclib.dumps.dashpot_at_half_step, the same alignment as the LIGGGHTS writer's).

Memory: the converters read the dumps one frame at a time (xclib.dumps.lockstep); the trace arrays
are [samples, layers] (or [samples, contacts]), so the resident size does not grow with the dumps.
"""
from __future__ import annotations

import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crosscheck"))
from xclib import driver as DRV  # noqa: E402
from xclib import dumps as D  # noqa: E402
from xclib import laws as L  # noqa: E402
from xclib.codefacts import FRICTION_STYLE_CONVENTIONS, MIXED_ARM, Unsupported, resistance_on  # noqa: E402,F401
from xclib import traces as T  # noqa: E402

TIME_CONVENTION = ("synchronous: LAMMPS velocity Verlet, dumps after a whole step; positions, velocities "
                   "and compute pair/local forces at step*dt (no shift); the normal dashpot of the dumped "
                   "contact forces is put back to the step's half-step velocity v(t) - f(t)/m dt/2 (the "
                   "force that acted, as granwave and YADE record)")

# Contact-law conventions of the pair styles the crystal deck uses, measured with two-sphere decks
# (liggghts_inputs/MAPPING.md, LAMMPS section): xclib.codefacts (
# FRICTION_STYLE_CONVENTIONS of gran/hooke/history and gran/hertz/history, MIXED_ARM of pair granular).

# The chain's wall: "plane" = fix wall/gran with the pair's own Hertz constant (exact), or
# "sphere:R" = a fixed sphere of radius R (m) just touching the wall plane (R* error r/R), as the YADE
# driver does. XC_LAMMPS_WALL selects it (used to measure what the sphere costs: MAPPING.md).
WALL = os.environ.get("XC_LAMMPS_WALL", "plane")


def _template(name: str):
    return DRV.template(HERE, name)


_g = DRV.g


def mass_lines(m: np.ndarray) -> str:
    """`set atom I*J mass m` over runs of equal masses (one line for a monodisperse packing): the
    data file's density gives rmass = density 4/3 pi r^3 only to round-off, and Table 1 masses are
    not density x volume at all."""
    out, k, n = [], 0, len(m)
    while k < n:
        e = k
        while e + 1 < n and m[e + 1] == m[k]:
            e += 1
        ids = "%d" % (k + 1) if e == k else "%d*%d" % (k + 1, e + 1)
        out.append("set             atom %s mass %s" % (ids, _g(m[k])))
        k = e + 1
    return "\n".join(out)


def _data_file(path, n_types, box, types, radius, mass, pos):
    DRV.data_file(path, "LAMMPS data file (atom_style sphere)", "Atoms # sphere", n_types, box, types, radius, mass, pos)


def e_star(e1, nu1, e2, nu2) -> float:
    """E* of eq. (13): 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2."""
    return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)


# ------------------------------------------------------------------------------------------ chain
def render_chain(case: dict, system: dict, workdir: str, facts: dict) -> str:
    lay = T.chain_layout(system)
    if float(system["attrs"].get("precompression", 0.0) or 0.0) > 0.0:
        raise Unsupported("precompression > 0: the LAMMPS chain deck has no static load (not needed by any "
                          "crosscheck case); not run rather than run without it")
    m = np.asarray(system["mass"], float)
    r = np.asarray(system["radius"], float)
    pos = np.asarray(system["position"], float)
    e = np.asarray(system["youngs_modulus"], float)
    nu = np.asarray(system["poisson_ratio"], float)
    n = len(m)
    mats, types = DRV.material_types(e, nu)
    nt = len(mats)
    # eq. (13) per pair of bead materials; checked against the system's Hertz constants below
    kmat = {(a, b): 4.0 / 3.0 * e_star(*mats[a - 1], *mats[b - 1]) for a in range(1, nt + 1) for b in range(a, nt + 1)}
    hc = np.asarray(system["hertz_constant"], float)
    for c in range(n - 1):
        a, b = sorted((types[c], types[c + 1]))
        rs = r[c] * r[c + 1] / (r[c] + r[c + 1])
        if abs(kmat[(a, b)] * math.sqrt(rs) - hc[c]) > 1e-12 * hc[c]:
            raise ValueError("contact %d: 4/3 E* sqrt(R*) = %r, system hertz_constant = %r" % (c, kmat[(a, b)] * math.sqrt(rs), hc[c]))
    wall_e, wall_nu = (float(system["attrs"].get("wall_youngs_modulus", 0)), float(system["attrs"].get("wall_poisson_ratio", 0)))
    ntypes = nt
    radius, mass, ppos, ptypes = r, m, pos, types
    wall_line, wall_cols = "# free end: no wall", ""
    k_wall = None
    if lay["has_wall"]:
        k_wall = 4.0 / 3.0 * e_star(float(e[-1]), float(nu[-1]), wall_e, wall_nu)
        if abs(k_wall * math.sqrt(r[-1]) - hc[-1]) > 1e-12 * hc[-1]:
            raise ValueError("wall contact: 4/3 E* sqrt(R) = %r, system hertz_constant = %r" % (k_wall * math.sqrt(r[-1]), hc[-1]))
    sphere_r = None
    if lay["has_wall"] and WALL.startswith("sphere:"):
        # a fixed sphere of radius R touching the plane: R* = r R/(r + R) instead of r
        sphere_r = float(WALL.split(":", 1)[1])
        ntypes = nt + 1
        radius = np.append(r, sphere_r)
        mass = np.append(m, 1.0)          # never integrated; no dashpot, so its mass enters nothing
        ppos = np.vstack([pos, [lay["wall_x"] + sphere_r, pos[-1, 1], pos[-1, 2]]])
        ptypes = np.append(types, ntypes)
    elif lay["has_wall"]:
        if WALL != "plane":
            raise ValueError("XC_LAMMPS_WALL = %r (allowed: plane, sphere:R)" % WALL)
        # fix wall/gran applies F = k sqrt(R) delta^3/2 with R the bead's radius: the pair's own
        # constant. (Its hertz/material mixes the given E, nu as E/(2 (1 - nu)), neither the wall's
        # nor the Hertz E*: measured, MAPPING.md.)
        wall_line = ("fix             wall beads wall/gran granular hertz %s 0 tangential linear_nohistory 0 0 "
                     "xplane NULL %s contacts" % (_g(k_wall), _g(lay["wall_x"])))
        wall_cols = "f_wall[2]"
    pair_lines = []
    for a in range(1, ntypes + 1):
        for b in range(a, ntypes + 1):
            if b <= nt:
                k = kmat[(a, b)]
            elif a <= nt:
                k = 4.0 / 3.0 * e_star(*mats[a - 1], wall_e, wall_nu)
            else:
                pair_lines.append("pair_coeff      %d %d hooke 0 0 tangential linear_nohistory 0 0" % (a, b))
                continue
            pair_lines.append("pair_coeff      %d %d hertz %s 0 tangential linear_nohistory 0 0" % (a, b, _g(k)))
    rmax = float(r.max())
    hi_x = (lay["wall_x"] + (2 * sphere_r if sphere_r else 0.0)) if lay["has_wall"] else pos[:, 0].max()
    lo = [float(pos[:, 0].min() - 3 * rmax), float(pos[:, 1].min() - 3 * rmax), float(pos[:, 2].min() - 3 * rmax)]
    hi = [float(hi_x + 3 * rmax), float(pos[:, 1].max() + 3 * rmax), float(pos[:, 2].max() + 3 * rmax)]
    if sphere_r:
        lo[1], hi[1] = pos[-1, 1] - 1.01 * sphere_r, pos[-1, 1] + 1.01 * sphere_r
        lo[2], hi[2] = pos[-1, 2] - 1.01 * sphere_r, pos[-1, 2] + 1.01 * sphere_r
    _data_file(os.path.join(workdir, "data.system"), ntypes, (lo, hi), ptypes, radius, mass, ppos)
    vel = DRV.velocity_lines(np.asarray(system["velocity"], float))
    facts.update(has_wall=lay["has_wall"], wall=("sphere R = %g m" % sphere_r) if sphere_r else "plane", n_beads=n,
                 wall_atom=(n + 1) if sphere_r else None)
    return _template("chain.in.tmpl").substitute(
        case_name=case["case"]["name"], mass_lines=mass_lines(mass), skin=_g(0.5 * float(r.min())),
        bead_ids="1:%d" % n, pair_lines="\n".join(pair_lines), wall_line=wall_line, dt=_g(facts["dt"]),
        velocity_lines=vel, every=facts["every"], thermo=max(1, facts["nsteps"] // 10), nsteps=facts["nsteps"],
        wall_columns=wall_cols)


# ---------------------------------------------------------------------------------------- crystal
def crystal_style(c: dict, mass: np.ndarray, radius=None) -> dict:
    """The pair style lines and the conventions it runs (MAPPING.md, LAMMPS section): the law's
    mapping module's (xclib.linear, xclib.hertz_mindlin)."""
    return L.law_of(c).lammps_style(c, mass, radius)


def render_crystal(case: dict, system: dict, workdir: str, facts: dict) -> str:
    x = DRV.crystal(case, system)
    c = x.c
    sty = crystal_style(c, x.m, x.r)
    for key, used in sty["conventions"].items():
        asked = c.get(key)
        law = L.law_of(c)
        matters = {"lever_arm": law.tangential(c), "normal_tension": law.dashpot(c),
                   "coulomb_normal": law.tangential(c) and law.dashpot(c) and c["normal_tension"] == "allow",
                   "tangential_history": law.tangential(c), "contact_law": False,
                   "rolling_lever": resistance_on(c) and c["lever_arm"] != "radius"}[key]
        if matters and asked != used:
            sys.stderr.write("lammps_case: the case asks for %s = \"%s\"; LAMMPS %s runs \"%s\", and the trace says so "
                             "(%s)\n" % (key, asked, sty["style"], used,
                                          "granwave cannot run it: a reported difference" if used == MIXED_ARM
                                          else "granwave can run it: [contact] %s" % key))
    if c["mu_static"] != c["mu_dynamic"] and sty["tangential"]:
        sys.stderr.write("lammps_case: LAMMPS has one Coulomb mu; using mu_static=%g (mu_dynamic=%g ignored: a "
                         "documented difference)\n" % (c["mu_static"], c["mu_dynamic"]))
    DRV.crystal_atoms(x, workdir, "LAMMPS data file (atom_style sphere)", "Atoms # sphere")
    src = DRV.crystal_source(x)
    facts.update(lay={k: v for k, v in x.lay.items() if k != "layer"}, conventions=sty["conventions"],
                 pair_style=sty["style"], tangential=sty["tangential"], damped=T.has_dashpot(c), clip=sty["clip"])
    return _template("crystal.in.tmpl").substitute(
        case_name=case["case"]["name"], mass_lines=mass_lines(x.m), skin=_g(0.2 * float(x.r.min())),
        exclude=src["exclude"], free_types=src["free_types"], pair_comment=sty["comment"], pair_lines=sty["lines"],
        dt=_g(facts["dt"]), excitation_line=src["excitation_line"], tangential_columns=" p1 p2 p3" if sty["tangential"] else "",
        every=facts["every"],
        thermo=max(1, facts["nsteps"] // 10), nsteps=facts["nsteps"])


def render_layers(case: dict, system: dict, workdir: str) -> dict:
    """The benchmark's deck (bench/side_by_side.py): per-layer means written by LAMMPS itself (`compute
    stress/atom`, `fix ave/chunk` into layers.txt), no dumps. Raises Unsupported beyond its crystals."""
    v = DRV.layer_deck_values(case, system)
    v.update(v["law"].bench_lammps(v))   # pair_style, pair_coeff, variant: the law's LAMMPS mapping
    v["format"] = '" %.10g"'   # a leading space separates the columns
    deck = _template("crystal_layers.in.tmpl").substitute(v)
    return DRV.write_layer_deck(deck, case, system, workdir, "LAMMPS data file (benchmark)", v)


def render_packing_layers(case: dict, system: dict, workdir: str, snapshots: int = 0) -> dict:
    """The benchmark's deck on a packing file (bench/side_by_side.py, case `disordered`): granwave's
    contact-list rule and z-bins (xclib.bench_packing), per-bin means by LAMMPS itself (chunks by the
    molecule ID that carries each atom's bin); `snapshots` > 0: also positions every that many steps
    (snap.txt, the contact count's run, not timed)."""
    from xclib import bench_packing as BP
    v = BP.deck_values(case, system)
    # the crosscheck's pair style (crystal_style): undamped Hertz-Mindlin with a displacement history is
    # gran/hertz/history, granwave's radius arm; its conventions must be the case's (else refused)
    sty = crystal_style(v["contact"], np.asarray(system["mass"], float), np.asarray(system["radius"], float))
    arm = sty["conventions"].get("lever_arm")
    if v["friction"] and arm != v["contact"]["lever_arm"]:
        raise Unsupported("case %s: lever_arm = \"%s\", LAMMPS %s runs \"%s\"" % (case["case"]["name"],
                          v["contact"]["lever_arm"], sty["style"], arm))
    v.update(pair_lines=sty["lines"], variant="(%s)" % sty["style"], format='" %.10g"')
    if snapshots:
        v["snapshot_lines"] = BP.snapshot_lines("lammps", snapshots)
    deck = _template("packing_layers.in.tmpl").substitute(v)
    return BP.write_deck(deck, case, system, workdir, "LAMMPS data file (benchmark, packing)", v, molecules=True)


def render(case: dict, system: dict, workdir: str, output: str = "dumps") -> dict:
    """Write in.case and data.system into workdir; returns the run facts (dt, steps, every, ...).
    output "dumps": the crosscheck's deck (per-atom and per-contact dumps for the trace file);
    "layers": the benchmark's (render_layers). Raises Unsupported for a case LAMMPS cannot run with
    the same law."""
    if output == "layers":
        return render_layers(case, system, workdir)
    facts = DRV.run_facts(case, system)
    scheme = case.get("integrator", {}).get("scheme", "verlet")
    if scheme != "verlet":
        sys.stderr.write("lammps_case: the case says scheme = \"%s\"; LAMMPS runs velocity Verlet at the same dt\n" % scheme)
    deck = (render_chain if facts["model"] == "chain" else render_crystal)(case, system, workdir, facts)
    with open(os.path.join(workdir, "in.case"), "w") as f:
        f.write(deck)
    return facts


# --------------------------------------------------------------------------------------- converting
def tangential_at_step(fs_dump, fn_dump, fn_step, mu):
    """The tangential force of the step from the one single() recomputed at dump time.

    gran/hooke/history's single() rebuilds f_t = -kt xi from the history the step left (not
    incremented: exact with gamma_t = 0), then applies the Coulomb test again with the dump-time
    normal force, whose dashpot sees v(t): where |f_t| > mu |f_n(dump)| it is cut to that. The step's
    force was -kt xi with |kt xi| <= mu |f_n(step)|, equal when the contact slid. So a row the dump did
    not cut is the step's force, and a row it cut slid in the step when |f_n(step)| <= |f_n(dump)|:
    mu |f_n(step)| along the dumped direction. A cut row with |f_n(step)| > |f_n(dump)| has
    mu |f_n(dump)| <= |kt xi| <= mu |f_n(step)|: it is taken as sliding too (mu |f_n(step)|), and
    returned as `assumed` for the check against the per-atom forces (convert_crystal).
    Returns (force rows, assumed [rows] bool)."""
    if len(fs_dump) == 0 or mu <= 0.0:
        return fs_dump, np.zeros(len(fs_dump), bool)
    fs = np.linalg.norm(fs_dump, axis=1)
    cut = (fs >= mu * np.abs(fn_dump) * (1.0 - 1e-12)) & (fs > 0.0)
    assumed = cut & (np.abs(fn_step) > np.abs(fn_dump))
    scale = np.where(cut, np.abs(fn_step) / np.where(np.abs(fn_dump) > 0, np.abs(fn_dump), 1.0), 1.0)
    return fs_dump * scale[:, None], assumed


def atom_forces(n, a, b, f_on_a):
    """Per-atom sums of the contact forces (f on a, -f on b)."""
    out = np.empty((n, 3))
    for k in range(3):
        out[:, k] = np.bincount(a, f_on_a[:, k], n) - np.bincount(b, f_on_a[:, k], n)
    return out


def convert_chain(workdir, system, facts):
    lay = T.chain_layout(system)
    n = facts["n_beads"]
    nc = lay["ncontacts"]
    r = np.asarray(system["radius"], float)
    m = np.asarray(system["mass"], float)
    a = np.asarray(system["hertz_constant"], float)
    wall_atom = facts.get("wall_atom")
    times, cf_rows, ke, pe = [], [], [], []
    for s, cols, rows, pr in D.lockstep(os.path.join(workdir, "dump.atoms"), os.path.join(workdir, "dump.pairs")):
        x = D.columns(cols, rows, ["x"])[:, 0]
        v = D.columns(cols, rows, ["vx"])[:, 0]
        cf = np.zeros(nc)
        if len(pr):
            i, j, f = D.unique_rows(pr, 2, 1)
            i, j, f = D.on_lower_id(i, j, f)
            bb = (j == i + 1) & (j < n)
            cf[i[bb]] = -f[bb, 0]                 # compressed: the force on the striker-side bead points back
            if wall_atom is not None:
                w = j == wall_atom - 1
                cf[nc - 1] = -float(f[w, 0].sum()) if np.any(w) else 0.0
        if lay["has_wall"] and wall_atom is None:
            cf[nc - 1] = -D.columns(cols, rows, ["f_wall[2]"])[-1, 0]   # fix wall/gran's own force on the last bead
        times.append(s * facts["dt"])
        cf_rows.append(cf)
        ke.append(0.5 * float(np.sum(m * v * v)))
        pe.append(DRV.chain_potential(a, r, x, lay))
    data = DRV.chain_datasets(np.array(cf_rows).reshape(len(times), nc), ke, pe, n, lay["has_wall"])
    return np.array(times), data, {"wall": facts["wall"]}


def convert_crystal(workdir, case, system, facts):
    x = DRV.crystal(case, system)
    lay, layer, fixed, mass, r, cp = x.lay, x.layer, x.fixed, x.m, x.r, x.c
    nl = lay["nlayers"]
    clip = facts["clip"]
    dl = L.law_of(cp).lammps_dump(cp)    # the law's dashpot correction (Hertz-Mindlin: per contact)
    gamma_n, normal = dl["gamma_n"], dl["normal"]
    mobile = DRV.mobile(case, x)
    bx, by, dt = lay["box_x"], lay["box_y"], facts["dt"]
    ncol = 6 if facts["tangential"] else 3
    times, coord = [], []
    layers = DRV.LayerRows(lay, x.pos)
    assumed_rows = unrecovered = 0
    balance = 0.0
    n_atoms = len(r)
    nfree = max(int(np.count_nonzero(~fixed)), 1)
    for s, cols, rows, pr in D.lockstep(os.path.join(workdir, "dump.atoms"), os.path.join(workdir, "dump.pairs")):
        p = D.columns(cols, rows, ["x", "y", "z"])
        v = D.columns(cols, rows, ["vx", "vy", "vz"])
        fa = D.columns(cols, rows, ["fx", "fy", "fz"])
        if len(pr):
            i, j, fr = D.unique_rows(pr, 2, ncol)
        else:
            i, j, fr = np.zeros(0, int), np.zeros(0, int), np.zeros((0, ncol))
        fnorm = fr[:, :3]                                   # compute pair/local fx fy fz: the normal force on i
        f = fnorm + fr[:, 3:6] if facts["tangential"] else fnorm.copy()
        assumed = np.zeros(len(i), bool)
        if gamma_n > 0.0 and s > 0 and len(i):   # step 0: the setup force already saw v(0), as the dump does
            n_ij, _, _ = D.contact_normals(p, i, j, bx, by)
            fn_dump = np.sum(fnorm * n_ij, axis=1)
            f_step = D.dashpot_at_half_step(p, v, fa, mass, mobile, dt, i, j, fnorm, r, gamma_n, bx, by, clip, normal)
            if facts["tangential"]:
                fn_step = np.sum(f_step * n_ij, axis=1)
                ft, assumed = tangential_at_step(fr[:, 3:6], fn_dump, fn_step, float(cp["mu_static"]))
                f_step = f_step + ft
            f = f_step
        # The contact forces must add up to the forces LAMMPS applied (dumped per atom): checks the rows,
        # the dashpot alignment and every "assumed" sliding row (exact only if it slid).
        if len(i):
            miss = np.abs(atom_forces(n_atoms, i, j, f) - fa).max(axis=1)
            scale = float(np.abs(f).max())
            balance = max(balance, float(miss.max()) / scale)
            if assumed.any():
                off = miss > 1e-9 * scale
                assumed_rows += int(np.count_nonzero(assumed))
                unrecovered += int(np.count_nonzero(assumed & (off[i] | off[j])))
        a, b, fab = D.on_lower_id(i, j, f)
        szz, szx = T.layer_stress(p, r, layer, fixed, a, b, fab, bx, by, lay["l0"], nl)
        times.append(s * dt)
        layers.add(p, v, layer, szz, szx)
        touch = ~(fixed[a] & fixed[b])
        coord.append(float(np.count_nonzero(~fixed[a[touch]]) + np.count_nonzero(~fixed[b[touch]])) / nfree)
    data = layers.datasets(len(times))
    data["/crystal/coordination"] = np.array(coord)
    if unrecovered:
        sys.stderr.write("lammps_case: %d of %d contact rows cut by the dump-time Coulomb test do not add up to the "
                         "per-atom forces when taken as sliding in the step (trace attribute "
                         "tangential_unrecovered_rows)\n" % (unrecovered, assumed_rows))
    extra = dict(facts["conventions"])
    extra.update(pair_style=facts["pair_style"], tangential_assumed_rows=assumed_rows,
                 tangential_unrecovered_rows=unrecovered, force_balance_residual=balance)
    if facts["tangential"]:
        # measured: a contact that opens loses its spring; touching again it starts from f_t = 0
        extra["history_on_contact_loss"] = "zeroed"
    return np.array(times), data, extra


def convert(workdir: str, case: dict, case_text: str, system_path: str, out: str, facts: dict, version: str) -> None:
    system = T.read_system(system_path)
    if facts["model"] == "chain":
        times, data, extra = convert_chain(workdir, system, facts)
    else:
        times, data, extra = convert_crystal(workdir, case, system, facts)
    extra.update(dt=facts["dt"], deck=open(os.path.join(workdir, "in.case")).read())
    T.write_trace(out, code="lammps", code_version=version, case_text=case_text, case_name=case["case"]["name"],
                  system_path=system_path, time_convention=TIME_CONVENTION, time=times, datasets=data,
                  extra_attrs=extra)


DRIVER = DRV.DeckDriver(name="lammps_case", code="lammps", title="LAMMPS", package="lammps", exe_option="lmp",
                        exe_default=os.environ.get("XC_LMP", "lmp"), version_prefix="LAMMPS (", refused=(Unsupported,),
                        render=render, convert=convert, run_args=("-in", "in.case", "-log", "log.lammps", "-nocite"),
                        doc=__doc__)


def render_impact(s, work: str) -> dict:
    """An impact deck (data/SCHEMA.md §7): the spheres as types 1, 2, their contact by xclib.hertz_mindlin
    (lammps_impact), every step dumped at full precision (xclib.impact)."""
    from xclib import hertz_mindlin_impact as HM
    from xclib import impact as I
    lines, attrs = HM.lammps_impact(s)
    deck = ("# granwave impact case %s -> LAMMPS (lammps_inputs/lammps_case.py; MAPPING.md, \"Impact\")\n" % s.name +
            I.deck_head(s, "sphere", "comm_modify     vel yes", 2) + lines + I.deck_run(s, I.velocity_lines(s)))
    with open(os.path.join(work, "in.case"), "w") as f:
        f.write(deck)
    attrs["deck"] = deck
    return attrs


def main(argv) -> int:
    from xclib import impact as I
    if argv and I.is_impact(argv[0]):
        return I.main(argv, code="lammps", title="LAMMPS", exe_option="lmp", exe_default=os.environ.get("XC_LMP", "lmp"),
                      render=render_impact, version_prefix="LAMMPS (",
                      run_args=("-in", "in.case", "-log", "log.lammps", "-nocite"))
    return DRIVER.main(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
