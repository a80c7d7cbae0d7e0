"""The contact laws' parameter descriptions as granwave exports them (`granwave laws --json`, written
by src/cli/laws.cpp from each law's own description in src/contact/): every law's [contact] keys with
their units, ranges and defaults. The crosscheck takes the defaults from here, never from a copy; the
granwave it asks is the one the harness and the drivers use (find_granwave).

Only the standard library (the YADE script imports it too)."""
from __future__ import annotations

import functools
import json
import os
import shutil
import subprocess

from .codefacts import Unsupported


def find_granwave(explicit: str | None = None) -> str | None:
    """granwave: EXPLICIT, else $GRANWAVE, this checkout's build/ and build-xc/, then PATH (the harness's and the
    drivers' search; a checkout judges its own build, never an older installed program)."""
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    for c in ([explicit] if explicit else [os.environ.get("GRANWAVE", ""), os.path.join(repo, "build", "granwave"),
                                           os.path.join(repo, "build-xc", "granwave"), "granwave"]):
        if not c:
            continue
        p = shutil.which(c) if "/" not in c else (c if os.access(c, os.X_OK) else None)
        if p:
            return os.path.abspath(p)
    return None

SCHEMA = "granwave-laws/1"


@functools.lru_cache(maxsize=None)
def _described(exe: str) -> tuple:
    p = subprocess.run([exe, "laws", "--json"], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("%s laws --json failed (exit %d): %s" % (exe, p.returncode, p.stderr.strip()[-300:]))
    doc = json.loads(p.stdout)
    if doc.get("schema") != SCHEMA:
        raise RuntimeError("%s laws --json: schema %r, expected %r" % (exe, doc.get("schema"), SCHEMA))
    return tuple(doc["laws"])


def laws(granwave: str | None = None) -> list:
    """Every law of granwave's registry, in its order (the first is the default): name, summary, keys."""
    exe = find_granwave(granwave)
    if exe is None:
        raise RuntimeError("granwave not found ($GRANWAVE, build/ or PATH): the contact laws' keys and defaults "
                           "are `granwave laws --json`")
    return list(_described(exe))


def default_law(granwave: str | None = None) -> str:
    """The law of a [contact] table without `law`."""
    return next(law["name"] for law in laws(granwave) if law["default"])


def law(name: str, granwave: str | None = None) -> dict:
    for d in laws(granwave):
        if d["name"] == name:
            return d
    raise Unsupported("contact.law = %r: granwave knows %s" % (name, ", ".join(d["name"] for d in laws(granwave))))


def with_defaults(given: dict, granwave: str | None = None) -> dict:
    """A case's [contact] table completed with its law's defaults: `law` set, every key the law has a
    default for (a default naming another key, mu_dynamic's "mu_static", takes that key's value; a key
    whose absence means something, mu_r's "no limit", stays absent); keys outside the law are kept as given."""
    name = given.get("law", default_law(granwave))
    keys = law(name, granwave)["keys"]
    c = dict(law=name)
    for k in keys:
        if k["default"] is not None:
            c[k["key"]] = k["default"]
    c.update(given)
    for k in keys:
        other = k.get("default_note", "")
        if k["key"] not in given and any(o["key"] == other for o in keys):
            c[k["key"]] = c[other]
    return c
