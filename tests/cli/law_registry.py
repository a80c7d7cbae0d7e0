"""The test-only third contact law through the same path as the real ones (issue #26):
`granwave_testlaw` (the registry built with GRANWAVE_TEST_LAW, tests/laws/test_linear_dashpot.hpp)
checks, runs and theorises a case file written here with law = "test_linear_dashpot"; the trace
names the law; eq. (10) and the stability guard take its stiffness (k, and k_t = 0: a dashpot) and
its damping (gamma_n + gamma_t); the real `granwave` refuses the name.

usage: law_registry.py GRANWAVE GRANWAVE_TESTLAW SOURCE_DIR WORKDIR
"""
import json
import math
import os
import subprocess
import sys

import h5py

gw, gw_test, src, work = sys.argv[1:5]
os.makedirs(work, exist_ok=True)

KN, GAMMA_N, GAMMA_T, A, RHO, OVERLAP = 1e5, 0.0, 0.05, 1e-3, 2000.0, 1e-3


def case(name, dt, mode="S"):
    text = f"""[case]
name = "{name}"
model = "crystal"

[crystal]
lattice = "fcc"
cells = [2, 2, 40]
radius = {A!r}
density = {RHO!r}
overlap = {OVERLAP!r}
fixed_layers = 2

[contact]
law = "test_linear_dashpot"
kn = {KN!r}
gamma_n = {GAMMA_N!r}
gamma_t = {GAMMA_T!r}

[excitation]
mode = "{mode}"
drive = "displacement"
amplitude = 1e-4

[integrator]
scheme = "verlet"
dt = {dt!r}
t_end = 1e-4

[output]
interval = 1e-6
"""
    path = os.path.join(work, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True)


def fail(msg, p=None):
    if p is not None:
        sys.stderr.write(p.stdout + p.stderr)
    sys.exit("FAIL: " + msg)


# The stability guard (crystal::derive): omega_max^2 = 2 z (k + 3.5 k_t)/m with z = 12 and k_t = 0,
# eta_max = z (gamma_n + gamma_t)/(2 m): dt_stable = 2/omega_max (sqrt(1 + zeta^2) - zeta).
m = RHO * 4.0 / 3.0 * math.pi * A ** 3
omega_max = math.sqrt(2 * 12 * KN / m)
zeta = 12 * (GAMMA_N + GAMMA_T) / (2 * m) / omega_max
dt_stable = 2 / omega_max * (math.sqrt(1 + zeta * zeta) - zeta)
assert zeta > 0.01, "gamma_t must move the limit measurably"

ok = case("testlaw", 2e-7)
p = run(gw_test, "check", ok)
if p.returncode != 0 or "contact law test_linear_dashpot" not in p.stdout:
    fail("granwave_testlaw check of the test law", p)
p = run(gw_test, "check", case("testlaw_dt_below", 0.99 * dt_stable))
if p.returncode != 0:
    fail("dt = 0.99 dt_stable (k and gamma_t of the test law) must pass the guard", p)
p = run(gw_test, "check", case("testlaw_dt_above", 1.01 * dt_stable))
if p.returncode != 2 or "integrator.dt" not in p.stderr or "stability limit" not in p.stderr:
    fail("dt = 1.01 dt_stable must be refused by the guard, naming integrator.dt", p)

trace = os.path.join(work, "testlaw.h5")
if os.path.exists(trace):
    os.remove(trace)
p = run(gw_test, "run", ok, "-o", trace, "--quiet")
if p.returncode != 0:
    fail("granwave_testlaw run", p)
with h5py.File(trace, "r") as f:
    attrs = {k: (v.decode() if isinstance(v, bytes) else str(v)) for k, v in f.attrs.items()}
    if attrs.get("contact_law") != "test_linear_dashpot" or attrs.get("tangential_history") != "none":
        fail("trace attributes: %r" % {k: attrs.get(k) for k in ("contact_law", "tangential_history")})
    if attrs.get("status") != "complete":
        fail("trace status %r" % attrs.get("status"))
    e = {k: f["energy/" + k][()] for k in ("kinetic", "potential", "dissipated", "work_in")}
