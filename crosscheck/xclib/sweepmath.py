"""Pure maths and text for the parameter sweeps (crosscheck sweep damping|friction): no code runs here.

- `derive_case`: a case text with some `key = value` lines replaced (or added) in their [section];
  comments and every other line are kept, so a derived case is its template plus the swept keys.
- `moved_case`: the same, for a case written to another directory: a relative `[packing] file` made
  absolute against the original case's directory (where the case loader resolves it).
- `peaks_at`: first-peak amplitudes at wanted z/l0 positions from the ruler's per-layer table.
- `pairwise`: per pair of codes, relative differences of one number (the same `rel_diff` as the
  harness: |a - b| / max(|a|, |b|)).
- `sweep_table`: the Markdown table of a sweep (one row per point and position, one column per code,
  then one per pair).
"""
from __future__ import annotations

import math
import os
import re

from .compare import rel_diff


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"%s"' % v
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, int):
        return str(v)
    return repr(float(v))


def derive_case(text: str, changes: dict) -> str:
    """`changes` maps (section, key) -> value. A key present in its section is replaced in place; a
    missing key is added at the end of its section; a missing section is appended. Nothing else moves."""
    lines = text.split("\n")
    sec_re = re.compile(r"^\s*\[([^\[\]]+)\]\s*(#.*)?$")
    todo = dict(changes)
    # section spans
    spans, cur, start = {}, None, 0
    for i, ln in enumerate(lines):
        m = sec_re.match(ln)
        if m:
            if cur is not None:
                spans[cur] = (start, i)
            cur, start = m.group(1).strip(), i
    if cur is not None:
        spans[cur] = (start, len(lines))
    for (sec, key), val in list(todo.items()):
        if sec not in spans:
            continue
        a, b = spans[sec]
        kre = re.compile(r"^(\s*)%s\s*=" % re.escape(key))
        for i in range(a + 1, b):
            if kre.match(lines[i]):
                lines[i] = "%s = %s" % (key, toml_value(val))
                del todo[(sec, key)]
                break
    # additions, last section first so the spans stay valid
    for sec in sorted({s for s, _ in todo if s in spans}, key=lambda s: -spans[s][1]):
        a, b = spans[sec]
        end = b
        while end - 1 > a and not lines[end - 1].strip():
            end -= 1
        add = ["%s = %s" % (k, toml_value(v)) for (s, k), v in todo.items() if s == sec]
        lines[end:end] = add
    tail = {}
    for (sec, key), val in todo.items():
        if sec not in spans:
            tail.setdefault(sec, []).append("%s = %s" % (key, toml_value(val)))
    for sec, add in tail.items():
        lines += ["", "[%s]" % sec] + add
    return "\n".join(lines)


def layer_table(raw: dict) -> list[dict]:
    """Rows {layer, z, arrived, peak, peak_time} of a `granwave analyze --json` crystal document."""
    L = raw["layers"]

    def col(name):
        c = L[name]
        return c["values"] if isinstance(c, dict) else c

    out = []
    for i, k in enumerate(col("layer")):
        out.append(dict(layer=int(k), z=float(col("z_over_l0")[i]), arrived=bool(col("arrived")[i]),
                        peak=col("peak_value")[i], peak_time=col("peak_time")[i]))
    return out


def moved_case(text: str, changes: dict, case_path: str) -> str:
    """derive_case for a case text that will live in another directory than case_path: the packing file
    (a path relative to the case file, data/SCHEMA.md §1) is made absolute so the moved case still finds it."""
    m = re.search(r'^\s*file\s*=\s*"([^"]+)"', _section_text(text, "packing"), re.M)
    changes = dict(changes)
    if m and not os.path.isabs(m.group(1)):
        changes[("packing", "file")] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(case_path)), m.group(1)))
    return derive_case(text, changes)


def _section_text(text: str, section: str) -> str:
    """The lines of [section] (without its header), or "" if the text has none."""
    out, inside = [], False
    for ln in text.split("\n"):
        h = re.match(r"^\s*\[([^\[\]]+)\]\s*(#.*)?$", ln)
        if h:
            inside = h.group(1).strip() == section
            continue
        if inside:
            out.append(ln)
    return "\n".join(out)


def peaks_at(rows: list[dict], positions, max_dz: float = 0.5) -> dict:
    """{position: peak or None} at the layer nearest each wanted z/l0 (within max_dz, arrived)."""
    out = {}
    for p in positions:
        best = min(rows, key=lambda r: abs(r["z"] - p)) if rows else None
        ok = best is not None and abs(best["z"] - p) <= max_dz and best["arrived"] and best["peak"] is not None
        out[p] = float(best["peak"]) if ok else None
    return out


def pairwise(values: dict, codes) -> dict:
    """{"a-b": rel_diff} for each pair of codes (in the order given) that both have a finite value."""
    out = {}
    cs = [c for c in codes if c in values]
    for i in range(len(cs)):
        for j in range(i + 1, len(cs)):
            a, b = values[cs[i]], values[cs[j]]
            if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)):
                out["%s-%s" % (cs[i], cs[j])] = None
            else:
                out["%s-%s" % (cs[i], cs[j])] = rel_diff(a, b)
    return out


def pair_names(codes) -> list[str]:
    cs = list(codes)
    return ["%s-%s" % (cs[i], cs[j]) for i in range(len(cs)) for j in range(i + 1, len(cs))]


def worst(diffs) -> float | None:
    """Largest finite value of an iterable of relative differences (None if there is none)."""
    v = [d for d in diffs if d is not None and math.isfinite(d)]
    return max(v) if v else None


def decay_ratio(peaks: dict, ref_key) -> dict:
    """Each point's peak divided by the reference point's (e.g. gamma_0 = 0) at the same position."""
    ref = peaks.get(ref_key)
    return {k: (v / ref if (v is not None and ref) else None) for k, v in peaks.items()}


def _f(v, fmt="%.5g"):
    return "-" if v is None else (fmt % v)


def sweep_table(points, codes, key_label: str, value_label: str, rows_of, pairs=None) -> list[str]:
    """Markdown lines. `points`: list of (point_label, sub_label, {code: value}). Columns: key, sub,
    each code's value, each pair's relative difference (`pairs`: [(a, b)], default every pair of codes)."""
    pairs = [tuple(p.split("-", 1)) for p in pair_names(codes)] if pairs is None else list(pairs)
    head = [key_label, value_label] + list(codes) + ["d(%s-%s)" % p for p in pairs]
    md = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for label, sub, vals in rows_of(points):
        d = [pairwise({a: vals.get(a), b: vals.get(b)}, [a, b]).get("%s-%s" % (a, b)) for a, b in pairs]
        cells = [label, sub] + [_f(vals.get(c)) for c in codes] + [_f(x, "%.2e") for x in d]
        md.append("| " + " | ".join(cells) + " |")
    return md
