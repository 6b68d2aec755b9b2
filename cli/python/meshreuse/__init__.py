"""meshreuse from Python: meshes, orderings, smoothing, access traces, exact reuse distances and
cache simulation, with numpy arrays in and out.

The compiled module (``meshreuse._meshreuse``, pybind11) only converts; every algorithm is the C++
libraries' that the ``meshreuse`` command runs, so a result here equals the command's on the same
input, table cell for table cell.

    import numpy as np, meshreuse as mr
    mesh = mr.Mesh.read("carabiner.node")          # or mr.Mesh(points, triangles)
    perm = mesh.ordering("grid-wave", seed=1)      # new id -> old id (numpy int32)
    r = mr.analyze(np.fromfile("t.u64", np.uint64), granularity="element", threads=2)
    r.cold, r.q50, r.sum, r.histogram              # histogram: (distances, counts) numpy arrays
    sim = mr.simulate(mesh, ordering="bfs", machine="westmere-ex", threads=8, placement="scatter")

Keywords of ``analyze``, ``simulate`` and ``compare`` are the command's options with ``_`` for
``-`` (``sample_rate=0.1`` is ``--sample-rate 0.1``; a list is joined with commas; ``True`` is a
flag): ``meshreuse analyze --help`` lists them, and they are checked, with the same messages, by
the command's own parser. Errors: ``ValueError`` for a bad option or bad data (the command's
message, naming the file and place), ``TypeError`` for an unknown keyword, ``OSError`` for a file
that cannot be read or written. Long work releases the GIL; Ctrl-C stops it at the next progress
point (``KeyboardInterrupt``; nothing half-written).
"""

import json as _json
import os as _os

import numpy as _np

from . import _meshreuse

__all__ = ["Mesh", "orderings", "save_permutation", "smooth", "trace", "analyze", "merge", "summarize", "simulate",
           "compare", "Analysis", "Stream", "Results", "Table", "ACCESS_DTYPE"]

Mesh = _meshreuse.Mesh
save_permutation = _meshreuse.save_permutation
Mesh.__doc__ = """A 2D triangle mesh (core/mesh.h).

Mesh.read(path): any format the command reads (.node/.ele, .msh, .mrm).
Mesh(points, triangles, name="mesh"): from arrays, points (n, 2) float, triangles (m, 3)
  0-based indices, checked as a file is (ValueError naming the row); points no triangle uses
  are dropped with a warning.
Arrays (read-only numpy views of the mesh's own memory, no copy): points (n, 2) float64,
triangles (m, 3) int32, boundary (n,) uint8, interior (int32: the smoother's iteration space),
neighbours and vertex_triangles (CSR rows: (offsets int64, ids int32)).
quality(): the global quality; triangle_qualities(), vertex_qualities().
ordering(spec, seed=1): a registered ordering (see orderings()) as a permutation, new id -> old id.
permute(perm, triangle_order="sorted"): the mesh laid out in a permutation (checked: a bijection).
write(path): any format the command writes (.vtu, .vtk, .msh, .mrm, or a prefix for .node/.ele);
  returns the files written.
"""

#: The numpy dtype of a traced access (tracer/access_stream.h Access): byte address, element (the
#: vertex id, or 2^64-1 when the access touches no vertex record), size in bytes, thread (stream),
#: kind (0 adjacency row, 1 coordinate read, 2 coordinate write, 3 other), array (core/access.h),
#: write.
ACCESS_DTYPE = _np.dtype([("address", "<u8"), ("element", "<u8"), ("size", "<u4"),
                          ("thread", "u1"), ("kind", "u1"), ("array", "u1"), ("write", "?")])

_NO_ELEMENT = (1 << 64) - 1


def orderings():
    """The registered orderings: a list of dicts (name, description, reference, seeded, argument:
    "none", "optional" or "required", as in "metis:BYTES")."""
    return _meshreuse._orderings()


