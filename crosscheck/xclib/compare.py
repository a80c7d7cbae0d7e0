"""Comparison maths on traces: pure numpy, no knowledge of which code wrote what."""
from __future__ import annotations

import numpy as np


def common_grid(ta: np.ndarray, tb: np.ndarray, rtol: float = 1e-9):
    """Indices (ia, ib) of the samples both traces share (same instants to rtol of the spacing).
    Traces are compared on shared instants only: no interpolation hides a convention."""
    ta = np.asarray(ta, float)
    tb = np.asarray(tb, float)
    if len(ta) == 0 or len(tb) == 0:
        return np.zeros(0, int), np.zeros(0, int)
    step = np.median(np.diff(ta)) if len(ta) > 1 else 1.0
    ib = np.searchsorted(tb, ta)
    ib = np.clip(ib, 0, len(tb) - 1)
    best = ib.copy()
    left = np.clip(ib - 1, 0, len(tb) - 1)
    closer = np.abs(tb[left] - ta) < np.abs(tb[ib] - ta)
    best[closer] = left[closer]
    ok = np.abs(tb[best] - ta) <= rtol * step + 1e-18
    return np.nonzero(ok)[0], best[ok]


def trace_metrics(a: np.ndarray, b: np.ndarray) -> dict:
    """max |a - b| / peak(|a|, |b|) and relative L2 ||a - b|| / ||a|| (a, b baseline-subtracted)."""
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    diff = a - b
    peak = max(float(np.max(np.abs(a))) if a.size else 0.0, float(np.max(np.abs(b))) if b.size else 0.0)
    na = float(np.linalg.norm(a))
    nb = float(np.linalg.norm(b))
    ref = max(na, nb)
    return dict(max_abs=float(np.max(np.abs(diff))) if diff.size else 0.0, peak=peak,
                max_rel=float(np.max(np.abs(diff))) / peak if peak > 0 else (0.0 if not diff.size or not np.any(diff) else np.inf),
                l2_rel=float(np.linalg.norm(diff)) / ref if ref > 0 else 0.0, n=int(a.size))


def rel_diff(x: float, y: float) -> float:
    s = max(abs(x), abs(y))
    return abs(x - y) / s if s > 0 else 0.0


def choose_layers(layer_z: np.ndarray, l0: float, nlayers: int, fixed_layers: int, wanted=(10, 80, 150),
                  free_range: tuple[int, int] | None = None) -> list[int]:
    """Layer indices at z/l0 = wanted (those inside the free part: the layers between the fixed ones, or
    `free_range` [first, last + 1) of a packing file's bins, xclib.traces.free_layer_range); if fewer than
    two exist, the middle and the last free layers are added."""
    zl = np.asarray(layer_z) / l0
    if free_range is None:
        free_range = (fixed_layers, nlayers - fixed_layers)
    free = range(*free_range)
    out = []
    for w in wanted:
        k = int(np.argmin(np.abs(zl - w)))
        if abs(zl[k] - w) < 0.5 and k in free and k not in out:
            out.append(k)
    if len(out) < 2:
        for k in (free.start + (free.stop - free.start) // 2, free.stop - 1):
            if k in free and k not in out:
                out.append(k)
    return sorted(out)


def choose_contacts(ncontacts: int, has_wall: bool) -> list[int]:
    """Chain contacts compared trace by trace: the striker's, two in the first dimers (9, 10: the
    two-hump and single-peak kinds), the middle and the last bead-bead contact, and the wall's."""
    nbb = ncontacts - (1 if has_wall else 0)
    cand = [0, 9, 10, nbb // 2, nbb - 1] + ([ncontacts - 1] if has_wall else [])
    out = []
    for c in cand:
        if 0 <= c < ncontacts and c not in out:
            out.append(c)
    return out
