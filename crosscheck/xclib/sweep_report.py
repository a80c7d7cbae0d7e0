"""A crosscheck sweep's report: its Markdown (head, verdict table, wall times) and its JSON."""
from __future__ import annotations

import json
import os

from .sweep_judge import sweep_tolerances


def report_head(tol, sweep, quantity, title, text):
    """(tolerance section, limit, why, the report's first lines) of a sweep."""
    tsec = sweep_tolerances(tol, sweep)
    return tsec, tsec.get(quantity), tsec.get(quantity + "_why", "no tolerance set"), [title, "", text, ""]


def fmtv(v):
    return "-" if v is None else "%.5g" % v


def verdict_md(md, verdict, why, tsec) -> int:
    md += ["## Verdict (pairs of codes)", "", "| pair | quantity | worst | tolerance | status | note |",
           "|---|---|---|---|---|---|"]
    for pair, q, w, lim, st, note in verdict:
        md.append("| %s | %s | %s | %s | %s | %s |" % (pair, q, "-" if w is None else "%.3g" % w,
                                                      "-" if lim is None else "%.3g" % lim, st, note.replace("|", "/")))
    md += ["", "Tolerance: %s" % why]
    if tsec.get("expected_pairs"):
        md += ["", "EXPECTED-DIFF pairs: %s" % tsec.get("expected_pairs_why", "")]
    md += ["", "A pair whose two codes ran different contact-law conventions at a point (the traces' lever_arm, "
           "normal_tension, coulomb_normal, tangential_history, rolling_lever, rolling_history) is not judged there; granwave then runs that point again with the other "
           "code's conventions (`granwave~<code>`), which is judged against it."]
    md.append("")
    return 1 if any(v[4] == "FAIL" for v in verdict) else 0


def timings_md(md, points, codes):
    tot = {c: sum((p["runs"].get(c, {}).get("wall_s") or 0.0) for p in points) for c in codes}
    md += ["Wall time over the sweep (s): " + ", ".join("%s %.1f" % (c, tot[c]) for c in codes), ""]


def write_report(report_dir, stem, md, data):
    with open(os.path.join(report_dir, stem + ".md"), "w") as f:
        f.write("\n".join(md) + "\n")
    with open(os.path.join(report_dir, stem + ".json"), "w") as f:
        json.dump(data, f, indent=1, default=str)
