"""Rolling and torsion resistance in the other codes' drivers (issue #28): LAMMPS maps them onto pair
granular's `rolling sds` / `twisting sds` (liggghts_inputs/MAPPING.md), every other driver refuses the
case naming the key and the code: none may drop them."""
import os
import sys
import tomllib

import numpy as np
import pytest

from xclib import hertz_mindlin, linear
from xclib import traces as T
from xclib.codefacts import Unsupported

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "lammps_inputs"))
import lammps_case as LM  # noqa: E402


def contact(name):
    with open(os.path.join(HERE, "cases", "crystal_small_%s.toml" % name), "rb") as f:
        return T.contact_params(tomllib.load(f))


MONO = np.full(4, 1e-3)


def test_lammps_rolling_is_sds_with_granwave_numbers():
    line = LM.crystal_style(contact("rolling"), np.ones(4), MONO)["lines"]
    assert "rolling sds 20000.0 0.1 1e+100" in line     # k_r, gamma_r, no limit
    assert "twisting" not in line


def test_lammps_twisting_is_per_radian_with_a_length_limit():
    line = LM.crystal_style(contact("rolltors_slip"), np.ones(4), MONO)["lines"]
    arm = 0.5e-3                                         # a' = R* of equal radii 1 mm
    assert "rolling sds 20000.0 0.1 0.01" in line
    assert "twisting sds %r %r %r" % (2e4 * arm * arm, 0.1 * arm * arm, 0.01 * arm) in line


def test_lammps_refuses_polydisperse_torsion_but_not_rolling():
    r = np.array([1e-3, 1.5e-3])
    with pytest.raises(Unsupported, match="ko = 20000.*polydisperse"):
        LM.crystal_style(contact("torsion"), np.ones(2), r)
    assert "rolling sds" in LM.crystal_style(contact("rolling"), np.ones(2), r)["lines"]


def test_lammps_kt0_rolling_is_not_treated_as_frictionless():
    c = dict(contact("rolling"), kt=0.0)
    sty = LM.crystal_style(c, np.ones(4), MONO)
    assert "rolling sds" in sty["lines"] and "linear_nohistory" in sty["lines"]


def test_hertz_mindlin_lammps_carries_the_resistance():
    c = dict(contact("rolltors"), law="hertz_mindlin", youngs_modulus=1e9, poisson_ratio=0.3)
    line = hertz_mindlin.lammps_style(c, np.ones(4), MONO)["lines"]
    assert line.startswith("pair_style      granular") and "rolling sds" in line and "twisting sds" in line


@pytest.mark.parametrize("law", [linear, hertz_mindlin])
@pytest.mark.parametrize("name,key", [("rolling", "kr = 20000"), ("torsion", "ko = 20000")])
def test_liggghts_and_yade_refuse_with_key_and_code(law, name, key):
    c = dict(contact(name), youngs_modulus=1e9, poisson_ratio=0.3)
    with pytest.raises(Unsupported, match="%s.*LIGGGHTS" % key):
        law.liggghts_lines(c, "off")
    with pytest.raises(Unsupported, match="%s.*YADE" % key):
        law.yade_interaction(c, None, 0.5)


def test_without_resistance_nothing_changes():
    c = contact("rolling")
    for k in ("kr", "gamma_r"):
        c.pop(k)
    assert LM.crystal_style(c, np.ones(4), MONO)["style"] == "gran/hooke/history"


def test_benchmark_decks_map_or_refuse_the_resistance():
    """The benchmark's LAMMPS deck (bench/side_by_side.py) takes the crosscheck deck's pair granular line,
    rolling and twisting sds included; LIGGGHTS' refuses, naming the keys. Both laws."""
    for name in ("rolling", "rolltors_slip"):
        c = contact(name)
        v = dict(contact=c, radius=MONO, mu=c["mu_static"])
        deck = linear.bench_lammps(v)
        assert deck["pair_style"] == "granular"
        assert "pair_coeff      * * " + deck["pair_coeff"] == LM.crystal_style(c, np.ones(4), MONO)["lines"].split("\n")[1]
        v_hm = dict(v, contact=dict(c, youngs_modulus=1e9, poisson_ratio=0.3))
        hm = hertz_mindlin.bench_lammps(v_hm)["pair_coeff"]
        assert hm.startswith("hertz/material 1000000000.0 0.0 0.3 tangential mindlin NULL 0.0 0.5 rolling sds 20000.0 ")
        for law, values in ((linear, v), (hertz_mindlin, v_hm)):
            with pytest.raises(Unsupported, match="kr = 20000.*LIGGGHTS"):
                law.bench_liggghts(values)
    assert " twisting sds %r" % (2e4 * 0.5e-3 ** 2) in linear.bench_lammps(v)["pair_coeff"]