class SmoothResult:
    """What smooth() returns: the smoothed points (n, 2) and per sweep the global quality, its
    improvement, wall and thread CPU seconds; quality before and after, converged."""

    def __init__(self, d):
        self.points = d["points"]
        self.quality = d["quality"]
        self.improvement = d["improvement"]
        self.seconds = d["seconds"]
        self.cpu_seconds = d["cpu_seconds"]
        self.sweeps = d["sweeps"]
        self.quality_before = d["quality_before"]
        self.quality_after = d["quality_after"]
        self.converged = d["converged"]

    def __repr__(self):
        return (f"SmoothResult(sweeps={self.sweeps}, quality {self.quality_before:.6f} -> "
                f"{self.quality_after:.6f}, converged={self.converged})")


def smooth(mesh, *, mode="gauss-seidel", quality="per-move", max_iters=100, tol=5e-6, threads=1,
           kernel="laplacian"):
    """Laplacian smoothing of the mesh as stored (the mesh itself is not changed): the paper's
    sweep, ``meshreuse smooth``'s options; ``kernel`` runs another mesh kernel instead
    (``kernels()``; its own measure per sweep in ``quality``). To smooth in an ordering, permute
    first: ``smooth(mesh.permute(mesh.ordering("bfs")))``."""
    return SmoothResult(_meshreuse._smooth(mesh, mode, quality, int(max_iters), float(tol),
                                           int(threads), kernel))


def kernels():
    """The registered mesh kernels (``meshreuse kernels``): name, visit unit, measure, threads."""
    return _meshreuse._kernels()


def trace(mesh, *, ordering="ori", seed=1, iterations=1, threads=1, mode="gauss-seidel",
          triangle_order="sorted", kernel="laplacian"):
    """The access stream of ``iterations`` exact sweeps of the mesh laid out in ``ordering``, as
    the analyzer receives it (``meshreuse trace``'s accesses): a structured array of
    ACCESS_DTYPE, threads' streams as the static schedule deals them; ``kernel``: another mesh
    kernel's sweeps."""
    a = _meshreuse._trace(mesh, ordering, int(seed), int(iterations), int(threads), mode,
                          triangle_order, kernel)
    return a.view(ACCESS_DTYPE)


# ---- keyword options to the command's options ----

def _option_args(options):
    args = []
    for key, value in options.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        if value is True:
            args.append(flag)
        elif isinstance(value, (list, tuple)):
            args += [flag, ",".join(str(v) for v in value)]
        else:
            args += [flag, str(value)]
    return args


def _ids(array):
    """A 1-d integer array as C-contiguous uint64 ids: uint64 and int64 without a copy (int64
    checked non-negative), other integer types converted."""
    a = _np.asarray(array)
    if a.ndim != 1:
        raise ValueError(f"ids must be one-dimensional, not of shape {a.shape}")
    if a.dtype.kind not in "iu":
        raise TypeError(f"ids must be integers, not {a.dtype}")
    if a.dtype.kind == "i" and a.size and int(a.min()) < 0:
        at = int(_np.argmax(a < 0))
        raise ValueError(f"ids: value {at} is {int(a[at])}, negative: ids must be >= 0")
    if a.dtype.itemsize == 8:
        a = a.view(_np.uint64)
    else:
        a = a.astype(_np.uint64)
    return _np.ascontiguousarray(a)


def _source(source, options):
    """Inputs for the command line and what is in memory: paths, a Mesh, or ids."""
    if isinstance(source, Mesh):
        name = source.path or source.name
        return [name], source
    if isinstance(source, (str, _os.PathLike)):
        return [_os.fspath(source)], None
    if isinstance(source, _np.ndarray):
        options.setdefault("format", "u64")
        return ["array"], _ids(source)
    if isinstance(source, (list, tuple)) and source and all(
            isinstance(s, (str, _os.PathLike)) for s in source):
        return [_os.fspath(s) for s in source], None
    raise TypeError("source must be a path, a list of paths, a Mesh or a 1-d integer numpy "
                    f"array, not {type(source).__name__}")


def _singular(options):
    if "ordering" in options:
        if "orderings" in options:
            raise TypeError("ordering and orderings exclude each other")
        options["orderings"] = options.pop("ordering")
    return options


