#!/usr/bin/python3
"""LIGGGHTS driver for granwave cases: render (case + system -> deck + data file), run, convert.

    /usr/bin/python3 liggghts_inputs/liggghts_case.py CASE.toml SYSTEM.h5 OUT.h5 [--workdir DIR]
                     [--timeout S] [--render-only] [--liggghts liggghts]

The deck templates are liggghts_inputs/templates/*.in.tmpl; every parameter mapping is explained in
liggghts_inputs/MAPPING.md. Prints one line "XC_SUMMARY {json}" at the end.

Time convention: LIGGGHTS integrates velocity Verlet and writes its dumps after a whole step, so
positions, velocities and the contact forces of `compute pair/gran/local` (recomputed from the
dumped state) belong to step*dt: already synchronous, no shift. The crystal deck builds contacts
with `run 1` in the undisplaced packing and resets the step counter before the source steps.
"""
from __future__ import annotations

import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crosscheck"))
from xclib import driver as DRV  # noqa: E402
from xclib import dumps as D  # noqa: E402
from xclib import laws as L  # noqa: E402
from xclib import traces as T  # noqa: E402
from xclib.codefacts import resistance_on  # noqa: E402

TIME_CONVENTION = ("synchronous: LIGGGHTS velocity Verlet, dumps after a whole step; positions, "
                   "velocities and compute pair/gran/local forces at step*dt (no shift); the normal "
                   "dashpot of the dumped contact forces is put back to the step's half-step velocity "
                   "v(t) - f(t)/m dt/2 (the force that acted, as granwave and YADE record)")


_g = DRV.g


def _template(name: str):
    return DRV.template(HERE, name)


# neigh_modify contact_distance_factor of the friction decks (render: the history is lost when a contact opens)
CONTACT_DISTANCE_FACTOR = 1.01


def _masses(m: np.ndarray) -> str:
    return "\n".join("set             atom %d mass %s" % (k + 1, _g(v)) for k, v in enumerate(m))


def _data_file(path, n_types, box, types, radius, mass, pos):
    DRV.data_file(path, "LIGGGHTS data file (atom_style granular)", "Atoms", n_types, box, types, radius, mass, pos)


def render_layers(case: dict, system: dict, workdir: str) -> dict:
    """The benchmark's deck (bench/side_by_side.py): per-layer means written by LIGGGHTS itself (`compute
    stress/atom`, `fix ave/spatial` into layers.txt), no dumps. Raises Unsupported beyond its crystals."""
    v = DRV.layer_deck_values(case, system)
    # LIGGGHTS 3.8 refuses shear history with newton on (pair_gran.cpp: "requires newton pair off")
    v.update(newton="off" if v["friction"] else "on")
    v.update(v["law"].bench_liggghts(v))   # properties, pair_style, variant: the law's LIGGGHTS mapping
    deck = _template("crystal_layers.in.tmpl").substitute(v)
    return DRV.write_layer_deck(deck, case, system, workdir, "LIGGGHTS data file (benchmark)", v)


def render_packing_layers(case: dict, system: dict, workdir: str, snapshots: int = 0) -> dict:
    """The benchmark's deck on a packing file (bench/side_by_side.py, case `disordered`): granwave's
    contact-list rule (xclib.bench_packing), per-bin means by `fix ave/spatial` over the atoms' current z
    (no chunks in LIGGGHTS 3.8); `snapshots` > 0: also positions every that many steps (snap.txt)."""
    from xclib import bench_packing as BP
    v = BP.deck_values(case, system)
    if v["friction"] and v["contact"]["lever_arm"] != "contact_point":
        raise DRV.Unsupported("case %s: lever_arm = \"%s\", LIGGGHTS' tangential history runs \"contact_point\"" % (
            case["case"]["name"], v["contact"]["lever_arm"]))
    v.update(newton="off" if v["friction"] else "on")   # shear history needs newton off
    v.update(v["law"].bench_liggghts(v))
    if snapshots:
        v["snapshot_lines"] = BP.snapshot_lines("liggghts", snapshots)
    deck = _template("packing_layers.in.tmpl").substitute(v)
    return BP.write_deck(deck, case, system, workdir, "LIGGGHTS data file (benchmark, packing)", v, molecules=False)