# An S wave shears the contacts: with gamma_n = 0 only the tangential dashpot dissipates.
if not e["dissipated"][-1] > 1e-3 * e["work_in"][-1]:
    fail("the tangential dashpot dissipated %g J of %g J put in" % (e["dissipated"][-1], e["work_in"][-1]))
total = e["kinetic"] + e["potential"] + e["dissipated"]  # the prestress's stored energy at t = 0 included
residual = abs((total[-1] - total[0]) - (e["work_in"][-1] - e["work_in"][0]))
if not residual < 1e-3 * e["work_in"][-1]:
    fail("energy balance residual %g J of %g J" % (residual, e["work_in"][-1]))

# Eq. (10) with the law's stiffness: k_n = kn, k_t = 0, V_pz = d' sqrt(k/m) (branch d').
p = run(gw_test, "theory", ok, "--json")
if p.returncode != 0:
    fail("granwave_testlaw theory", p)
t = json.loads(p.stdout)
val = lambda q: q["value"] if isinstance(q, dict) else q
d_prime = 2 * A * (1 - OVERLAP)
checks = [(t["contact_law"] == "test_linear_dashpot", "contact_law %r" % t["contact_law"]),
          (abs(val(t["k_n"]) - KN) <= 1e-12 * KN, "k_n %r" % t["k_n"]),
          (val(t["k_t"]) == 0.0, "k_t %r" % t["k_t"]),
          (abs(val(t["V_pz"]) / (d_prime * math.sqrt(KN / m)) - 1) < 1e-6, "V_pz %r" % t["V_pz"])]
for good, what in checks:
    if not good:
        fail("theory --json: " + what)

# The test law's parameters come with it: `granwave_testlaw laws --json` lists its own keys (from its
# file alone) beside friction's, and the real binary does not list it.
p = run(gw_test, "laws", "--json")
if p.returncode != 0:
    fail("granwave_testlaw laws --json", p)
listed = {d["name"]: d for d in json.loads(p.stdout)["laws"]}
own = [k["key"] for k in listed.get("test_linear_dashpot", {}).get("keys", []) if k["group"] == "law"]
if own != ["kn", "gamma_n", "gamma_t"] or not any(k["key"] == "lever_arm" for k in listed["test_linear_dashpot"]["keys"]):
    fail("laws --json: the test law's keys %r" % own)
p = run(gw, "laws", "--json")
if p.returncode != 0 or "test_linear_dashpot" in p.stdout or "hertz_mindlin" not in p.stdout:
    fail("granwave laws --json must list the real laws only", p)
# The real binary does not know the test law: exit 2 naming contact.law and the laws it knows.
p = run(gw, "check", ok)
if p.returncode != 2 or "contact.law" not in p.stderr or '"hertz_mindlin"' not in p.stderr:
    fail("granwave must refuse law = \"test_linear_dashpot\"", p)
# The impact model runs the laws of granwave's own registry: the test binary refuses the test law in an
# impact case with exit 2 naming contact.law (not an internal error mid-run), in check, theory and run.
imp = os.path.join(work, "impact_test_law.toml")
with open(os.path.join(src, "data", "impact", "t2", "t2_al_alloy_t2.toml")) as f:
    t2 = f.read()
with open(imp, "w") as f:  # Chung & Ooi's T2 with the test law in place of its [contact]
    f.write(t2[:t2.index("[contact]")] + '[contact]\nlaw = "test_linear_dashpot"\nkn = 1e6\ngamma_n = 0.0\n'
            'gamma_t = 0.01\n\n[integrator]\ndt_over_tc = 0.01\n')
for verb in ("check", "theory", "run"):
    p = run(gw_test, verb, imp, *(["-o", os.path.join(work, "impact_test_law.h5")] if verb == "run" else []))
    if p.returncode != 2 or "contact.law" not in p.stderr or "impact" not in p.stderr:
        fail("granwave_testlaw %s of an impact case with the test law: exit 2 naming contact.law" % verb, p)
print("test law: check, guard at %.6g s, run (dissipated %.3g J), theory V_pz %.6g m/s: ok" %
      (dt_stable, e["dissipated"][-1], val(t["V_pz"])))
