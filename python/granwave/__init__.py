"""granwave from Python: the solver's verbs in-process, on the same code as the program.

    import granwave as g
    case = g.Case.load(g.data_path("cases/crystal40.toml"))
    r = g.run(case.replace({"contact.kt": 1e5}))
    r.traces["layer_stress_zz"], r.time, r.layer_z, r.units["layer_stress_zz"], r.analysis["v_half_peak"]

Bad input raises ValueError with the program's message (the one `granwave check` prints after
"error: "), a failed run RuntimeError. Every function releases the GIL while the solver works;
run and sweep handle Ctrl-C (KeyboardInterrupt) within a fraction of a second and report progress.
A run's arrays are its own series in memory (no copies); run(out=None) writes no file at all.
"""
# Modules under underscore names: dir(granwave) shows the API only (tests/python/test_granwave.py).
import json as _json
import os as _os
import tempfile as _tempfile

from . import _granwave
from ._config import DATA_DIR as _DATA_DIR
from ._pulse import pulse_table

__all__ = ["Case", "Result", "data_path", "run", "analyze", "theory", "probe", "build", "sweep", "pulse_table"]



def _units(table):
    """{dataset name: unit} of the trace file's datasets (data/SCHEMA.md §3; the file says "SI"): the
    crystal's from its table of observables (`granwave observables --json`), /time, /crystal/layer_z
    (always written) and the chain's."""
    units = {"time": "s", "layer_z": "m", "bead_force": "N", "contact_force": "N"}
    units.update({o["name"]: o["unit"] for o in table["crystal"]})
    return units


_UNITS = _units(_json.loads(_granwave.observables(["--json"])))


def data_path(relative=""):
    """The path of a paper case or study shipped with granwave, e.g. data_path("cases/crystal40.toml").

    Installed: PREFIX/share/granwave/...; from a build tree: the source tree's data/.
    Raises FileNotFoundError when there is no such file."""
    p = _os.path.join(_DATA_DIR, relative)
    if not _os.path.exists(p):
        raise FileNotFoundError(f"{relative}: not among granwave's data in {_DATA_DIR}")
    return p


class Case:
    """One case file's setup (data/SCHEMA.md §1), checked as the program checks it.

    Case.load(path), Case.from_dict(d), case.to_dict(), case.replace({"contact.kt": 1e5});
    case.text is the TOML text a run stores in its trace, case.path the name messages give."""

    def __init__(self, text, path="<case>"):
        self.text = text
        self.path = path
        self.name, self.model = _granwave.parse_case(text, path)

    @classmethod
    def load(cls, path):
        """Read and check a case file (ValueError: the program's message naming the file and key)."""
        path = _os.fspath(path)
        try:
            with open(path, "rb") as f:
                text = f.read().decode("utf-8", errors="surrogateescape")
        except OSError:
            raise ValueError(f"{path}: cannot open the case file") from None
        return cls(text, path)

    @classmethod
    def from_dict(cls, d, path="<dict>"):
        """A case from a dict of TOML tables ({"case": {...}, "crystal": {...}, ...})."""
        return cls(_granwave.toml_text(d), path)

    def to_dict(self):
        """The case as nested dicts (what tomllib reads from its text)."""
        import tomllib
        return tomllib.loads(self.text)

    def replace(self, changes=None, **keys):
        """A new case with dotted keys changed: case.replace({"contact.kt": 1e5}) or
        case.replace(contact__kt=1e5). The result is checked like a case file; ValueError names the key."""
        d = self.to_dict()
        items = dict(changes or {})
        items.update({k.replace("__", "."): v for k, v in keys.items()})
        for key, value in items.items():
            *tables, last = key.split(".")
            t = d
            for name in tables:
                t = t.setdefault(name, {})
                if not isinstance(t, dict):
                    raise ValueError(f"{key}: {name} is not a table")
            t[last] = value
        # Messages name the changed case and a line of its new text, not the file's.
        return Case.from_dict(d, self.path if self.path.endswith(" (replaced)") else f"{self.path} (replaced)")

    def save(self, path):
        """Write the case text to a file (what `granwave run FILE` reads)."""
        with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(self.text)
        return path

    def _file(self, tmp):
        """A file holding this case: its own file when unchanged, else a copy in tmp."""
        if _os.path.isfile(self.path):
            with open(self.path, "rb") as f:
                if f.read().decode("utf-8", errors="surrogateescape") == self.text:
                    return self.path
        return self.save(_os.path.join(tmp, f"{self.name}.toml"))

    def __repr__(self):
        return f"Case({self.name!r}, model={self.model!r}, path={self.path!r})"


def _case(case):
    return case if isinstance(case, Case) else Case.load(case)


def _read_arrays(path):
    """Every dataset of a trace or study file but the system's copy, as numpy arrays keyed by path."""
    import h5py
    out = {}
    with h5py.File(path, "r") as f:
        def take(name, obj):
            if isinstance(obj, h5py.Dataset) and not name.startswith("system/"):
                out[name] = obj[()]
        f.visititems(take)
    return out


