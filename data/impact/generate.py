#!/usr/bin/python3
"""Writes the Chung & Ooi (2011) impact cases of this folder (README.md): T1-T7 as granwave case
files, one per material and swept value. Parameters: docs/research/contact_models_sources.md A.2.
usage: /usr/bin/python3 data/impact/generate.py [OUTDIR]   (default: this folder)"""
import math
import os
import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))

# name: (E Pa, nu, rho kg/m^3, source)
MATERIALS = {
    "glass": (48e9, 0.20, 2800, "Chung & Ooi T1 (YADE Test1.py; Kratos Materials1.json)"),
    "limestone": (20e9, 0.25, 2500, "Chung & Ooi T1 (YADE Test1.py)"),
    "al_alloy_t2": (70e9, 0.30, 2699, "Chung & Ooi T2 (YADE Test2.py; Kratos Materials2.json)"),
    "mg_alloy": (40e9, 0.35, 1800, "Chung & Ooi T2 (YADE Test2.py)"),
    "alumina": (380e9, 0.23, 4000, "Chung & Ooi T3/T4 (YADE Test3.py, Test4.py; Kratos Materials32.json)"),
    "cast_iron": (100e9, 0.25, 7000, "Chung & Ooi T3 (YADE Test3.py)"),
    "al_alloy": (70e9, 0.33, 2700, "Chung & Ooi T4/T6/T7 (YADE Test4.py; Kratos benchmark6/7DEM.mdpa)"),
    "steel": (208e9, 0.30, 7850, "Chung & Ooi T5 (Kratos benchmark5DEM.mdpa; PySPH chung_test_5.py)"),
}

ANGLES = [5 * i for i in range(1, 18)]  # 5..85 deg (Kratos: 90/(N+1) i, N = 17)


def vec(v):
    return "[" + ", ".join(repr(float(x)) for x in v) + "]"


def material(name):
    E, nu, rho, src = MATERIALS[name]
    return f'[materials.{name}]\nyoungs_modulus = {E!r}\npoisson_ratio = {nu!r}\ndensity = {rho!r}\nsource = "{src}"\n'


def body(key, mat, R, x, v, w=(0.0, 0.0, 0.0)):
    return (f"[impact.{key}]\nmaterial = \"{mat}\"\nradius = {R!r}\nposition = {vec(x)}\nvelocity = {vec(v)}\n"
            f"angular_velocity = {vec(w)}\n")


WALL = '[impact.wall]\nmaterial = "rigid"\nnormal = [0.0, 0.0, 1.0]\n'


def contact(tangential, mu=None, restitution=None):
    s = '[contact]\nlaw = "hertz_mindlin"\ntangential = "' + tangential + '"\n'
    if mu is not None:
        s += f"mu_static = {mu!r}\nmu_dynamic = {mu!r}\n"
    if restitution is not None:  # a damped contact: the dashpot may not pull (as YADE always; SCHEMA §7.1)
        s += f'restitution = {restitution!r}\nnormal_tension = "clip"\n'
    return s


def write(sub, name, title, text, dt_over_tc=0.002):
    os.makedirs(os.path.join(OUT, sub), exist_ok=True)
    head = f'# {title}\n# Written by data/impact/generate.py; parameters: docs/research/contact_models_sources.md A.2.\n'
    with open(os.path.join(OUT, sub, name + ".toml"), "w") as f:
        f.write(head + f'[case]\nname = "{name}"\nmodel = "impact"\n\n' + text +
                f"\n[integrator]\ndt_over_tc = {dt_over_tc!r}\n\n[output]\ninterval = 0.0\n")


