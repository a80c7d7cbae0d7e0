# YADE driver for granwave cases (chain and crystal).
#
#   yade -n -x yade_scripts/run_case.py CASE.toml SYSTEM.h5 OUT.h5
#
# Reads the case (TOML) and granwave's system file (data/SCHEMA.md §2), never re-draws anything,
# runs YADE and writes the trace file of SCHEMA.md §3 with h5py. Prints one JSON line
# ({"code": "yade", "wall_s": ..., "steps": ..., ...}) on stdout at the end.
#
# Time convention (made synchronous, exactly):
#  * YADE integrates leapfrog: a body's stored velocity is v(t - dt/2). Velocity Verlet (granwave,
#    LIGGGHTS) starts from v(0). The two give identical trajectories when the leapfrog starts
#    from v(-dt/2) = v(0) - F(0)/m dt/2, so F(0) is evaluated first (a step with NewtonIntegrator
#    dead) and the initial velocities are set accordingly. Without this an impulsive start (the
#    step of the source layers) leads the velocity-Verlet codes by dt/2.
#  * In a PyRunner placed after NewtonIntegrator, forces belong to the time t of the step,
#    positions to t + dt and velocities to t + dt/2. The writer labels the sample with t and
#    shifts positions x(t) = x - v dt and velocities v(t) = v - F(t)/m dt/2 (exact for the scheme).
#  * Crystals (dashpots possible): the leapfrog start above would give the first dashpot force the
#    velocity v(-dt/2) instead of v(0), so `first_verlet_step` evaluates F(0) with v(0), does the
#    first half kick and drift itself and takes the t = 0 sample from that state; from then on the
#    dashpots (ViscEl) see the velocity half a step behind the force, as granwave and LIGGGHTS.
#  * Crystal shear increments: Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting=False) (the default
#    scales the translational part by (r1+r2)/(r1+r2-delta): kt 1e-3 too stiff here).
import math
from itertools import repeat
from operator import attrgetter, itemgetter
import os
import sys
import time as _time

_me = sys.argv[0] if sys.argv and sys.argv[0].endswith("run_case.py") else globals().get("__file__", "")
HERE = os.environ.get("GRANWAVE_YADE_SCRIPTS") or os.path.dirname(os.path.abspath(_me))
sys.path.insert(0, os.path.join(HERE, "..", "crosscheck"))

import numpy as np  # noqa: E402

from xclib import driver as DRV  # noqa: E402
from xclib import laws as L  # noqa: E402
from xclib import traces as T  # noqa: E402

from yade import O, utils  # noqa: E402
import yade.wrapper  # noqa: E402  (the crystal's contact classes: xclib.linear, xclib.hertz_mindlin)
from yade.wrapper import (  # noqa: E402
    ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb, InteractionLoop, Ig2_Sphere_Sphere_ScGeom, Ig2_Sphere_Sphere_ScGeom6D,
    Law2_ScGeom6D_CohFrictPhys_CohesionMoment,
    Ip2_FrictMat_FrictMat_MindlinPhys, Law2_ScGeom_MindlinPhys_Mindlin, NewtonIntegrator, PyRunner, FrictMat)
from yade.minieigenHP import Vector3  # noqa: E402

# YADE 2023.02a's Mindlin gives box/wall bodies R* = R/2 (wrong): the wall is a fixed sphere this big
# (R* error r/R_wall). XC_YADE_WALL_RADIUS overrides it (used to show where chain differences come from).
WALL_SPHERE_RADIUS = float(os.environ.get("XC_YADE_WALL_RADIUS", "1000.0"))  # m


def fail(msg, code=2):
    sys.stderr.write("run_case.py: " + msg + "\n")
    sys.stdout.flush()
    os._exit(code)


def yade_version():
    try:
        import yade.config
        return "yade " + str(yade.config.version)
    except Exception:
        return "yade"


class Sampler:
    """Called by a PyRunner after NewtonIntegrator; collects synchronous samples."""

    def __init__(self, every, record, ids_free, dt):
        self.every, self.record, self.dt = every, record, dt
        self.t0_iter = None
        self.times, self.rows = [], []
        self.cost = 0.0   # seconds spent sampling (subtracted for the solver's own speed)

    def __call__(self):
        k = O.iter - self.t0_iter          # physical step index; forces belong to t = k dt
        if k < 0 or k % self.every:
            return
        self.take(k)

    def take(self, k):
        t = _time.time()
        self.times.append(k * self.dt)
        self.rows.append(self.record())
        self.cost += _time.time() - t


