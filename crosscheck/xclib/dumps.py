"""Text dumps of LIGGGHTS and LAMMPS, read one frame at a time, and the writers' alignments of the
dumped contact forces to the forces of the step (liggghts_inputs/MAPPING.md, "Time conventions").

Both codes write `dump custom` (atoms) and `dump local` (contacts) in the same text layout. A paper
crystal writes 1200 frames of 3200 atoms and 19 136 contacts (2-4 GB of text): the converters hold
one frame of each dump at a time (`frames`, `lockstep`), never the file.

Only numpy: imported by the LIGGGHTS and LAMMPS drivers under /usr/bin/python3.
"""
from __future__ import annotations

import itertools
import os
import warnings

import numpy as np


class DumpError(ValueError):
    """A malformed dump (a copy cut short, a full disk, a damaged file): names the file, the line and
    what was expected. The drivers report it as a failed conversion, never a traceback."""


def frames(path: str):
    """Yield (timestep, column names, rows [n, ncol]) for each frame of a text dump (custom or
    local), streaming the file frame by frame; each body is parsed by numpy's C parser. A malformed
    frame raises DumpError; a row count the rest of the file could not hold is refused before
    anything is read (every line ends the file or holds at least one character and its newline)."""
    size = os.path.getsize(path)
    with open(path, "rb") as f:
        lineno = 0

        def line_of(what):
            nonlocal lineno
            ln = f.readline()
            lineno += 1
            if not ln:
                raise DumpError("%s: ends at line %d where %s was expected (a copy cut short?)" % (path, lineno, what))
            return ln

        def integer(what):
            ln = line_of(what)
            try:
                return int(ln)
            except ValueError:
                raise DumpError("%s: line %d: expected %s, found %r" % (path, lineno, what, ln[:60])) from None

        while True:
            line = f.readline()
            lineno += 1
            if not line:
                return
            if not line.startswith(b"ITEM: TIMESTEP"):
                continue
            step = integer("the time step")
            line_of("ITEM: NUMBER OF ATOMS | ENTRIES")
            n = integer("the number of rows")
            if n < 0 or n > (size - f.tell()) // 2 + 1:
                raise DumpError("%s: line %d: step %d claims %d rows, more than the rest of the file holds"
                                % (path, lineno, step, n))
            line = line_of("ITEM: ATOMS | ENTRIES")
            while not (line.startswith(b"ITEM: ATOMS") or line.startswith(b"ITEM: ENTRIES")):
                line = line_of("ITEM: ATOMS | ENTRIES of step %d" % step)
            try:
                cols = line.decode().split()[2:]
            except UnicodeDecodeError:
                raise DumpError("%s: line %d: column names are not text" % (path, lineno)) from None
            if n and not cols:
                raise DumpError("%s: line %d: step %d has %d rows but no columns" % (path, lineno, step, n))
            body = b"".join(itertools.islice(f, n))
            lineno += n
            try:
                with warnings.catch_warnings():   # numpy warns, then stops, at the first token that is no number
                    warnings.simplefilter("ignore")
                    vals = np.fromstring(body.decode(), sep=" ") if n else np.zeros(0)   # C parser; size checked
            except (UnicodeDecodeError, ValueError):
                vals = None
            if vals is None or vals.size != n * len(cols):
                raise DumpError("%s: step %d (before line %d) has %s values, expected %d x %d numbers"
                                % (path, step, lineno, "unreadable" if vals is None else vals.size, n, len(cols)))
            yield step, cols, vals.reshape(n, len(cols))


def lockstep(atoms_path: str, pairs_path: str):
    """Yield (step, atom columns, atom rows, pair rows) with the two dumps read side by side, one
    frame each in memory. Both dumps are written at the same steps; a step missing from either (a
    run stopped while writing) ends the iteration with an error naming it."""
    pa = frames(pairs_path)
    for step, cols, rows in frames(atoms_path):
        try:
            pstep, _, prow = next(pa)
        except StopIteration:
            raise DumpError("%s ends before step %d of %s" % (pairs_path, step, atoms_path)) from None
        if pstep != step:
            raise DumpError("%s: step %d where %s has step %d" % (pairs_path, pstep, atoms_path, step))
        yield step, cols, rows, prow


def columns(cols, rows, names):
    """rows[:, [index of each name]] (a KeyError names the missing column)."""
    try:
        return rows[:, [cols.index(n) for n in names]]
    except ValueError:
        raise KeyError("dump has columns %s, not all of %s" % (cols, names)) from None


def unique_rows(rows: np.ndarray, first_force_col: int = 3, ncols: int = 6):
    """(id1, id2, the ncols columns from first_force_col) of the first dumped row of each physical
    contact, as dumped. With newton off a contact across a periodic boundary can be listed from both
    sides; ids are 1-based in the dump, 0-based here."""
    i = rows[:, 0].astype(int) - 1
    j = rows[:, 1].astype(int) - 1
    key = np.minimum(i, j).astype(np.int64) * (1 << 32) + np.maximum(i, j)
    _, first = np.unique(key, return_index=True)
    return i[first], j[first], rows[first, first_force_col:first_force_col + ncols]


