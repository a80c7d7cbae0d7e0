"""Judging a crosscheck sweep: every pair of codes over the sweep's points against [sweep.<name>] of
tolerances.toml (on the points where the two ran the same conventions), and a code that failed at a point."""
from __future__ import annotations

from . import runners as RN
from . import sweepmath as M


def sweep_tolerances(tol: dict, name: str) -> dict:
    return tol.get("sweep", {}).get(name, {})


def judge_pairs(points, pairs, value_sets, lim, tsec, quantity):
    """Verdict rows (pair, quantity, worst, tolerance, status, note) over the sweep. value_sets(p)
    yields {code: value} dicts of one point (one per position or speed kind). A pair is judged on
    the points where both ran the same conventions; at the others it is EXPECTED-DIFF (the reason
    is in the note)."""
    rows = []
    for a, b in pairs:
        name = "%s-%s" % (a, b)
        judged, conv, why = [], [], ""
        for p in points:
            st = p.get("pairs", {}).get("%s-%s" % (a, b), "absent")
            if st == "absent":
                continue
            vals = [M.pairwise({a: v.get(a), b: v.get(b)}, [a, b]).get(name) for v in value_sets(p)]
            (conv if st else judged).extend(vals)
            why = why or (st or "")
        if not judged and not conv:
            continue
        if judged:
            w = M.worst(judged)
            wc = M.worst(conv)
            note = ("%d values with a convention difference not judged (largest %s)"
                    % (len(conv), "-" if wc is None else "%.2g" % wc)) if conv else ""
            rows.append((name, quantity, w, lim, judge(w, lim, name, tsec), note))
        else:
            rows.append((name, quantity, M.worst(conv), lim, "EXPECTED-DIFF", why[:300]))
    return rows


def judge(value, lim, pair, tsec):
    if pair in tsec.get("expected_pairs", []):
        return "EXPECTED-DIFF"
    if lim is None:
        return "INFO"
    if value is None:
        return "FAIL"
    return "PASS" if value <= lim else "FAIL"


def run_failures(points, codes):
    """A code that failed, crashed or timed out at any point where it ran is a FAIL row (the sweep
    cannot pass). A twin runs only where conventions differ: its absence elsewhere is not a failure."""
    rows = []
    for c in codes:
        bad = [p for p in points if p["runs"].get(c, {}).get("status", "absent" if RN.TWIN_SEP in c else "missing")
               not in ("ok", "absent")]
        if bad:
            r = bad[0]["runs"].get(c, {})
            rows.append((c, "runs not ok: %d of %d (%s)" % (len(bad), len(points), r.get("status", "missing")),
                         None, None, "FAIL", (r.get("detail") or "")[:200]))
    return rows