def main():
    for mat in ("glass", "limestone"):  # T1: two identical spheres head-on, 10 m/s each
        R = 0.010
        write("t1", f"t1_{mat}", f"Chung & Ooi T1: two {mat} spheres head-on, 10 m/s each, elastic",
              material(mat) + "\n" + body("body1", mat, R, (-R, 0, 0), (10, 0, 0)) + "\n" +
              body("body2", mat, R, (R, 0, 0), (-10, 0, 0)) + "\n" + contact("mindlin", mu=0.35))
    for mat in ("al_alloy_t2", "mg_alloy"):  # T2: sphere on a rigid wall, 0.2 m/s, mu = 0
        R = 0.1
        write("t2", f"t2_{mat}", f"Chung & Ooi T2: a {mat} sphere on a rigid wall, 0.2 m/s, elastic",
              material(mat) + "\n" + body("body1", mat, R, (0, 0, R), (0, 0, -0.2)) + "\n" + WALL + "\n" +
              contact("none"))
    for mat in ("alumina", "cast_iron"):  # T3: restitution in vs out, 3.9 m/s, mu = 0
        R = 0.0025
        for e in (0.2, 0.4, 0.6, 0.8, 1.0):
            write("t3", f"t3_{mat}_e{int(round(e * 10)):02d}", f"Chung & Ooi T3: a {mat} sphere on a rigid wall, 3.9 m/s, e = {e}",
                  material(mat) + "\n" + body("body1", mat, R, (0, 0, R), (0, 0, -3.9)) + "\n" + WALL + "\n" +
                  contact("none", restitution=e))
    for mat in ("alumina", "al_alloy"):  # T4: oblique, |v| = 3.9 m/s, mu = 0.092, e = 0.98
        R = 0.0025
        for a in ANGLES:
            th = math.radians(a)
            write("t4", f"t4_{mat}_{a:02d}deg", f"Chung & Ooi T4: a {mat} sphere on a rigid wall, 3.9 m/s at {a} deg",
                  material(mat) + "\n" + body("body1", mat, R, (0, 0, R), (3.9 * math.sin(th), 0, -3.9 * math.cos(th))) +
                  "\n" + WALL + "\n" + contact("mindlin", mu=0.092, restitution=0.98))
    for a in ANGLES:  # T5: steel, vn = 5 m/s, vt = 5 tan(theta), mu = 0.3, e = 1
        R, th = 1e-5, math.radians(a)
        write("t5", f"t5_steel_{a:02d}deg", f"Chung & Ooi T5: a steel sphere on a rigid wall, vn = 5 m/s, vt = 5 tan({a} deg)",
              material("steel") + "\n" + body("body1", "steel", R, (0, 0, R), (5 * math.tan(th), 0, -5.0)) + "\n" + WALL +
              "\n" + contact("mindlin", mu=0.3))
    for a in ANGLES:  # T6: Al alloy, vn = 0.2 m/s, spin only: contact-point speed 0.2 tan(theta), mu 0.4, e 0.5
        R, th = 0.1, math.radians(a)
        w = 0.2 * math.tan(th) / R  # v_ct = v_t - R w_y = 0.2 tan(theta) along +x
        write("t6", f"t6_al_alloy_{a:02d}deg", f"Chung & Ooi T6: an Al alloy sphere on a rigid wall, vn = 0.2 m/s, "
              f"spin {w:.6g} rad/s", material("al_alloy") + "\n" +
              body("body1", "al_alloy", R, (0, 0, R), (0, 0, -0.2), (0, -w, 0)) + "\n" + WALL + "\n" +
              contact("mindlin", mu=0.4, restitution=0.5), dt_over_tc=0.0005)  # data/impact/README.md: T6's time step
    for a in ANGLES:  # T7: two Al alloy spheres, 0.2 m/s each, spins +w and -w (their surfaces move together), mu 0.4, e 0.5
        R, th = 0.1, math.radians(a)
        w = 2.0 * math.tan(th)
        write("t7", f"t7_al_alloy_{a:02d}deg", f"Chung & Ooi T7: two Al alloy spheres, 0.2 m/s each, spins +-{w:.6g} rad/s",
              material("al_alloy") + "\n" + body("body1", "al_alloy", R, (-R, 0, 0), (0.2, 0, 0), (0, 0, w)) + "\n" +
              body("body2", "al_alloy", R, (R, 0, 0), (-0.2, 0, 0), (0, 0, -w)) + "\n" +
              contact("mindlin", mu=0.4, restitution=0.5))


if __name__ == "__main__":
    main()