# Fast crystal sampling. The per-sample record() used to rebuild everything through YADE's Python API:
# measured on the paper packing (3200 particles, 19 136 contacts, machine under load 2): listing the
# real interactions 28 ms, their ids 15 ms, phys 16 ms, reading normalForce 24-70 ms and turning the
# Vector3s into floats with v[0], v[1], v[2] 27-43 ms (as much again for shearForce), sync_state 43 ms,
# T.layer_stress 34 ms (np.add.at): 0.19 s per sample, 232 of the 317 s of crystal_p. YADE 2023.02a
# has no bulk accessor for interaction forces (O.interactions.all(True) still makes one Python object
# per interaction, 12 ms), and any C++ summary (utils.bodyStressTensors) sums in another order and with
# other arms: the P cases' sigma_zx, u_x, v_x are pure round-off (1e-7 Pa, 1e-17 m), so only the same
# arithmetic on the same numbers keeps every dataset within 1e-12 of its peak. So record() now
#  * keeps the list of real interactions, their ids and phys objects while the contact set is unchanged
#    (checked every sample: same container size, same countReal(), every kept interaction still real:
#    10 ms; InteractionContainer::requestErase resets geom and phys of an opening contact at once, so
#    a stale force is never read; any change re-reads everything in container order, as before. The
#    fixtures' polydisperse packing re-reads 50 times in 201 samples, the others once);
#  * converts Vector3s with map(itemgetter(0, 1, 2), map(attrgetter(...), objs)) (no Python loop:
#    63 ms instead of 70 + 43 ms for the normal forces) and keeps the State objects of the bodies;
#  * T.layer_stress and T.layer_mean sum with np.bincount instead of np.add.at: the same sequential
#    double additions in the same order (bitwise equal).
# Result on crystal_p (same system, same load): 194 -> 68.5 ms per sample, YADE wall 317 -> 167 s (its
# own stepping 85 s either way); every trace dataset bitwise equal to the old driver's, also on the four
# crystal fixtures (undamped, damped, sliding, polydisperse).
_XYZ = itemgetter(0, 1, 2)


def vec3_array(vectors):
    """[n, 3] float array from an iterable of YADE Vector3 (same values as (v[0], v[1], v[2]))."""
    return np.array(list(map(_XYZ, vectors)), float).reshape(-1, 3)


def sync_state(ids, masses, dt, fixed, states=None):
    """Positions and velocities at the force time t (see the header). `states`: the bodies' State
    objects, if the caller keeps them (they live as long as the bodies)."""
    st = states if states is not None else [O.bodies[i].state for i in ids]
    pos = vec3_array(map(attrgetter("pos"), st))
    vel = vec3_array(map(attrgetter("vel"), st))
    frc = vec3_array(map(O.forces.f, ids, repeat(True)))
    pos = pos - vel * dt
    vs = vel - frc / masses[:, None] * (0.5 * dt)
    vs[fixed] = vel[fixed]
    return pos, vs


def start_leapfrog(ids, masses, v0, fixed, dt, newton, runner):
    """Evaluate F(0) with NewtonIntegrator dead, then set v(-dt/2) = v(0) - F(0)/m dt/2."""
    newton.dead = True
    runner.dead = True
    O.step()
    for k, i in enumerate(ids):
        if fixed[k]:
            continue
        f = np.array(tuple(O.forces.f(i, True)))
        v = v0[k] - f / masses[k] * (0.5 * dt)
        O.bodies[i].state.vel = Vector3(*v)
    newton.dead = False
    runner.dead = False