# ---- results ----

class Table(dict):
    """A result table: column name -> numpy array (int64, or float64 with NaN for a missing
    value) or a list (text, None where missing; whole numbers beyond 64 bits as Python ints), in
    the command's column order; cell for cell its CSV."""

    @property
    def nrows(self):
        return len(next(iter(self.values()))) if self else 0

    def rows(self):
        """Each row as a dict."""
        keys = list(self)
        return [{k: self[k][i] for k in keys} for i in range(self.nrows)]

    def __repr__(self):
        return f"Table({self.nrows} rows: {', '.join(self)})"


class _Tables(dict):
    """The tables by name, each converted when first read (a histogram or a miss-ratio curve may
    hold a row per distance)."""

    def __init__(self, run):
        super().__init__((name, None) for name in run.names())
        self._run = run

    def __getitem__(self, name):
        t = super().__getitem__(name)
        if t is None:
            t = Table(self._run.table(name))
            super().__setitem__(name, t)
        return t

    def values(self):
        return [self[k] for k in self]

    def items(self):
        return [(k, self[k]) for k in self]

    def __repr__(self):
        return f"tables({', '.join(self)})"


class Results:
    """What a command produced: ``tables`` (name -> Table, the files ``--out`` writes; converted
    when read), ``table`` (what ``--csv`` prints), ``text`` (what it prints for people; also
    str()), ``configuration`` (run.json's)."""

    def __init__(self, run):
        self._run = run
        self.tables = _Tables(run)
        self.configuration = _json.loads(run.configuration())
        self.extra = _json.loads(run.extra())
        self._table = None

    @property
    def table(self):
        if self._table is None:
            csv = self._run.csv()
            self._table = None if csv is None else Table(csv)
        return self._table

    @property
    def text(self):
        return self._run.text()

    def __str__(self):
        return self.text

    def __repr__(self):
        return f"{type(self).__name__}({', '.join(self.tables)})"


class Stream:
    """One analysed stream (an input x ordering x thread x granularity): accesses, cold (= distinct
    ids), sum (exact, an int), mean, max, quantiles and modelled misses (its row of the summary
    table: ``row``; ``q50``, ``L1_misses``... as attributes), and the exact histogram as numpy
    arrays: ``histogram`` = (distances, counts), every distance with a count, in order."""

    def __init__(self, d, row):
        self.input = d["input"]
        self.ordering = d["ordering"]
        self.thread = d["thread"]
        self.granularity = d["granularity"]
        self.accesses = d["accesses"]
        self.cold = d["cold"]
        self.distinct = d["cold"]
        self.sum = d["sum"]
        self.max = d["max"]
        self.histogram = (d["distances"], d["counts"])
        self.row = row

    @property
    def mean(self):
        finite = self.accesses - self.cold
        return self.sum / finite if finite else float("nan")

    def __getattr__(self, name):
        row = self.__dict__.get("row") or {}
        if name in row:
            return row[name]
        raise AttributeError(f"a stream has no {name!r} (its row: {', '.join(row)})")

    def __repr__(self):
        return (f"Stream({self.input} {self.ordering or ''} thread {self.thread} "
                f"{self.granularity}: {self.accesses} accesses, {self.cold} cold)")


class Analysis(Results):
    """What analyze() returns (``meshreuse analyze``): ``tables`` analyze (the summary), histogram
    (binned as the command writes it), mrc, and profile when asked; ``streams``, one Stream per
    exact stream with its exact histogram. With a single stream its attributes are the analysis'
    own: ``r.cold``, ``r.q50``, ``r.sum``, ``r.histogram``."""

    def __init__(self, d):
        super().__init__(d["run"])
        rows = {}
        for row in self.table.rows():
            key = (row["input"], row["ordering"] or "", str(int(row["thread"])),
                   row["granularity"])
            rows[key] = row
        self.streams = [Stream(s, rows.get((s["input"], s["ordering"], str(s["thread"]),
                                            s["granularity"])))
                        for s in d["streams"]]

    def stream(self, granularity=None, thread=0, input=None, ordering=None):
        """The stream with this key (each left out: any)."""
        for s in self.streams:
            if ((granularity is None or s.granularity == granularity) and s.thread == thread
                    and (input is None or s.input == input)
                    and (ordering is None or s.ordering == ordering)):
                return s
        raise KeyError((granularity, thread, input, ordering))

    def __getattr__(self, name):
        streams = self.__dict__.get("streams", [])
        if len(streams) == 1:
            return getattr(streams[0], name)
        raise AttributeError(f"{name!r}: the analysis has {len(streams)} streams; pick one with "
                             f".stream(granularity=..., thread=..., ordering=...)")


