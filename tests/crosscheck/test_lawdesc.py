"""xclib.lawdesc: the contact laws' keys and defaults come from `granwave laws --json` (the laws' own
descriptions in src/contact/), and granwave's reader uses the same description: the range it prints in
a refusal is the exported one, and a key left out reads as the exported default."""
import os
import subprocess

import pytest

from xclib import lawdesc
from xclib import runners as RN
from xclib import traces as T
from xclib.codefacts import Unsupported

GW = RN.find_granwave(None)
pytestmark = pytest.mark.skipif(GW is None, reason="granwave not built (cmake --build build --target granwave)")
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def keys_of(name):
    return {k["key"]: k for k in lawdesc.law(name)["keys"]}


def test_every_law_and_its_own_keys():
    names = [d["name"] for d in lawdesc.laws()]
    assert names[:2] == ["linear", "hertz_mindlin"] and lawdesc.default_law() == "linear"
    lin, hm = keys_of("linear"), keys_of("hertz_mindlin")
    assert lin["kn"]["required"] and lin["kn"]["unit"] == "N/m" and lin["kn"]["range"] == "> 0 (N/m)"
    assert lin["gamma_n"]["default"] == 0.0 and lin["mu_static"]["default"] == 0.5
    assert lin["mu_dynamic"]["default"] is None and lin["mu_dynamic"]["default_note"] == "mu_static"
    assert lin["mu_r"]["default"] is None and lin["mu_r"]["group"] == "rolling_torsion"
    assert hm["poisson_ratio"]["min"] == -1.0 and hm["poisson_ratio"]["max"] == 0.5 and hm["poisson_ratio"]["max_open"]
    assert hm["tangential_history"]["choices"] == ["displacement", "displacement_rescale", "force"]
    assert "kn" not in hm and "youngs_modulus" not in lin           # each law only its own
    assert {"normal_tension", "lever_arm", "coulomb_normal"} <= set(lin) & set(hm)   # friction: every law's


def test_contact_params_takes_the_laws_defaults_and_no_other_laws_keys():
    c = T.contact_params({"contact": {"kn": 1e5, "mu_static": 0.3}})
    assert c["law"] == "linear" and c["gamma_n"] == 0.0 and c["kt"] == 0.0 and c["mu_dynamic"] == 0.3
    assert "damping_ratio" not in c and "tangential" not in c and "mu_r" not in c
    h = T.contact_params({"contact": {"law": "hertz_mindlin", "youngs_modulus": 1e9, "poisson_ratio": 0.3}})
    assert h["damping_ratio"] == 0.0 and h["tangential"] == "mindlin" and h["mu_dynamic"] == 0.5
    assert not {"kn", "kt", "gamma_n", "gamma_t"} & set(h)
    with pytest.raises(Unsupported, match="granwave knows linear, hertz_mindlin"):
        T.contact_params({"contact": {"law": "no_such_law"}})


def test_the_reader_refuses_with_the_exported_range(tmp_path):
    """granwave check of a case with poisson_ratio out of range names the key and the exported range."""
    with open(os.path.join(REPO, "data", "cases", "crystal_p.toml")) as f:
        text = f.read()
    i = text.index("[contact]")
    j = text.index("\n[", i + 1)
    bad = text[:i] + '[contact]\nlaw = "hertz_mindlin"\nyoungs_modulus = 63e9\npoisson_ratio = 0.6\n' + text[j:]
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    p = subprocess.run([GW, "check", str(path)], capture_output=True, text=True)
    assert p.returncode == 2
    assert "contact.poisson_ratio" in p.stderr and keys_of("hertz_mindlin")["poisson_ratio"]["range"] in p.stderr