class Result:
    """A run: traces, energies, the run's numbers and its analysis.

    traces   {name: array} of /crystal or /chain (layer_stress_zz [nt, nlayers], ...)
    time     /time [nt] (s);  layer_z  /crystal/layer_z [nlayers] (m; crystal only)
    energy   {kinetic, potential, dissipated, work_in[, verlet_correction]: [nt] (J)}
    units    {name: unit} of every array
    numbers  the `granwave run --json` object without its analysis (steps, wall_seconds, ...)
    analysis what `granwave analyze TRACE --json` gives (None when the trace cannot be measured);
             with out=None its "file" is None
    trace    the trace file written (None when run(out=None))

    The arrays of a chain or crystal run are the run's own series, not copies: numpy views of the
    buffers the solver filled (flags.owndata is False; their base holds the buffers), bit for bit
    the datasets of the trace file. Two were made for the file rather than filled by the run and
    are held the same way: a chain's energy "dissipated" (zeros: the chain is conservative) and
    traces["full_rate/beads"] (bead indices as int64). An impact run's arrays are its series, moved
    (owned by the capsule, not copied): traces "overlap", "contact_force_normal", "body1/position", ..."""

    def __init__(self, numbers, arrays, trace):
        self.analysis = numbers.pop("analysis", None)
        self.numbers = numbers
        self.trace = trace
        if trace is None:
            self.numbers["trace"] = None
            if self.analysis is not None:
                self.analysis["file"] = None
        self.time = arrays.pop("time", None)
        self.energy = {k.split("/", 1)[1]: v for k, v in arrays.items() if k.startswith("energy/")}
        self.traces = {k.split("/", 1)[-1]: v for k, v in arrays.items() if not k.startswith("energy/")}
        self.layer_z = self.traces.pop("layer_z", None)
        self.units = {k: _UNITS.get(k.rsplit("/", 1)[-1], "SI") for k in
                      ["time", *self.traces, *self.energy] + (["layer_z"] if self.layer_z is not None else [])}

    def __repr__(self):
        return f"Result({self.numbers.get('case')!r}, {len(self.time)} samples, traces={sorted(self.traces)})"


class _Bar:
    """progress=True: a tqdm bar of a run's steps or a study's runs (Debian: python3-tqdm)."""

    def __init__(self, name, unit="steps"):
        from tqdm import tqdm  # the text bar: works in a terminal and a notebook without ipywidgets
        self.bar = tqdm(desc=name, unit=unit, unit_scale=True)

    def __call__(self, done, total):
        self.bar.total = total
        self.bar.update(done - self.bar.n)

    def close(self):
        self.bar.close()


def _progress(progress, name, unit):
    """The callback of progress= (None, True for a bar, or a callable) and the bar to close."""
    bar = _Bar(name, unit) if progress is True else None
    return (bar if bar else (progress or None)), bar


def run(case, out=None, system=None, progress=None):
    """Run a case in-process, as `granwave run CASE --json -o OUT` does, and return a Result.

    case      a Case or a case file's path
    out       the trace file to write (the program's file, written as OUT.tmp and renamed, bit
              for bit the program's); None: no file at all -- the trace is built and measured in
              memory (no VTK snapshots either)
    system    a system file from build() to run instead of building the packing
    progress  None; True for a tqdm bar; or a callable progress(steps_done, steps_total), called
              from the run's thread with the GIL every few milliseconds

    The arrays are the run's own series (see Result), not read back from the file.
    The GIL is released while the run works; every 5 ms (at the next output sample of a crystal or
    chain run) it takes it back, so Ctrl-C (KeyboardInterrupt) stops the run, leaving neither OUT
    nor OUT.tmp.
    Raises ValueError for a refused case, RuntimeError for a failed run (an unstable crystal)."""
    case = _case(case)
    callback, bar = _progress(progress, case.name, "steps")
    in_memory = out is None
    # without out, the path names the trace in messages only
    path = f"{case.name}.traces.h5 (not written)" if in_memory else _os.fspath(out)
    try:
        text, arrays = _granwave.run(case.text, case.path, path, _os.fspath(system) if system else "", callback,
                                     in_memory=in_memory)
    except KeyboardInterrupt:
        # A Ctrl-C after the time loop (while the file was written) is handled here: no file either.
        for p in (path, path + ".tmp") if not in_memory else ():
            if _os.path.exists(p):
                _os.remove(p)
        raise
    finally:
        if bar:
            bar.close()
    return Result(_json.loads(text), arrays, None if in_memory else path)


def _options(opts):
    args = []
    for k, v in opts.items():
        if v is None or v is False:
            continue
        args += [f"--{k.replace('_', '-')}"] + ([] if v is True else [str(v)])
    return args