# ------------------------------------------------------------------------------------------ chain
def run_chain(case, system, dt, nsteps, every):
    lay = T.chain_layout(system)
    n = lay["n"]
    mats = {}
    names = system["material_names"]
    mi = np.asarray(system["material_index"], int)
    e, nu = np.asarray(system["youngs_modulus"]), np.asarray(system["poisson_ratio"])
    for k in range(n):
        key = (float(e[k]), float(nu[k]))
        if key not in mats:
            mats[key] = O.materials.append(FrictMat(young=key[0], poisson=key[1], frictionAngle=0.0,
                                                    density=1000.0, label="m%d_%s" % (len(mats), names[mi[k]])))
    pos = np.asarray(system["position"], float)
    r = np.asarray(system["radius"], float)
    m = np.asarray(system["mass"], float)
    inertia = np.asarray(system["inertia"], float)
    v0 = np.asarray(system["velocity"], float)
    ids = []
    for k in range(n):
        b = utils.sphere(Vector3(*pos[k]), float(r[k]), material=mats[(float(e[k]), float(nu[k]))], fixed=False)
        b.state.mass = float(m[k])
        b.state.inertia = Vector3(*([float(inertia[k])] * 3))
        ids.append(O.bodies.append(b))
    wall_id = None
    if lay["has_wall"]:
        wm = O.materials.append(FrictMat(young=float(system["attrs"]["wall_youngs_modulus"]),
                                         poisson=float(system["attrs"]["wall_poisson_ratio"]),
                                         frictionAngle=0.0, density=1000.0, label="wall"))
        c = Vector3(lay["wall_x"] + WALL_SPHERE_RADIUS, float(pos[-1, 1]), float(pos[-1, 2]))
        wall_id = O.bodies.append(utils.sphere(c, WALL_SPHERE_RADIUS, material=wm, fixed=True))
    O.dt = dt
    newton = NewtonIntegrator(damping=0.0, gravity=(0, 0, 0))
    pairs = [(k, k + 1) for k in range(n - 1)] + ([(n - 1, wall_id)] if wall_id is not None else [])
    fixed = np.zeros(n, bool)

    def record():
        cf = np.zeros(len(pairs))
        for c, (a, b) in enumerate(pairs):
            if O.interactions.has(a, b):
                it = O.interactions[a, b]
                if it.isReal:
                    cf[c] = float(it.phys.normalForce.dot(it.geom.normal))
        p, v = sync_state(ids, m, dt, fixed)
        ke = 0.5 * float(np.sum(m * np.sum(v * v, axis=1)))
        return cf, ke, p

    sampler = Sampler(every, record, ids, dt)
    runner = PyRunner(command="__import__('builtins').xc_sampler()", iterPeriod=1)
    __import__("builtins").xc_sampler = sampler
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_FrictMat_FrictMat_MindlinPhys()],
                                 [Law2_ScGeom_MindlinPhys_Mindlin()]),
                 newton, runner]
    start_leapfrog(ids, m, v0, fixed, dt, newton, runner)
    sampler.t0_iter = O.iter
    runner.iterPeriod = every           # fire only on sampled steps (Python per step is costly)
    runner.iterLast = O.iter - every
    t = _time.time()
    O.run(nsteps + 1, True)
    if len(sampler.times) != nsteps // every + 1:
        fail("sampling misaligned: %d samples, expected %d" % (len(sampler.times), nsteps // every + 1), 1)
    wall = _time.time() - t
    cf = np.array([row[0] for row in sampler.rows])
    ke = np.array([row[1] for row in sampler.rows])
    # potential energy from the synchronous positions (Hertz: 2/5 A delta^5/2)
    a = np.asarray(system["hertz_constant"], float)
    pe = [DRV.chain_potential(a, r, row[2][:, 0], lay) for row in sampler.rows]
    data = DRV.chain_datasets(cf, ke, pe, n, lay["has_wall"])
    return np.array(sampler.times), data, wall, n, sampler.cost


def first_verlet_step(ids, masses, v0, fixed, dt, newton, runner, sampler, f0_dt=0.0):
    """Crystal start: F(0) at x(0), v(0) (NewtonIntegrator dead: the dashpots see v(0), as in
    velocity Verlet), then the first half kick and drift are done here, v(dt/2) = v(0) + F(0)/m dt/2,
    x(dt) = x(0) + v(dt/2) dt (fixed bodies keep their velocity), and the t = 0 sample is taken from
    that state, exactly as a PyRunner after NewtonIntegrator would see it. YADE's own loop then
    starts with F(dt) computed from x(dt) and v(dt/2): identical to velocity Verlet from the first
    step on. (Starting the leapfrog from v(-dt/2) = v(0) - F(0)/m dt/2 instead, as for chains, gives
    the same trajectory without dashpots, but the first dashpot force would see v(-dt/2) != v(0).)

    F(0) is evaluated with O.dt = 0: the contact laws add their shear increments (relative velocity
    x O.dt) in every step, also in this one, while velocity Verlet's F(0) (granwave; LIGGGHTS' setup,
    PairGran::compute with shearupdate_ = 0) does not move the history. With the velocity drive the
    source already has v(0) here, so with O.dt = dt the springs between the source and the first free
    layer started pre-loaded by ks v_t(0) dt (Law2_ScGeom_ViscElPhys_Basic: shearForce += ks dt
    shearVelocity): measured +5.0 Pa in the t = 0 sigma_zz of layers 1-2, 1.1e-5 of the peak at z/l0
    = 10 (9.4e-5 in layer 1, 2.7e-5 in the layer velocities) on the prestressed 4x4x40 velocity drive
    (1e-3 m/s, gamma_n = 0.1, kt = k); without it YADE = LIGGGHTS to all digits until the first
    contacts pull (t = 21 us), and to 5.5e-10 throughout with normal_tension = "clip". The normal
    force and the dashpots do not involve O.dt; with the displacement drive (v = 0 here) the increment
    was exactly zero already. Law2_ScGeom_MindlinPhys_Mindlin divides by O.dt (its shear force is NaN at
    O.dt = 0), so Hertz-Mindlin runs pass f0_dt = 1e-300 s: increments of 1e-300 v, nothing at double
    precision."""
    newton.dead = True
    runner.dead = True
    dt_run = O.dt
    O.dt = f0_dt
    O.step()
    O.dt = dt_run
    for k, i in enumerate(ids):
        st = O.bodies[i].state
        v = np.array(tuple(v0[k]), float) if not fixed[k] else np.array(tuple(st.vel), float)
        if not fixed[k]:
            v = v + np.array(tuple(O.forces.f(i, True))) / masses[k] * (0.5 * dt)
        st.vel = Vector3(*v)
        st.pos = st.pos + Vector3(*(v * dt))
    sampler.t0_iter = O.iter - 1      # inside the next O.step O.iter is this value + 1: physical step 1 (F(dt))
    sampler.take(0)
    newton.dead = False
    runner.dead = False


# ---------------------------------------------------------------------------------------- crystal
class CrystalContacts:
    """The real interactions in YADE's container order, re-read only when the set changes."""

    def __init__(self):
        self.real = None
        self.rereads = 0

    def current(self):
        if self.real is not None and len(O.interactions) == self.ntotal and \
                O.interactions.countReal() == len(self.real) and all(map(attrgetter("isReal"), self.real)):
            return False
        self.real = [it for it in O.interactions if it.isReal]
        self.ntotal = len(O.interactions)
        self.rereads += 1
        self.ii = np.array([it.id1 for it in self.real], int)
        self.jj = np.array([it.id2 for it in self.real], int)
        self.phys = [it.phys for it in self.real]
        return True

    def forces_on_id1(self, has_shear):
        # force on id1 = -(normalForce + shearForce) (YADE applies +F to id2)
        ff = -vec3_array(map(attrgetter("normalForce"), self.phys))
        if has_shear:
            ff -= vec3_array(map(attrgetter("shearForce"), self.phys))
        return ff


def run_crystal(case, system, dt, nsteps, every):
    x = DRV.crystal(case, system)
    c, ex, lay, pos, r, m, fixed, layer = x.c, x.ex, x.lay, x.pos, x.r, x.m, x.fixed, x.layer
    inertia = np.asarray(system["inertia"], float)
    n = len(m)
    # The source. A displacement drive moves all bottom fixed layers by a held step; a velocity drive
    # (granwave: set_mobile) makes the innermost bottom fixed layer free particles with an initial
    # velocity, integrated from then on (not moved at a constant velocity), between the fixed layers
    # below it (the wall that holds the prestress) and the first free layer.
    vdrive = ex["drive"] != "displacement"
    source = T.source_of(lay, fixed, ex["drive"])   # by layer (FCC) or by role (a packing file's slabs)
    dyn_fixed = fixed & ~source if vdrive else fixed
    # YADE keeps one interaction per particle pair: a particle must not touch two images of one neighbour
    if lay["generator"] == "fcc":
        cells = case["crystal"]["cells"]
        if min(int(cells[0]), int(cells[1])) < 3:
            fail("YADE keeps one interaction per particle pair: a periodic layer needs >= 3 particles in x "
                 "and y (this case has %d x %d), otherwise a particle touches two images of the same neighbour"
                 % (int(cells[0]), int(cells[1])))
    elif min(lay["box_x"], lay["box_y"]) < 6 * float(np.max(r)):
        fail("YADE keeps one interaction per particle pair: the periodic box (%g x %g m) must be at least three "
             "largest diameters (%g m) across, otherwise a particle touches two images of the same neighbour"
             % (lay["box_x"], lay["box_y"], 6 * float(np.max(r))))
    law = L.law_of(c)   # the law's mapping onto YADE (xclib.linear, xclib.hertz_mindlin)
    has_shear = law.tangential(c)
    if c["mu_static"] != c["mu_dynamic"] and has_shear:
        sys.stderr.write("run_case.py: YADE has one friction coefficient; using mu_static=%g (mu_dynamic=%g "
                         "ignored: a documented difference)\n" % (c["mu_static"], c["mu_dynamic"]))
    phi = math.atan(c["mu_static"])
    from xclib.codefacts import NOT_EXPRESSIBLE, Unsupported
    try:
        mat, ip2, law2 = law.yade_interaction(c, yade.wrapper, phi)
    except Unsupported as e:
        fail("%s: %s YADE: %s" % (case["case"]["name"], NOT_EXPRESSIBLE, e))
    six_d = isinstance(law2, Law2_ScGeom6D_CohFrictPhys_CohesionMoment)   # rolling and torsion
    if six_d:
        if float(np.max(r)) != float(np.min(r)):
            fail("%s: %s YADE: rolling/torsion resistance is mapped for YADE for equal radii only (CohesionMoment's "
                 "stiffness a_i a_j and limit lever min(a_i, a_j))" % (case["case"]["name"], NOT_EXPRESSIBLE))
        mat.young = law.yade_young(c, float(r[0]))    # the law's map of its kn for these radii
    mat = O.materials.append(mat)
    zoff = 2 * float(np.max(r))
    lz = float(np.ptp(pos[:, 2])) + 4 * zoff + 10 * float(np.max(r))
    O.periodic = True
    O.cell.setBox(lay["box_x"], lay["box_y"], lz)
    ids = []
    for k in range(n):
        b = utils.sphere(Vector3(pos[k, 0], pos[k, 1], pos[k, 2] + zoff), float(r[k]), material=mat,
                         fixed=bool(dyn_fixed[k]))
        b.state.mass = float(m[k])
        b.state.inertia = Vector3(*([float(inertia[k])] * 3))
        ids.append(O.bodies.append(b))
    O.dt = dt
    newton = NewtonIntegrator(damping=0.0, gravity=(0, 0, 0))
    nl = lay["nlayers"]
    x0 = pos.copy()
    layers = DRV.LayerRows(lay, x0)

    states = [O.bodies[i].state for i in ids]   # kept: they live as long as the bodies
    dyn_fixed_mask = np.zeros(n, bool) | dyn_fixed
    contacts = CrystalContacts()

    def record():
        p, v = sync_state(ids, m, dt, dyn_fixed_mask, states)
        p[:, 2] -= zoff
        contacts.current()
        ff = contacts.forces_on_id1(has_shear)
        # positions of id2 across the periodic boundary: layer_stress takes the minimum image in x, y
        szz, szx = T.layer_stress(p, r, layer, fixed, contacts.ii, contacts.jj, ff, lay["box_x"], lay["box_y"],
                                  lay["l0"], nl)
        layers.add(p, v, layer, szz, szx, periodic=False)

    sampler = Sampler(every, record, ids, dt)
    runner = PyRunner(command="__import__('builtins').xc_sampler()", iterPeriod=1)
    __import__("builtins").xc_sampler = sampler
    # avoidGranularRatcheting=False: the shear increment is the relative velocity of the contact point
    # times dt. YADE's default (True) multiplies the translational part by alpha = (r1 + r2)/(r1 + r2 -
    # delta) = 1/(1 - 1e-3) here, which makes CundallStrack's effective kt 1e-3 stiffer (measured: P speed
    # 2.6e-4 faster than LIGGGHTS with kt = k). ViscEl computes its own contact-point velocity (no alpha).
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([(Ig2_Sphere_Sphere_ScGeom6D if six_d else Ig2_Sphere_Sphere_ScGeom)(
                     avoidGranularRatcheting=False)], [ip2], [law2]),
                 newton, runner]
    # contacts are made in the undisplaced packing (tangential springs start from zero there) ...
    newton.dead = True
    runner.dead = True
    O.step()
    # Drain this step's forces. YADE's ForceContainer (OpenMP build) accumulates into per-thread
    # buffers that only sync() (NewtonIntegrator, or f(id, True)) adds up and zeroes; ForceResetter
    # zeroes the summed array only. With NewtonIntegrator dead nothing syncs here, so the F(0) that
    # first_verlet_step reads after its own O.step() would be the sum of both steps' forces: measured
    # on the relaxed polydisperse 4x4x40 crystal (residual forces up to 2.0e-5 N on free particles)
    # F(0) = F(undisplaced) + F(displaced) to 5e-12 N, i.e. a doubled first half kick (2.4e-7 m/s,
    # layer-mean v_z off by 6e-8 m/s from the first sample, sigma_zz 8.4e-4 of the peak at z/l0 = 36).
    # Invisible on perfect (monodisperse) crystals, where the undisplaced packing has zero net forces.
    O.forces.f(ids[0], True)
    nreal = sum(1 for it in O.interactions if it.isReal)
    law.yade_check(c, O, ids, r, m, dyn_fixed, fail)   # the interactions YADE made, as the law maps them
    # ... then the source (the bottom fixed layers; for a velocity drive the innermost one) makes its
    # step, and the leapfrog starts.
    src = [k for k in range(n) if source[k]]
    axis = 2 if ex["mode"] == "P" else 0
    v0 = np.zeros((n, 3))
    if ex["drive"] == "displacement":
        shift = float(ex["amplitude"]) * lay["d"]
        for k in src:
            p = O.bodies[ids[k]].state.pos
            p[axis] += shift
            O.bodies[ids[k]].state.pos = p
            x0[k, axis] += 0.0  # displacement outputs are measured from the undisplaced packing
    else:
        for k in src:
            v0[k, axis] = float(ex["amplitude"])
            O.bodies[ids[k]].state.vel = Vector3(*v0[k])   # F(0) below sees v(0), as LIGGGHTS' setup
    first_verlet_step(ids, m, v0, dyn_fixed, dt, newton, runner, sampler, law.YADE_F0_DT)
    runner.iterPeriod = every           # fire only on sampled steps (Python per step is costly)
    runner.iterLast = O.iter - 1        # = the step of the t = 0 sample: first fire at physical step `every`
    runner.nDone = max(1, runner.nDone)  # a PeriodicEngine that never ran re-bases iterLast on its first call
    t = _time.time()
    O.run(nsteps, True)
    if len(sampler.times) != nsteps // every + 1:
        fail("sampling misaligned: %d samples, expected %d" % (len(sampler.times), nsteps // every + 1), 1)
    wall = _time.time() - t
    sys.stderr.write("run_case.py: crystal sampling %.1f ms per sample, contact set read %d times\n"
                     % (1e3 * sampler.cost / max(len(sampler.times), 1), contacts.rereads))
    law.yade_after_run(c, contacts.rereads)
    return np.array(sampler.times), layers.datasets(len(sampler.times)), wall, n, nreal, sampler.cost


def run_impact(case_path, out_path, case, text):
    """An impact case (data/SCHEMA.md §7): the spheres (the wall: a fixed sphere of
    HM.YADE_WALL_RADIUS_FACTOR (xclib.hertz_mindlin_impact) radii with the material that makes YADE's mixing exact), every step
    sampled by a PyRunner after NewtonIntegrator and made synchronous as the chain's samples."""
    from xclib import hertz_mindlin_impact as HM
    from xclib import impact as I
    from xclib.codefacts import NOT_EXPRESSIBLE, Unsupported
    try:
        s = I.setup(case, case_path)
        m1, m2, ip2 = HM.yade_impact_materials(s, yade.wrapper, math.atan(s.mu) if s.friction else 0.0)
    except Unsupported as e:
        fail("%s: %s YADE: %s" % (case_path, NOT_EXPRESSIBLE, e))
    O.materials.append(m1)
    O.materials.append(m2)
    b1 = utils.sphere(Vector3(*s.b1.x), s.b1.radius, material=m1)
    if s.b2 is not None:
        b2 = utils.sphere(Vector3(*s.b2.x), s.b2.radius, material=m2)
        other = s.b2
    else:
        rw = s.b1.radius * HM.YADE_WALL_RADIUS_FACTOR
        b2 = utils.sphere(Vector3(*(s.wall.point - rw * s.wall.normal)), rw, material=m2, fixed=True)
        other = None
    bodies = [(b1, s.b1), (b2, other)]
    for b, spec in bodies:
        if spec is not None:
            b.state.mass = spec.mass
            b.state.inertia = Vector3(spec.inertia, spec.inertia, spec.inertia)
            b.state.vel = Vector3(*spec.v)
            b.state.angVel = Vector3(*spec.w)
    i1, i2 = O.bodies.append(b1), O.bodies.append(b2)
    O.dt = s.dt
    rows = []
    iters = []
    phys = []

    def sample():
        # after NewtonIntegrator: F, T of time t; x of t + dt; v, w of t + dt/2 (header)
        row = []
        for i, spec in ((i1, s.b1), (i2, other)):
            if spec is None:
                continue
            st = O.bodies[i].state
            f = np.array(tuple(O.forces.f(i, True)))
            tq = np.array(tuple(O.forces.t(i, True)))
            v = np.array(tuple(st.vel))
            w = np.array(tuple(st.angVel))
            row.append((np.array(tuple(st.pos)) - v * s.dt, v - f / spec.mass * (0.5 * s.dt),
                        w - tq / spec.inertia * (0.5 * s.dt), f))
        rows.append(row)
        iters.append(O.iter)
        inter = O.interactions[i1, i2] if O.interactions.has(i1, i2) else None
        if inter is not None and inter.isReal and not phys:
            phys.append(HM.yade_impact_check(s, inter.phys))

    __import__("builtins").xc_impact_sample = sample
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting=False)], [ip2],
                                 [Law2_ScGeom_MindlinPhys_Mindlin()]),
                 NewtonIntegrator(damping=0.0, gravity=(0, 0, 0)),
                 PyRunner(command="__import__('builtins').xc_impact_sample()", iterPeriod=1)]
    t0 = _time.time()
    # the cases start touching with F(0) = 0: the leapfrog's v(-dt/2) is v(0)
    O.run(s.nsteps, True)
    wall = _time.time() - t0
    # the PyRunner first runs in step 1 (O.iter = 1: the force of x(dt)); sample 0 is the initial state
    # (touching, F(0) = 0)
    rows.insert(0, [(spec.x, spec.v, spec.w, np.zeros(3)) for spec in (s.b1, other) if spec is not None])
    iters.insert(0, 0)
    t = np.array(iters, float) * s.dt
    col = lambda b, q: np.array([r[b][q] for r in rows])  # noqa: E731
    kw = dict(x1=col(0, 0), v1=col(0, 1), w1=col(0, 2), f1=col(0, 3))
    if other is not None:
        kw.update(x2=col(1, 0), v2=col(1, 1), w2=col(1, 2))
    attrs = dict(lever_arm=T.FIXED_LEVER_ARM, coulomb_normal="magnitude",
                 normal_tension="clip", tangential_history=HM.YADE_TANGENTIAL_HISTORY if s.friction else "none",
                 yade_engines="Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting=False) + "
                              "Ip2_FrictMat_FrictMat_MindlinPhys(betan=damping_ratio, betas=0) + Law2_ScGeom_MindlinPhys_Mindlin",
                 wall_model="" if other is not None else
                 "fixed sphere of %g R1, material nu = 1, E = %g E1 (rigid in YADE's E*, G* mixing)" % (
                     HM.YADE_WALL_RADIUS_FACTOR, HM.YADE_RIGID_WALL_FACTOR))
    attrs.update(phys[0] if phys else {})
    conv = ("synchronous: leapfrog from v(-dt/2) = v(0) (the bodies start touching, F(0) = 0); samples taken by a "
            "PyRunner after NewtonIntegrator are labelled with the force time t, x(t) = x(t+dt) - v(t+dt/2) dt, "
            "v(t) = v(t+dt/2) - F(t)/m dt/2, w(t) = w(t+dt/2) - T(t)/I dt/2")
    I.write(out_path, s, text, code="yade", version=yade_version(), time_convention=conv, t=t, attrs=attrs, **kw)
    DRV.summary_line(code="yade", case=s.name, dt=s.dt, steps=s.nsteps, wall_s=wall, particles=2 if other else 1,
                     trace=out_path)