def analyze(source, *, profile=False, progress=False, **options):
    """Exact LRU reuse distances (``meshreuse analyze``) of a mesh (a Mesh or its path: streamed
    through the traced smoother in each of ``orderings``), trace files (ours, or another tool's
    with ``format=``), or a 1-d integer numpy array of ids (read where it lies, exactly as a u64
    trace file of the same values: its values are addresses, analysed by cache line, unless
    ``granularity="element"`` makes them ids, as the command's ``--format u64``). Options are the command's
    (``orderings``, ``iterations``, ``threads``, ``granularity``, ``line_bytes``, ``quantiles``,
    ``cache``, ``sample_rate``, ``sample_size``, ``seed``, ``ranks``...); ``profile=True``
    computes the reuse profile over time (the command does when it writes one); ``progress=True``
    prints progress lines on stderr. A chunk (``chunk="r/P"`` with ``summary_out=PATH``) writes
    its summary and returns None: see summarize() and merge()."""
    options = _singular(options)
    inputs, memory = _source(source, options)
    d = _meshreuse._analyze(inputs + _option_args(options), memory, bool(profile),
                            bool(progress))
    return None if d is None else Analysis(d)


def summarize(source, chunk, out, **options):
    """Chunk r of P of a trace file (``chunk=(r, P)`` or "r/P") analysed into the summary file
    ``out`` (``meshreuse analyze --chunk r/P --summary-out out``): a batch array's task; merge()
    joins the P summaries into exactly the whole analysis."""
    if isinstance(chunk, (tuple, list)):
        chunk = f"{chunk[0]}/{chunk[1]}"
    analyze(source, chunk=chunk, summary_out=_os.fspath(out), **options)


def merge(summaries, *, profile=False, progress=False, **options):
    """The summaries of chunks 0..P-1 (summarize()) merged into exactly the serial analysis."""
    return analyze([_os.fspath(s) for s in summaries], merge=True, profile=profile,
                   progress=progress, **options)


def simulate(source, *, per_sweep=False, progress=False, **options):
    """The set-associative cache simulator (``meshreuse simulate``) over a mesh, trace files or
    a numpy array of addresses (a u64 trace's values): private caches per stream (``cache=``,
    default the Westmere-EX's), or with ``machine="westmere-ex"`` the many-core machine
    (``threads``, a list for several runs, ``placement``, ``prefetch``...). Returns Results:
    ``table`` holds the counts per level (accesses, hits, misses...) as numpy arrays."""
    options = _singular(options)
    inputs, memory = _source(source, options)
    return Results(_meshreuse._simulate(inputs + _option_args(options), memory, bool(per_sweep),
                                        bool(progress)))


def compare(meshes, *, progress=False, **options):
    """The smoother timed under several orderings and thread counts (``meshreuse compare``:
    warm-up, interleaved rounds, medians with bootstrap intervals, speedups with verdicts).
    ``meshes``: paths, or Mesh objects read from a file."""
    if not isinstance(meshes, (list, tuple)):
        meshes = [meshes]
    paths = []
    for m in meshes:
        if isinstance(m, Mesh):
            if not m.path:
                raise ValueError("compare times the command's whole run from a file: write the "
                                 "mesh first (mesh.write('m.mrm')) and give its path")
            paths.append(m.path)
        else:
            paths.append(_os.fspath(m))
    return Results(_meshreuse._compare(paths + _option_args(_singular(options)), bool(progress)))