def analyze(trace, **options):
    """`granwave analyze TRACE --json` of any code's trace file (or a Result written with out=).

    options: layers="LO:HI", field=..., t_max=..., period="oscillation"|"pulse",
    wavenumber_speed=...; the dict the program prints (speeds, arrivals, peaks, dispersion)."""
    if isinstance(trace, Result):
        if trace.trace is None:
            raise ValueError("analyze: this Result has no trace file (run it with out=...); its .analysis is there")
        trace = trace.trace
    return _json.loads(_granwave.analyze([_os.fspath(trace), "--json", *_options(options)]))


def theory(case, layers=None, nk=None):
    """`granwave theory CASE --json`: eq. (10)'s tensor, the lattice dynamics with rotations and
    prestress (long-wave speeds, dispersion), V_p, V_s, omega_0; "relaxed" (the non-affine tensor of
    the slab and the bulk: V_pz, V_sz, A_relaxed, rattlers, zero modes) and "effective_medium" (the
    affine estimate; Walton's for Hertz-Mindlin); for impact cases Hertz and Coulomb. pulse_table
    sets the relaxed speeds beside what a pulse measures (`analyze`)."""
    case = _case(case)
    with _tempfile.TemporaryDirectory(prefix="granwave-") as tmp:
        return _json.loads(_granwave.theory([case._file(tmp), "--json", *_options({"layers": layers, "nk": nk})]))


def probe(case, strains=None, amplitude=None, tolerance=None):
    """`granwave probe CASE --json`: the static probe (issue 39) of a crystal case. The simulation
    strains the packing by +-amplitude (default 1e-7), relaxes it with FIRE under the full law and
    compares the nominal stress's change dP/de with the relaxed slab tensor's column.

    strains    None (all: zz, zx, xx, yy, yx), one name ("yx") or a list of them
    tolerance  FIRE's stop, a fraction of amplitude <k_n> <l> (default 1e-6)

    The dict the program prints (data/SCHEMA.md), with every 3 x 3 matrix ("P0" and each strain's
    "dP_de", "A_relaxed_column", "dsigma_de") as a numpy array under its "values", and "table": the
    strains' rows as arrays keyed by column ("strain", "A_relaxed", "dP" in Pa, "relative_error",
    "max_slip", "sliding", "contacts_changed")."""
    import numpy as np
    case = _case(case)
    if strains is not None and not isinstance(strains, str):
        strains = ",".join(strains)
    opts = {"strain": strains, "amplitude": amplitude, "tolerance": tolerance}
    with _tempfile.TemporaryDirectory(prefix="granwave-") as tmp:
        out = _json.loads(_granwave.probe([case._file(tmp), "--json", *_options(opts)]))
    matrices = [out["P0"]] + [r[k] for r in out["strains"] for k in ("dP_de", "A_relaxed_column", "dsigma_de")]
    for m in matrices:
        m["values"] = np.array(m["values"], dtype=float)
    rows = out["strains"]
    out["table"] = {"strain": np.array([r["strain"] for r in rows])}
    for k in ("A_relaxed", "dP"):
        out["table"][k] = np.array([r[k]["value"] for r in rows], dtype=float)
    for k in ("relative_error", "max_slip"):
        out["table"][k] = np.array([r[k] for r in rows], dtype=float)
    for k in ("sliding", "contacts_changed"):
        out["table"][k] = np.array([r[k] for r in rows], dtype=int)
    return out


def build(case, out=None):
    """`granwave build CASE -o OUT`: the resolved system file (default NAME.system.h5); its path."""
    case = _case(case)
    out = _os.fspath(out) if out is not None else f"{case.name}.system.h5"
    with _tempfile.TemporaryDirectory(prefix="granwave-") as tmp:
        _granwave.build([case._file(tmp), "-o", out])
    return out


def sweep(study, out=None, threads=None, limit=None, progress=None):
    """`granwave sweep STUDY -o OUT --threads N`: a study (resumable: the same call again finishes
    a stopped one). Returns {"file": OUT, "tables": {path: array} of every dataset but /system,
    "attrs": the root attributes, "text": what the program prints}.

    progress  None; True for a tqdm bar; or a callable progress(runs_done, runs_total), called from
              this thread with the GIL every few milliseconds

    The study runs on a thread of its own (its members on `threads` OpenMP threads) without the
    GIL; this thread handles signals meanwhile, so Ctrl-C (KeyboardInterrupt) stops it within a
    fraction of a second: each running member ends at its next output sample. What it leaves is what
    the program leaves after a kill: neither OUT nor OUT.tmp, the finished runs committed under
    OUT.parts/ (no temporary file there either), which the same call again resumes from. A Ctrl-C
    once every run is done lets the study file be written, then raises."""
    study = _os.fspath(study)
    out = _os.fspath(out) if out is not None else _os.path.splitext(_os.path.basename(study))[0] + ".h5"
    callback, bar = _progress(progress, _os.path.basename(study), "runs")
    try:
        text = _granwave.sweep([study, "-o", out, "--quiet", *_options({"threads": threads, "limit": limit})], callback)
    finally:
        if bar:
            bar.close()
    import h5py
    with h5py.File(out, "r") as f:
        attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
    return {"file": out, "tables": _read_arrays(out), "attrs": attrs, "text": text}
