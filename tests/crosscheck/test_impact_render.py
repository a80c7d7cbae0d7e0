"""The impact decks' contact lines (xclib.hertz_mindlin, measured conventions) and the dump reader,
without running any code."""
from types import SimpleNamespace

import numpy as np
import pytest

from xclib import hertz_mindlin_impact as HM
from xclib import impact as I
from xclib.codefacts import Unsupported


def _setup(two=False, zeta=0.0, mu=0.092):
    b = SimpleNamespace(E=380e9, nu=0.23, rho=4000.0, radius=2.5e-3, mass=2.6e-4, inertia=6.5e-10,
                        x=np.array([0, 0, 2.5e-3]), v=np.array([1.0, 0, -3.0]), w=np.zeros(3))
    wall = None if two else SimpleNamespace(normal=np.array([0, 0, 1.0]), point=np.zeros(3), rigid=True,
                                             material="rigid")
    gs = b.E / (2 * (1 + b.nu)) / (2 - b.nu)
    return SimpleNamespace(b1=b, b2=b if two else None, wall=wall, zeta=zeta, clip=True, mu=mu, friction=mu > 0,
                           th={"effective_shear_modulus": gs}, name="x", dt=1e-8, nsteps=10)


def test_lammps_wall_takes_2E_over_1_plus_nu_and_an_explicit_kt():
    lines, attrs = HM.lammps_impact(_setup())
    wall = [ln for ln in lines.splitlines() if ln.startswith("fix")][0]
    w = wall.split()       # fix wall all wall/gran granular hertz/material E damp nu tangential mindlin KT ...
    assert w[5] == "hertz/material" and w[10] == "mindlin"
    assert float(w[6]) == pytest.approx(2 * 380e9 / 1.23, rel=1e-15)
    kt = float(w[11])
    assert kt == pytest.approx(8 * 380e9 / 2.46 / 1.77, rel=1e-14)
    assert attrs["lever_arm"] == "radius" and "zplane 0.0 NULL" in wall


def test_lammps_refuses_what_it_cannot_run():
    with pytest.raises(Unsupported):
        HM.lammps_impact(_setup(zeta=0.667))          # tsuji's alpha(e) covers zeta <= 0.5196
    s = _setup(two=True)
    s.b2 = SimpleNamespace(**dict(vars(s.b1), E=1e9))
    with pytest.raises(Unsupported):
        HM.lammps_impact(s)                           # two materials: this version's 1-2 mixing


def test_liggghts_wall_options_follow_the_primitive():
    lines, attrs = HM.liggghts_impact(_setup(zeta=0.1))
    wall = [ln for ln in lines.splitlines() if "wall/gran" in ln][0]
    assert wall.index("primitive") < wall.index("limitForce on")
    assert attrs["lever_arm"] == "contact_point" and attrs["liggghts_restitution"] == HM.liggghts_restitution(0.1)


def test_tangential_motion():
    head_on = {"impact": {"body1": {"position": [0, 0, 1], "velocity": [0, 0, -1]}, "wall": {}}}
    assert not I.tangential_motion(head_on)
    head_on["impact"]["body1"]["angular_velocity"] = [0, 1, 0]
    assert I.tangential_motion(head_on)


def test_read_dump(tmp_path):
    rows = "ITEM: TIMESTEP\n%d\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\n" \
           "ITEM: ATOMS id x y z vx vy vz omegax omegay omegaz fx fy fz\n1 %s\n"
    p = tmp_path / "dump.atoms"
    p.write_text("".join(rows % (k, " ".join(["%.17g" % (0.1 * k + j) for j in range(12)])) for k in range(3)))
    d = I.read_dump(str(p), 1)
    assert list(d["step"]) == [0, 1, 2] and d["f"][2, 0, 2] == pytest.approx(11.2, rel=1e-15)