def on_lower_id(i, j, f):
    """(a, b, force on a) with a = min(i, j): each contact once, force turned to the lower index."""
    a = np.minimum(i, j)
    b = np.maximum(i, j)
    sgn = np.where(i == a, 1.0, -1.0)
    return a, b, f * sgn[:, None]


def contact_normals(p, i, j, box_x, box_y):
    """(unit normal from j to i, centre distance, periodic shift flag of j) with minimum image in x, y."""
    d = p[i] - p[j]
    sx = np.round(d[:, 0] / box_x)
    sy = np.round(d[:, 1] / box_y)
    d[:, 0] -= box_x * sx
    d[:, 1] -= box_y * sy
    r = np.linalg.norm(d, axis=1)
    return d / r[:, None], r, (sx != 0) | (sy != 0)


def half_step_velocities(v, f_atoms, m, mobile, dt):
    """v(t - dt/2) = v(t) - f(t)/m dt/2 of the integrated particles (velocity Verlet); others as dumped."""
    vh = np.array(v, float, copy=True)
    mob = np.asarray(mobile, bool)
    vh[mob] -= np.asarray(f_atoms, float)[mob] / np.asarray(m, float)[mob][:, None] * (0.5 * dt)
    return vh


def dashpot_at_half_step(p, v, f_atoms, m, mobile, dt, i, j, f_pair, radius, gamma_n, box_x, box_y, clip=False,
                         normal=None):
    """The force each contact applied in the step, from the force the dump recomputed.

    LIGGGHTS' `compute pair/gran/local` and LAMMPS' `compute pair/local` (through the pair style's
    single()) recompute the contact forces at dump time (after final_integrate), so the normal
    dashpot sees the velocity of the owned atom i at v(t) -- and, for a pair across a periodic
    boundary, the ghost image of j at the half-step velocity v(t - dt/2) communicated before the
    step's force (ghosts are not touched by final_integrate). The step itself (and granwave, YADE)
    fed the dashpot v(t - dt/2) = v(t) - f(t)/m dt/2 for both (f: the dumped per-atom total force,
    the step's). The difference gamma_n (ddelta_half - ddelta_used) n is put back, so the trace
    carries the forces that moved the particles (verified: the corrected pair forces sum to the
    dumped per-atom forces to 1e-16 N). Only the normal dashpot is corrected (gamma_t = 0). p, v,
    f_atoms [n, 3]; i (id of the dumped row, owned), j; f_pair: force on i, rows as dumped (not
    reordered); one MPI rank.

    clip (normal_tension = "clip": LIGGGHTS `limitForce on`, LAMMPS `limit_damping`): the step's
    normal force was max(kn delta + gamma_n ddelta_half, 0) and the dump's max(kn delta + gamma_n
    ddelta_used, 0); where either one was cut to zero the difference is not the dashpot difference,
    so the normal force of the step is computed whole (normal: the law's). Measured on the
    prestressed velocity drive with "clip" (contacts opening with the dashpot pulling): LIGGGHTS vs
    granwave and YADE 4.2e-5 at z/l0 = 10 with the additive correction, with the same dynamics (layer
    velocities 1e-10); 5.6e-10 computed whole.

    normal(r_i, r_j, m_i, m_j, delta) -> (elastic force, dashpot) of these contacts: the law's mapping
    module's `normal_force(c)` (xclib.laws; Hertz-Mindlin's dashpot depends on the contact, and gamma_n
    is then only a flag: > 0 when damped). None: the dashpot gamma_n and no elastic force (without clip)."""
    if gamma_n == 0.0 or len(i) == 0:
        return f_pair
    vh = half_step_velocities(v, f_atoms, m, mobile, dt)
    n, r, ghost_j = contact_normals(p, i, j, box_x, box_y)   # n from j to i
    touching = r < radius[i] + radius[j]
    vj_used = np.where(ghost_j[:, None], vh[j], v[j])        # j seen through a periodic image: half-step
    dd_used = -np.sum(n * (v[i] - vj_used), axis=1)
    dd_half = -np.sum(n * (vh[i] - vh[j]), axis=1)
    delta = np.maximum(radius[i] + radius[j] - r, 0.0)
    if normal is not None:
        f_el, gamma_n = normal(radius[i], radius[j], m[i], m[j], delta)
    else:
        f_el = 0.0 * delta
    if clip:
        fn_step = np.where(touching, np.maximum(f_el + gamma_n * dd_half, 0.0), 0.0)
        return f_pair + (fn_step - np.sum(f_pair * n, axis=1))[:, None] * n
    corr = np.where(touching, gamma_n * (dd_half - dd_used), 0.0)
    return f_pair + corr[:, None] * n