def main(argv):
    if len(argv) == 2 and os.path.exists(argv[0]) and T.load_case(argv[0])[0]["case"].get("model") == "impact":
        if os.path.exists(argv[1]):
            fail("%s exists: nothing is overwritten" % argv[1])
        case, text = T.load_case(argv[0])
        run_impact(argv[0], argv[1], case, text)
        return
    if len(argv) < 3 or argv[0] in ("-h", "--help"):
        sys.stderr.write("usage: yade -n -x yade_scripts/run_case.py CASE.toml SYSTEM.h5 OUT.h5\n"
                         "       yade -n -x yade_scripts/run_case.py IMPACT_CASE.toml OUT.h5\n")
        os._exit(2)
    case_path, system_path, out_path = argv[:3]
    if os.path.exists(out_path):
        fail("%s exists: nothing is overwritten" % out_path)
    case, text = T.load_case(case_path)
    system = T.read_system(system_path)
    model = case["case"]["model"]
    if system["attrs"].get("model", model) != model:
        fail("system file is a %s, case is a %s" % (system["attrs"].get("model"), model))
    facts = DRV.run_facts(case, system)
    dt, nsteps, every = facts["dt"], facts["nsteps"], facts["every"]
    summary = {"code": "yade", "case": case["case"]["name"], "dt": dt, "steps": nsteps}
    if model == "chain":
        times, data, wall, n, cost = run_chain(case, system, dt, nsteps, every)
        law = "Ip2_FrictMat_FrictMat_MindlinPhys + Law2_ScGeom_MindlinPhys_Mindlin, wall = fixed sphere R=%g m" % WALL_SPHERE_RADIUS
    else:
        times, data, wall, n, nreal, cost = run_crystal(case, system, dt, nsteps, every)
        summary["contacts"] = nreal
        law = L.law_of(T.contact_params(case)).YADE_ENGINES
    start = ("leapfrog started from v(-dt/2) = v(0) - F(0)/m dt/2 (F(0) evaluated with NewtonIntegrator dead)"
             if model == "chain" else "F(0) with v(0) (NewtonIntegrator dead), first half kick and drift by the "
             "script, t = 0 sampled from that state")
    conv = ("synchronous: " + start + "; samples taken by a PyRunner after NewtonIntegrator are labelled "
            "with the force time t, positions shifted x(t) = x(t+dt) - v(t+dt/2) dt, velocities "
            "v(t) = v(t+dt/2) - F(t)/m dt/2")
    extra = {"yade_engines": law, "dt": dt}
    if model != "chain":
        cp = T.contact_params(case)
        extra["contact_law"] = L.law_of(cp).NAME
        extra["lever_arm"] = T.lever_arm_used(cp, "YADE")
        extra["coulomb_normal"] = T.coulomb_normal_used(cp, "YADE")
        # the law's tension convention and history as YADE runs them (see run_crystal)
        extra.update(L.law_of(cp).yade_attrs(cp))
    T.write_trace(out_path, code="yade", code_version=yade_version(), case_text=text,
                  case_name=case["case"]["name"], system_path=system_path, time_convention=conv,
                  time=times, datasets=data, extra_attrs=extra)
    solver = max(wall - cost, 1e-9)
    summary.update(wall_s=wall, sampling_s=cost, solver_s=solver, particles=n,
                   particle_steps_per_s=n * nsteps / solver,
                   trace=out_path)
    DRV.summary_line(**summary)


main(sys.argv[1:])
