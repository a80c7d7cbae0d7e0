"""The registry of contact laws on the Python side: one mapping module per law (`xclib.linear`,
`xclib.hertz_mindlin`), each mapping the case's [contact] onto YADE, LIGGGHTS and LAMMPS with the
same functions, so a driver asks `law_of(c)` and never branches on the law's name (issue #26; the
C++ side is src/contact/case_laws.hpp). A new law is a new module listed in LAWS.

Every module has: NAME; tangential(c), dashpot(c); yade_interaction(c, W, phi, note), YADE_ENGINES,
yade_attrs(c); liggghts_lines(c, limit_force), liggghts_dump(c, r, lay), liggghts_attrs(c);
lammps_style(c, mass, radius), lammps_dump(c); bench_refusals(c), bench_lammps(v), bench_liggghts(v).
Only the standard library and numpy at import (the YADE script imports these too)."""
from __future__ import annotations

from xclib import hertz_mindlin, linear
from xclib.codefacts import Unsupported

LAWS = {m.NAME: m for m in (linear, hertz_mindlin)}


def law_of(c: dict):
    """The mapping module of the case's law ([contact] law, default "linear")."""
    name = c.get("law", "linear")
    if name not in LAWS:
        raise Unsupported("contact.law = %r: the other codes' drivers know %s" % (name, ", ".join(sorted(LAWS))))
    return LAWS[name]