def test_yade_cohesion_moment_map_without_dashpots():
    """kn = E a, ks = nu kn; alphaKr ks a^2 = k_r a'^2 (a' = a/2): alphaKr = k_r/(4 kt); etaRoll a = mu_r a'."""
    from types import SimpleNamespace
    W = SimpleNamespace(CohFrictMat=dict, Ip2_CohFrictMat_CohFrictMat_CohFrictPhys=lambda: "ip2",
                        Law2_ScGeom6D_CohFrictPhys_CohesionMoment=dict)
    c = dict(contact("rolltors_slip"), gamma_r=0.0, gamma_o=0.0)
    mat, ip2, law2 = linear.yade_interaction(c, W, 0.5)
    assert mat["poisson"] == 1.0 and mat["alphaKr"] == 2e4 / 4e5 and mat["alphaKtw"] == 2e4 / 4e5
    assert mat["etaRoll"] == 0.005 and mat["etaTwist"] == 0.005 and mat["momentRotationLaw"]
    assert law2 == dict(useIncrementalForm=True, always_use_moment_law=True)
    c.pop("mu_r")
    assert linear.yade_interaction(c, W, 0.5)[0]["etaRoll"] == -1.0      # no limit
    with pytest.raises(Unsupported, match="gamma_r"):
        linear.yade_interaction(dict(c, gamma_r=0.1), W, 0.5)


def test_liggghts_luding_map_of_the_undamped_fixture():
    """rolling_friction luding on model luding (MAPPING.md): coeffRollingStiffness = k_r/k_n, coefficientRollingFriction
    = mu_r (absent: a limit never reached), tan_luding's coeffFrictionStiffness = kt/kn, `torsion on` for ko = kr
    without limits; the trace records R* of the radii and the fixed history."""
    c = contact("rolltors_nodash")
    lines, history = linear.liggghts_lines(c, "off")
    assert history
    assert "pair_style      gran model luding tangential tan_luding rolling_friction luding torsion on limitForce off" in lines
    for name, value in (("LoadingStiffness", 1e5), ("coeffRollingStiffness", 0.2), ("coeffFrictionStiffness", 1.0),
                        ("coefficientRollingFriction", 1e100), ("coefficientRestitution", 1.0),
                        ("coefficientRollingViscousDamping", 0.0), ("coefficientFriction", 0.5)):
        assert "property/global %s peratomtypepair 3 %s\n" % (name, " ".join([repr(value)] * 9)) in lines, name
    assert linear.liggghts_attrs(c) == dict(rolling_history="fixed", rolling_lever="radii")
    rolling = dict(c, ko=0.0, mu_r=0.01)          # rolling alone with a limit: torsion off
    lines, _ = linear.liggghts_lines(rolling, "on")
    assert "rolling_friction luding limitForce on" in lines and "0.01 0.01" in lines
    assert linear.liggghts_attrs(dict(c, kr=0.0, ko=0.0)) == {}


@pytest.mark.parametrize("change,match", [
    (dict(gamma_r=0.1), "gamma_r > 0.*LIGGGHTS.*coefficientRestitution"),
    (dict(gamma_n=0.1), "gamma_n > 0.*LIGGGHTS"),
    (dict(ko=1e4), "ko = 10000.*LIGGGHTS.*torsion on.*ko = kr"),
    (dict(mu_o=0.01), "mu_o = 0.01.*LIGGGHTS.*one limit"),
    (dict(kt=0.0), "kt = 0.*LIGGGHTS"),
])
def test_liggghts_refuses_what_luding_cannot_express(change, match):
    with pytest.raises(Unsupported, match=match):
        linear.liggghts_lines(dict(contact("rolltors_nodash"), **change), "off")


def test_rolling_conventions_make_the_twins():
    """YADE and LIGGGHTS take a' of the radii (LIGGGHTS also a fixed history): their twins run those keys; granwave's
    default lever on the radius arm is the radii's, so LAMMPS (radii) differs only by its mixed arm."""
    from xclib import conventions as CV
    with open(os.path.join(HERE, "cases", "crystal_small_rolltors_nodash.toml"), "rb") as f:
        case = tomllib.load(f)
    gw = dict(lever_arm="radius", normal_tension="allow", coulomb_normal="compressive", contact_law="linear",
              rolling_lever="lever_arm", rolling_history="rotated")
    yade = dict(gw, lever_arm="contact_point", coulomb_normal="magnitude", rolling_lever="radii")
    lig = dict(yade, rolling_history="fixed")
    lmp = dict(gw, lever_arm="radius_velocity_contact_point_torque", coulomb_normal="magnitude", rolling_lever="radii")
    tw = {name: (codes, changes) for name, codes, changes in CV.twins(case, dict(granwave=gw, yade=yade, liggghts=lig,
                                                                                   lammps=lmp))}
    assert tw["granwave~yade"] == (["yade"], dict(lever_arm="contact_point", rolling_lever="radii",
                                                  rolling_history="rotated"))
    assert tw["granwave~liggghts"] == (["liggghts"], dict(lever_arm="contact_point", rolling_lever="radii",
                                                          rolling_history="fixed"))
    assert "granwave~lammps" not in tw
    why = CV.difference(case, gw, lmp)
    assert why.count("convention: the traces say") == 1 and "lever-arm" in why
    # the contact-point arm without the radii key is a rolling-lever difference
    assert "rolling-lever" in CV.difference(case, dict(gw, lever_arm="contact_point"), yade)
    # no resistance: neither rolling convention matters
    plain = {"case": case["case"], "contact": {k: v for k, v in case["contact"].items() if k not in ("kr", "ko")}}
    assert CV.difference(plain, dict(yade, rolling_history="rotated"), lig) is None