def render(case: dict, system: dict, workdir: str, output: str = "dumps") -> dict:
    """Write in.case and data.system into workdir; returns the run facts (dt, steps, every, ...).
    output "dumps": the crosscheck's deck (per-atom and per-contact dumps for the trace file);
    "layers": the benchmark's (render_layers)."""
    if output == "layers":
        return render_layers(case, system, workdir)
    facts = DRV.run_facts(case, system)
    dt, nsteps, every = facts["dt"], facts["nsteps"], facts["every"]
    if facts["model"] == "chain":
        m = np.asarray(system["mass"], float)
        r = np.asarray(system["radius"], float)
        pos = np.asarray(system["position"], float)
        lay = T.chain_layout(system)
        keys, types = DRV.material_types(np.asarray(system["youngs_modulus"], float),
                                         np.asarray(system["poisson_ratio"], float))
        ym = [k[0] for k in keys]
        pr = [k[1] for k in keys]
        wall_line = "# free end: no wall"
        if lay["has_wall"]:
            ym.append(float(system["attrs"]["wall_youngs_modulus"]))
            pr.append(float(system["attrs"]["wall_poisson_ratio"]))
            wall_line = ("fix             wall all wall/gran model hertz tangential no_history primitive type %d "
                         "xplane %s store_force yes" % (len(ym), _g(lay["wall_x"])))
        nt = len(ym)
        rmax = float(r.max())
        lo = [float(pos[:, 0].min() - 3 * rmax), float(pos[:, 1].min() - 3 * rmax), float(pos[:, 2].min() - 3 * rmax)]
        hi = [float((lay["wall_x"] if lay["has_wall"] else pos[:, 0].max()) + 3 * rmax),
              float(pos[:, 1].max() + 3 * rmax), float(pos[:, 2].max() + 3 * rmax)]
        _data_file(os.path.join(workdir, "data.system"), nt, (lo, hi), types, r, m, pos)
        deck = _template("chain.in.tmpl").substitute(
            case_name=case["case"]["name"], mass_lines=_masses(m), skin=_g(0.5 * float(r.min())),
            youngs=" ".join(map(_g, ym)), poissons=" ".join(map(_g, pr)), ntypes=nt,
            restitution=" ".join(["1.0"] * nt * nt), friction=" ".join(["0.0"] * nt * nt),
            wall_line=wall_line, dt=_g(dt), velocity_line=DRV.velocity_lines(np.asarray(system["velocity"], float)),
            atom_format="%d" + " %.17g" * 9, every=every, thermo=max(1, nsteps // 10), nsteps=nsteps)
        facts.update(has_wall=lay["has_wall"])
    else:
        x = DRV.crystal(case, system)
        c = x.c
        DRV.crystal_atoms(x, workdir, "LIGGGHTS data file (atom_style granular)", "Atoms")
        if c["mu_static"] != c["mu_dynamic"]:
            sys.stderr.write("liggghts_case: LIGGGHTS has one coefficientFriction; using mu_static=%g "
                             "(mu_dynamic=%g ignored: a documented difference)\n" % (c["mu_static"], c["mu_dynamic"]))
        src = DRV.crystal_source(x)
        exclude = src["exclude"]
        limit_force = "on" if c["normal_tension"] == "clip" else "off"
        contact_lines, with_history = L.law_of(c).liggghts_lines(c, limit_force)  # xclib.linear / hertz_mindlin
        record = _record_without_pair_dumps(x) if resistance_on(c) else _record_with_pair_dumps(with_history, every)
        if with_history:
            # A contact that opens loses its spring (seed 002 sec. 2.1: a contact starts with xi = 0; granwave,
            # YADE, LAMMPS). LIGGGHTS zeroes the shear history only in surfacesClose, which pair_gran_base.h
            # calls for a non-touching pair closer than contact_distance_factor x (r_i + r_j): at the default
            # factor 1 never, so an opened contact kept its last spring and took it up again on reclosing
            # (relaxed polydisperse packing, kt = k, mu = 0.5: 6.1e-6 of the peak, docs/validation.md). Any
            # factor above 1 + (one step's opening)/(r_i + r_j) zeroes it in the step the contact opens; 1.01 is
            # LIGGGHTS' own choice for its energy bookkeeping. Touching pairs and the dumps (touching rows only)
            # are unchanged; the neighbour list reaches 1 % further. (${exclude} is the neigh_modify tail.)
            exclude = "contact_distance_factor %s %s" % (_g(CONTACT_DISTANCE_FACTOR), exclude)
        deck = _template("crystal.in.tmpl").substitute(
            case_name=case["case"]["name"], mass_lines=_masses(x.m), skin=_g(0.2 * float(x.r.min())),
            contact_lines=contact_lines, exclude=exclude, free_types=src["free_types"],
            dt=_g(dt), excitation_line=src["excitation_line"], every=every,
            thermo=max(1, nsteps // 10), nsteps=nsteps, **record)
        facts.update(lay={k: v for k, v in x.lay.items() if k != "layer"}, pair_dumps=not resistance_on(c))
    with open(os.path.join(workdir, "in.case"), "w") as f:
        f.write(deck)
    return facts


def _record_with_pair_dumps(with_history: bool, every: int) -> dict:
    """The record of a deck without rolling or torsion: per-atom dumps and the pairs' rows id1 id2 flag f(3)
    [shear history(3)] (with a tangential spring: the converter's step force, tangential_at_step)."""
    ncol = 9 if with_history else 6
    return dict(record_lines="# with a tangential spring the pairs also carry the shear history (the converter's "
                "step force)\ncompute         cpl all pair/gran/local id force%s\ndump            dpl all local %d "
                "dump.pairs %s" % (" history" if with_history else "", every,
                                   " ".join("c_cpl[%d]" % k for k in range(1, ncol + 1))),
                atom_extra="", atom_format="%d" + " %.17g" * 9,
                pair_format_line='dump_modify     dpl format "%s"' % " ".join(["%.17g"] * ncol))


def _record_without_pair_dumps(x) -> dict:
    """The record of a deck with rolling or torsion resistance: per-atom dumps only.

    `compute pair/gran/local` runs the pair style again at each dump, and rolling_friction luding then
    adds one more increment to its history (MAPPING.md): a run with pair dumps is not LIGGGHTS' run.
    So sigma_zz comes from `compute stress/atom pair` (its zz is sum 0.5 delz fz per atom, which is
    SCHEMA §3's (x_c - x_p)_z f_z with the contact point at the middle of the overlap only for equal
    radii), and sigma_zx is not recorded: stress/atom keeps six symmetric components, its xz is
    delx fz, and sigma_zx needs delz fx. The crosscheck judges these traces on the layer velocity."""
    if not np.all(x.r == x.r[0]):
        raise DRV.Unsupported("LIGGGHTS with rolling or torsion resistance: the layer stress comes from compute "
                              "stress/atom (pair dumps turn rolling_friction luding's spring), which puts the contact "
                              "point at the middle of the overlap only for equal radii (radii %g .. %g m)"
                              % (float(x.r.min()), float(x.r.max())))
    return dict(record_lines="# no pair dumps: they would turn rolling_friction luding's spring (MAPPING.md)\n"
                "compute         sa all stress/atom pair", atom_extra=" c_sa[3]", atom_format="%d" + " %.17g" * 10,
                pair_format_line="")


# ------------------------------------------------------------------------------------ dump reading
def read_dump(path: str):
    """Yield (timestep, column names, rows [n, ncol]) for each frame of a LIGGGHTS text dump, one
    frame in memory at a time (xclib.dumps.frames)."""
    return D.frames(path)


def _pairs_on_first(rows: np.ndarray, correct=None):
    """(i, j, force on i) with each physical contact once, i < j. pair/gran/local rows are id1 id2 flag
    fx fy fz (force on id1); with newton off a contact across a periodic boundary is listed from both
    sides. `correct(id1, id2, f)` (optional) adjusts the forces of the chosen rows before reordering;
    when the rows carry the shear history (columns 6:9), it is called as correct(id1, id2, f, shear)."""
    i, j, fh = _unique_rows(rows)
    f, shear = fh[:, :3], (fh[:, 3:6] if fh.shape[1] >= 6 else None)
    if correct is not None:
        f = correct(i, j, f) if shear is None else correct(i, j, f, shear)
    a = np.minimum(i, j)
    b = np.maximum(i, j)
    sgn = np.where(i == a, 1.0, -1.0)
    return a, b, f * sgn[:, None]


# The dashpot alignment is shared with the LAMMPS writer (same dump-time recomputation).
dashpot_at_half_step = D.dashpot_at_half_step


def tangential_at_step(p, i, j, f_pair, shear, kt, box_x, box_y):
    """The force each contact applied in the step: the normal part of the dumped force plus the
    tangential force -kt * shear of the history the step left.

    `compute pair/gran/local` recomputes the force at dump time with shearupdate = 0: it does not
    increment the history, but it applies the Coulomb test again, mu |Fn|, with the normal force of
    the dump, whose dashpot sees the owned atom at v(t) instead of the step's v(t - dt/2)
    (dashpot_at_half_step). Where a contact slides, or is near the limit, the dumped tangential force
    is therefore cut to mu |Fn(dump)| instead of the step's mu |Fn(step)|. With gamma_t = 0 the step's
    tangential force is exactly -kt * shear: not sliding, the spring alone; sliding, LIGGGHTS 3.8
    (tangential_model_history.h, surfacesIntersect) rescales the force to mu |Fn| and sets the history
    to -Ft / kt. Measured on the prestressed velocity drive (4x4x40, gamma_n = 0.1, kt = k, mu = 0.5,
    1e-3 m/s: contacts open with the dashpot pulling), granwave with LIGGGHTS' Coulomb limit mu |f_n|
    vs LIGGGHTS: 3.0e-5 (max/peak, z/l0 = 10; the layer velocities equal to 1e-10, i.e. the record
    only) -> 5.6e-10.
    p [n, 3]; i (owned, id1 of the row), j; f_pair: force on i; shear [rows, 3]: i's history."""
    if len(i) == 0:
        return f_pair
    d = p[i] - p[j]
    d[:, 0] -= box_x * np.round(d[:, 0] / box_x)
    d[:, 1] -= box_y * np.round(d[:, 1] / box_y)
    n = d / np.linalg.norm(d, axis=1)[:, None]
    fn = np.sum(f_pair * n, axis=1)
    return fn[:, None] * n - kt * shear


def _unique_rows(rows: np.ndarray):
    """(id1, id2, force on id1) of the first dumped row of each physical contact, as dumped (the
    force and, with `history` in the compute, the shear history after it: columns 3:9)."""
    return D.unique_rows(rows, 3, 6 if rows.shape[1] >= 9 else 3)


def convert(workdir: str, case: dict, case_text: str, system_path: str, out: str, facts: dict, version: str) -> None:
    """Dumps -> trace file, one frame of each dump in memory at a time (xclib.dumps.lockstep): the
    resident size no longer grows with the run (it held every frame: 1.8 GB on crystal_kt10)."""
    system = T.read_system(system_path)
    dt = facts["dt"]
    atoms = os.path.join(workdir, "dump.atoms")
    pair_dumps = facts.get("pair_dumps", True)
    frames = (D.lockstep(atoms, os.path.join(workdir, "dump.pairs")) if pair_dumps else
              ((s, cols, rows, None) for s, cols, rows in D.frames(atoms)))
    r = np.asarray(system["radius"], float)
    n = len(r)
    steps = []
    if facts["model"] == "chain":
        lay = T.chain_layout(system)
        nc = lay["ncontacts"]
        cf_rows, ke, pe = [], [], []
        m = np.asarray(system["mass"], float)
        a = np.asarray(system["hertz_constant"], float)
        for s, cols, rows, pr in frames:
            steps.append(s)
            cf = np.zeros(nc)
            x = rows[:, cols.index("x")]
            v = rows[:, [cols.index("vx"), cols.index("vy"), cols.index("vz")]]
            ke.append(0.5 * float(np.sum(m * np.sum(v * v, axis=1))))
            if lay["has_wall"]:
                # primitive wall: R* = R, its force from the same Hertz law LIGGGHTS applied
                cf[n - 1] = a[-1] * max(r[-1] - (lay["wall_x"] - x[-1]), 0.0) ** 1.5
            pe.append(DRV.chain_potential(a, r, x, lay))
            if len(pr):
                i, j, f = _pairs_on_first(pr)
                ok = j == i + 1
                # force on the striker-side bead points back (-x) when compressed
                cf[i[ok]] = -f[ok, 0]
            cf_rows.append(cf)
        data = DRV.chain_datasets(np.array(cf_rows).reshape(len(steps), nc), ke, pe, n, lay["has_wall"])
    else:
        x = DRV.crystal(case, system)
        lay, layer, fixed, mass = x.lay, x.layer, x.fixed, x.m
        nl = lay["nlayers"]
        cp = x.c
        clip = cp["normal_tension"] == "clip"
        # the law's parameters of the dashpot correction (Hertz-Mindlin: per contact; xclib.laws)
        dl = L.law_of(cp).liggghts_dump(cp, r, lay)
        gamma_n, gamma_t, kt, normal = dl["gamma_n"], dl["gamma_t"], dl["kt"], dl["normal"]
        mobile = DRV.mobile(case, x)
        layers = DRV.LayerRows(lay, x.pos)
        for s, cols, rows, pr in frames:
            steps.append(s)
            p = rows[:, [cols.index("x"), cols.index("y"), cols.index("z")]]
            v = rows[:, [cols.index("vx"), cols.index("vy"), cols.index("vz")]]
            if not pair_dumps:   # _record_without_pair_dumps: stress/atom's zz is minus the virial
                vol = lay["box_x"] * lay["box_y"] * lay["l0"]
                szz = -np.bincount(layer, rows[:, cols.index("c_sa[3]")], nl) / vol
                layers.add(p, v, layer, szz, None)
                continue
            correct = None
            if gamma_n > 0.0 and s > 0:   # step 0: the setup force already saw v(0), as the dump does
                fa = rows[:, [cols.index("fx"), cols.index("fy"), cols.index("fz")]]

                def correct(i1, i2, ff, shear=None, p=p, v=v, fa=fa):
                    if shear is not None and gamma_t == 0.0:   # the Coulomb test of the step, not the dump's
                        k = kt(i1, i2, p)[:, None] if callable(kt) else kt
                        ff = tangential_at_step(p, i1, i2, ff, shear, k, lay["box_x"], lay["box_y"])
                    return dashpot_at_half_step(p, v, fa, mass, mobile, dt, i1, i2, ff, r, gamma_n,
                                                lay["box_x"], lay["box_y"], clip, normal)
            i, j, f = _pairs_on_first(pr, correct) if len(pr) else (np.zeros(0, int), np.zeros(0, int), np.zeros((0, 3)))
            szz, szx = T.layer_stress(p, r, layer, fixed, i, j, f, lay["box_x"], lay["box_y"], lay["l0"], nl)
            layers.add(p, v, layer, szz, szx)
        data = layers.datasets(len(steps))
    times = np.array(steps, float) * dt
    extra = {"dt": dt, "deck": open(os.path.join(workdir, "in.case")).read()}
    if "/crystal/layer_z" in data:
        cp = T.contact_params(case)
        extra["lever_arm"] = T.lever_arm_used(cp, "LIGGGHTS")
        extra["normal_tension"] = cp["normal_tension"]          # limitForce off / on: both available
        extra["coulomb_normal"] = T.coulomb_normal_used(cp, "LIGGGHTS")
        extra["contact_law"] = L.law_of(cp).NAME
        if "contact_distance_factor" in extra["deck"]:
            # measured (probe_linear.py): with the factor a contact that opens loses its spring, as in LAMMPS
            extra["history_on_contact_loss"] = "zeroed"
        extra.update(L.law_of(cp).liggghts_attrs(cp))
        if not pair_dumps:
            extra["layer_stress"] = ("sigma_zz from compute stress/atom (equal radii); no sigma_zx: pair dumps would "
                                     "turn rolling_friction luding's spring, stress/atom's xz is delx fz")
    T.write_trace(out, code="liggghts", code_version=version, case_text=case_text, case_name=case["case"]["name"],
                  system_path=system_path, time_convention=TIME_CONVENTION, time=times, datasets=data,
                  extra_attrs=extra)


# refused: a law LIGGGHTS cannot express (damping_ratio beyond its hertz damping)
DRIVER = DRV.DeckDriver(name="liggghts_case", code="liggghts", title="LIGGGHTS", package="liggghts",
                        exe_option="liggghts", exe_default="liggghts", version_prefix="LIGGGHTS", refused=(ValueError,),
                        render=render, convert=convert, doc=__doc__)


def render_impact(s, work: str) -> dict:
    """An impact deck (data/SCHEMA.md §7): body 1 type 1, body 2 or the wall type 2, the contact by
    xclib.hertz_mindlin (liggghts_impact), every step dumped at full precision (xclib.impact)."""
    from xclib import hertz_mindlin_impact as HM
    from xclib import impact as I
    lines, attrs = HM.liggghts_impact(s)
    I.data_file(s, os.path.join(work, "data.system"), "Atoms")
    masses = "\n".join("set             atom %d mass %r" % (k + 1, b.mass) for k, b in enumerate([s.b1, s.b2]) if b)
    deck = ("# granwave impact case %s -> LIGGGHTS (liggghts_inputs/liggghts_case.py; MAPPING.md, \"Impact\")\n"
            "units           si\natom_style      granular\natom_modify     map array\nboundary        f f f\n"
            "newton          off\ncommunicate     single vel yes\nread_data       data.system\n%s\n" % (s.name, masses)
            + lines + I.deck_run(s, "", "format"))
    with open(os.path.join(work, "in.case"), "w") as f:
        f.write(deck)
    attrs["deck"] = deck
    return attrs


def main(argv) -> int:
    from xclib import impact as I
    if argv and I.is_impact(argv[0]):
        return I.main(argv, code="liggghts", title="LIGGGHTS", exe_option="liggghts", exe_default="liggghts",
                      render=render_impact, version_prefix="LIGGGHTS")
    return DRIVER.main(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
