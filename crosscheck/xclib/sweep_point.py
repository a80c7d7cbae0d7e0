"""One point of a crosscheck sweep: its case derived from a template, every code run on it through the
harness's own steps (granwave build, each code in a fresh directory, granwave's convention twins, the
ruler), and which pairs of codes ran the same conventions there."""
from __future__ import annotations

import math
import os
import sys
import tomllib

from . import conventions as CV
from . import ruler as R
from . import runners as RN
from . import sweepmath as M
from . import traces as T

SIZES = {
    # small: 4x4x40; the first peak reaches z/l0 = 25 at ~1.7e-4 s (P) and the top reflection returns
    # there after ~3.9e-4 s, so t_end = 3e-4 s keeps every position's first peak clean.
    "small": dict(template_P="tests/crosscheck/cases/crystal_small.toml", template_S="tests/crosscheck/cases/crystal_small.toml",
                  positions=(5, 10, 15, 20, 25), t_end=3e-4, layers="5:25"),
    # paper: seed 002's 4x4x200 with the seed's positions (fig. 3 right) and its fit range.
    "paper": dict(template_P="data/cases/crystal_p.toml", template_S="data/cases/crystal_s.toml",
                  positions=(10, 45, 80, 115, 150), t_end=None, layers=None),
}


def _log(msg):
    print("sweep: " + msg, file=sys.stderr, flush=True)


def parse_values(text: str, option: str):
    """Comma-separated finite numbers >= 0, or None (the defaults); ValueError names the option."""
    if not text:
        return None
    out = []
    for x in text.split(","):
        try:
            v = float(x)
        except ValueError:
            raise ValueError("%s: '%s' is not a number (allowed: comma-separated numbers >= 0)" % (option, x)) from None
        if not math.isfinite(v) or v < 0:
            raise ValueError("%s: %s is outside the allowed range (finite, >= 0)" % (option, x))
        out.append(v)
    return out


def sweep_setup(a, defaults):
    """(size, values, modes, codes, ruler_args) of a sweep over `defaults` (or --values)."""
    size = SIZES[a.size]
    values = parse_values(a.values, "--values") or list(defaults)
    modes = [m.strip() for m in a.modes.split(",") if m.strip()]
    ruler_args = ["--layers", size["layers"]] if size["layers"] else []
    return size, values, modes, RN.parse_codes(a.codes), ruler_args


def template(size, mode):
    """(template path, its kn) of a mode's point."""
    tmpl = RN.repo_path(size["template_" + mode])
    with open(tmpl, "rb") as f:
        return tmpl, float(tomllib.load(f)["contact"]["kn"])


def make_case(template_path: str, name: str, changes: dict, out_dir: str) -> str:
    with open(template_path) as f:
        text = f.read()
    ch = {("case", "name"): name}
    ch.update(changes)
    path = os.path.join(out_dir, name + ".toml")
    with open(path, "w") as f:
        f.write("# derived by crosscheck sweep from %s\n" % os.path.relpath(template_path, RN.REPO)
                + M.moved_case(text, ch, template_path))
    return path


def sweep_point(a, report_dir, name, template, ch, size, codes, granwave, ruler_args):
    """(case path, results) of one point: the template with the changes `ch` (and the size's t_end), run by
    every code in its own directory (resumable)."""
    if size["t_end"]:
        ch[("integrator", "t_end")] = size["t_end"]
    casedir = RN.work_dir(os.path.join(report_dir, name), a.resume)
    cp = make_case(template, name, ch, casedir)
    return cp, run_point(cp, casedir, codes, granwave, a.timeout, a.fixture_system, ruler_args, a.resume)


def run_point(case_path: str, casedir: str, codes, granwave, timeout, fixture, ruler_args, resume=False) -> dict:
    """One case through the harness steps (runners.run_codes: each code, then granwave's convention
    twins); returns {name: {"status", "wall_s", "detail", "attrs", "raw", ["twin_of"]}}."""
    try:
        system, _ = RN.build_system(case_path, casedir, granwave, fixture, timeout, resume)
    except Exception as e:  # noqa: BLE001 -- a point that cannot be built is a row, not a crash
        _log("%s: system not built: %s" % (os.path.basename(case_path), e))
        return {code: dict(status="failed", wall_s=None, detail="system not built: %s" % e) for code in codes}

    def log(msg):
        _log("%s: %s" % (os.path.basename(case_path), msg))

    runs = RN.run_codes(case_path, system, casedir, codes, timeout, granwave, resume, log)
    return {code: _record(r, granwave, ruler_args) for code, r in runs.items()}


def _record(r: dict, granwave, ruler_args) -> dict:
    """A sweep point's row of one run: status, time, its conventions and the ruler's JSON ("raw")."""
    rec = dict(status=r["status"], wall_s=r.get("wall_s"), detail=r.get("detail", ""))
    if r.get("twin_of"):
        rec.update(twin_of=r["twin_of"], conventions=r["conventions"])
    if r["status"] == "ok":
        try:
            rec["attrs"] = {k: v for k, v in T.read_trace(r["trace"])["attrs"].items()
                            if k in CV.GRANWAVE_RUNS}
            rec["raw"] = R.granwave_analyze(r["trace"], granwave or "granwave", extra_args=ruler_args)
            rec["pulse_field"] = rec["raw"].get("measure_field")   # the field the ruler measured
        except R.RulerError as e:
            rec["status"], rec["detail"] = "failed", "not measurable: %s" % e
    return rec


def point_pairs(case_path: str, runs: dict) -> dict:
    """{(a, b): None (judged) or the convention difference (not judged)} at one sweep point: every
    pair of codes that ran, and each twin with the codes it stands for."""
    case, _ = T.load_case(case_path)
    ok = {c: r for c, r in runs.items() if r.get("status") == "ok"}
    twins = {c: r["twin_of"] for c, r in ok.items() if r.get("twin_of")}
    out = {}
    for a, b in pairs_all([c for c in ok if c in RN.CODES], twins):
        out[(a, b)] = CV.difference(case, ok[a].get("attrs", {}), ok[b].get("attrs", {}))
    return out


def pairs_all(codes, twins) -> list:
    cs = [c for c in RN.CODES if c in codes]
    out = [(cs[i], cs[j]) for i in range(len(cs)) for j in range(i + 1, len(cs))]
    for t, members in twins.items():
        out += [(t, m) for m in members if m in cs]
    return out


def columns_of(points, codes) -> tuple:
    """(columns, pairs) of a sweep's tables: the codes, then the twins that ran at any point; every pair
    of codes, then each twin with its codes."""
    twins = {}
    for p in points:
        for c, r in p["runs"].items():
            if r.get("twin_of"):
                twins.setdefault(c, [])
                twins[c] += [m for m in r["twin_of"] if m not in twins[c]]
    return list(codes) + sorted(twins), pairs_all(codes, twins)
