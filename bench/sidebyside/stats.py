"""Statistics of paired runs: medians, per-repetition ratios, the rotated order of the runs."""
from __future__ import annotations

import statistics


def median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def paired_ratio(other: list, ref: list):
    """Median of the per-repetition ratios other[k] / ref[k] (runs of the same repetition)."""
    r = [o / g for o, g in zip(other, ref) if o is not None and g is not None and g > 0]
    return statistics.median(r) if r else None


def rotation(items: list, k: int) -> list:
    """The order of repetition k: items rotated by k, so each code takes each place in turn."""
    if not items:
        return []
    k %= len(items)
    return items[k:] + items[:k]


def summarize(res: dict, runners: list) -> dict:
    """Medians and paired ratios of one case."""
    runs = res["runs"]
    runners = [r for r in runners if r.key in runs]
    out = {}
    for r in runners:
        w = [x["wall"] for x in runs[r.key]]
        c = [x["cpu"] for x in runs[r.key]]
        out[r.key] = dict(wall=median(w), cpu=median(c), maxrss_kb=max(x["maxrss_kb"] for x in runs[r.key]),
                          walls=w, cpus=c)
    gw = [r for r in runners if r.code == "granwave"]
    others = [r for r in runners if r.code != "granwave"]
    ratios = {}
    for g in gw:
        for o in others:
            ratios["%s/%s" % (o.key, g.key)] = dict(
                wall=paired_ratio([x["wall"] for x in runs[o.key]], [x["wall"] for x in runs[g.key]]),
                cpu=paired_ratio([x["cpu"] for x in runs[o.key]], [x["cpu"] for x in runs[g.key]]))
    return dict(times=out, ratios=ratios)
