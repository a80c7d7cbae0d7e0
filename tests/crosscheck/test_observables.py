"""The crosscheck's crystal field list is granwave's table of observables (`granwave observables --json`),
not a second literal list in xclib."""
import os

import pytest

from xclib import observables as OB
from xclib import runners as RN

GW = RN.find_granwave(None)
needs_granwave = pytest.mark.skipif(GW is None, reason="granwave not built (cmake --build build --target granwave)")


@needs_granwave
def test_crystal_fields_come_from_granwaves_table():
    fields = OB.crystal_fields(GW)
    assert fields[:6] == ("layer_stress_zz", "layer_stress_zx", "layer_displacement_z", "layer_displacement_x",
                          "layer_velocity_z", "layer_velocity_x")
    assert "coordination" in fields and "kinetic" not in fields  # /energy is not /crystal
    units = {o["name"]: o["unit"] for o in OB.crystal_observables(GW)}
    assert units["layer_stress_zz"] == "Pa" and units["layer_velocity_x"] == "m/s" and units["kinetic"] == "J"


def test_no_literal_crystal_field_list_in_xclib():
    here = os.path.join(os.path.dirname(__file__), "..", "..", "crosscheck", "xclib", "traces.py")
    with open(here) as f:
        assert "CRYSTAL_FIELDS" not in f.read()
