"""The crystal trace's observables as granwave lists them (`granwave observables --json`, the one table
of src/crystal/observables.cpp): no second, literal list of field names on the Python side."""
from __future__ import annotations

import functools
import json
import subprocess

from .impact import find_granwave


@functools.lru_cache(maxsize=None)
def crystal_observables(granwave: str | None = None) -> tuple[dict, ...]:
    """Every crystal observable: {"name", "path", "field", "shape", "unit", "sampled"}, in trace order."""
    exe = find_granwave(granwave)
    if not exe:
        raise RuntimeError("granwave executable not found: the observables are `granwave observables --json`")
    p = subprocess.run([exe, "observables", "--json"], capture_output=True, text=True, timeout=60)
    if p.returncode != 0:
        raise RuntimeError("granwave observables --json failed (exit %d): %s" % (p.returncode, p.stderr.strip()[-300:]))
    raw = json.loads(p.stdout)
    if raw.get("schema") != "granwave-observables/1":
        raise RuntimeError("unexpected observables schema %r" % raw.get("schema"))
    return tuple(raw["crystal"])


def crystal_fields(granwave: str | None = None) -> tuple[str, ...]:
    """The crystal's dataset names under /crystal (what CRYSTAL_FIELDS listed by hand before)."""
    return tuple(o["name"] for o in crystal_observables(granwave) if o["path"].startswith("/crystal/"))
