# The Python module against the command line: every function's result equals what `meshreuse`
# prints or writes for the same input (tables cell for cell, histograms bucket for bucket, misses
# per level, smoothed coordinates bit for bit, permutations equal); zero-copy views; errors mapped
# with the command's messages; Ctrl-C; no leak over 1,000 calls. Run by ctest (tests/CMakeLists.txt)
# with PYTHONPATH at the built package, MESHREUSE_BIN the command, MESHREUSE_TEST_DATA the meshes.
import csv
import gc
import io
import json
import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import meshreuse as mr

BIN = os.environ["MESHREUSE_BIN"]
DATA = os.environ["MESHREUSE_TEST_DATA"]
NODE = os.path.join(DATA, "two_interior.node")
PLATE = os.path.join(DATA, "plate41.msh")


def cli(*args, quiet=True):
    r = subprocess.run([BIN, *map(str, args)] + (["--quiet"] if quiet else []),
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


def cli_csv(*args):
    return list(csv.reader(io.StringIO(cli(*args, "--csv"))))


def rows_of(table):
    """The Table's cells as strings, read back from the numbers it holds (exact: ints as ints,
    floats by repr, which round-trips the command's shortest decimals)."""
    out = [list(table)]
    for i in range(table.nrows):
        row = []
        for k in table:
            v = table[k][i]
            if v is None or (isinstance(v, float) and np.isnan(v)):
                row.append("")
            elif isinstance(v, (np.integer, int)):
                row.append(str(int(v)))
            elif isinstance(v, (np.floating, float)):
                row.append(repr(float(v)))
            else:
                row.append(str(v))
        out.append(row)
    return out


def same_cells(ours, theirs, skip=()):
    """Tables equal cell for cell; numbers compared as numbers (the command may print 2.10 where
    repr says 2.1), every other cell as text; columns in `skip` left out."""
    assert ours[0] == theirs[0]
    assert len(ours) == len(theirs)
    for a, b in zip(ours[1:], theirs[1:]):
        for col, x, y in zip(ours[0], a, b):
            if col in skip:
                continue
            if x == y:
                continue
            assert float(x) == float(y), (col, x, y)


@pytest.fixture(scope="module")
def ids():
    rng = np.random.default_rng(7)
    return (rng.zipf(1.3, 20000) % 3000).astype(np.uint64)


@pytest.fixture
def u64file(tmp_path, ids):
    p = tmp_path / "ids.u64"
    ids.tofile(p)
    return str(p)


# ---- meshes ----

def test_mesh_read_matches_mesh_info():
    m = mr.Mesh.read(NODE)
    info = json.loads(cli("mesh", "info", NODE, "--json"))
    assert m.num_vertices == info["vertices"]
    assert m.num_triangles == info["triangles"]
    assert m.num_boundary == info["boundary_vertices"]
    assert len(m.interior) == info["interior_vertices"]
    assert m.points.shape == (m.num_vertices, 2) and m.points.dtype == np.float64
    assert m.triangles.shape == (m.num_triangles, 3) and m.triangles.dtype == np.int32
    assert m.quality() == info["quality"]["mean"]


def test_views_are_zero_copy_and_read_only():
    m = mr.Mesh.read(PLATE)
    p1, p2 = m.points, m.points
    assert p1.__array_interface__["data"][0] == p2.__array_interface__["data"][0]
    assert not p1.flags.writeable and not m.triangles.flags.writeable
    with pytest.raises(ValueError):
        p1[0, 0] = 1.0
    off, nbr = m.neighbours
    assert off.dtype == np.int64 and nbr.dtype == np.int32 and off[-1] == len(nbr)
    # The view keeps the mesh alive.
    pts = m.points
    expect = pts.copy()
    del m, p1, p2
    gc.collect()
    assert np.array_equal(pts, expect)


def test_mesh_from_arrays_equals_the_file():
    m = mr.Mesh.read(PLATE)
    b = mr.Mesh(np.array(m.points), np.array(m.triangles, dtype=np.int64))
    assert np.array_equal(b.points, m.points)
    assert np.array_equal(b.triangles, m.triangles)
    assert np.array_equal(b.neighbours[1], m.neighbours[1])
    assert b.quality() == m.quality()


def test_mesh_from_arrays_refused_with_the_readers_messages():
    pts = np.array([[0, 0], [1, 0], [0, 1], [1, 1]], dtype=float)
    with pytest.raises(ValueError, match="corner 7"):
        mr.Mesh(pts, np.array([[0, 1, 7]]))
    with pytest.raises(ValueError, match="shape"):
        mr.Mesh(pts[:, :1], np.array([[0, 1, 2]]))
    with pytest.raises(ValueError, match="triangles:1"):  # the row, as a file's line
        mr.Mesh(np.array([[0, 0], [1, 0], [2, 0], [0, 1]], float), np.array([[0, 1, 3], [0, 1, 2]]))


def test_write_and_read_back(tmp_path):
    m = mr.Mesh.read(PLATE)
    files = m.write(str(tmp_path / "m.mrm"))
    assert files == [str(tmp_path / "m.mrm")]
    back = mr.Mesh.read(files[0])
    assert np.array_equal(back.points, m.points) and np.array_equal(back.triangles, m.triangles)


# ---- orderings ----

def test_orderings_listed_as_the_command_lists_them():
    names = [o["name"] for o in mr.orderings()]
    listed = json.loads(cli("orderings", "--json", quiet=False))
    assert names == [o["name"].split("[")[0].split(":")[0] for o in listed]  # the command adds
    # how an argument is written (metis[:ARG], file:PATH); the module says it in "argument"
    assert {o["name"]: o["argument"] for o in mr.orderings()}["file"] == "required"
    assert "rdr" in names and "grid-wave" in names


@pytest.mark.parametrize("spec", ["bfs", "rdr", "grid-wave", "random"])
def test_ordering_equals_reorder(tmp_path, spec):
    m = mr.Mesh.read(PLATE)
    perm = m.ordering(spec, seed=3)
    cli("reorder", PLATE, "--ordering", spec, "--seed", "3", "-o", tmp_path / "r")
    theirs = np.loadtxt(tmp_path / "r.perm", dtype=np.int64, comments="#")
    assert np.array_equal(perm, theirs)
    assert np.array_equal(np.sort(perm), np.arange(m.num_vertices))


def test_permutation_from_python_checked_and_applied(tmp_path):
    m = mr.Mesh.read(PLATE)
    perm = np.random.default_rng(1).permutation(m.num_vertices)
    laid = m.permute(perm)
    assert np.array_equal(laid.points, m.points[perm])
    bad = perm.copy()
    bad[1] = bad[0]
    with pytest.raises(ValueError, match="repeat|twice|appears"):
        m.permute(bad)
    with pytest.raises(ValueError, match="permutation of 3 ids"):
        m.permute(np.arange(3))
    # Saved, it is an ordering the command reads back.
    mr.save_permutation(m, perm, str(tmp_path / "p.perm"))
    cli("reorder", PLATE, "--ordering", f"file:{tmp_path / 'p.perm'}", "-o", tmp_path / "q")
    assert np.array_equal(np.loadtxt(tmp_path / "q.perm", dtype=np.int64, comments="#"), perm)


# ---- smoothing ----

# Another mesh kernel (meshreuse kernels): the module's smoothing and trace are the command's.
@pytest.mark.parametrize("kernel", ["untangle", "smart-laplacian", "edge-swap"])
def test_a_kernel_smooths_as_the_command(tmp_path, kernel):
    assert kernel in [k["name"] for k in mr.kernels()]
    m = mr.Mesh.read(PLATE)
    r = mr.smooth(m, kernel=kernel, max_iters=5)
    # The mesh as read: its own triangle order (the command sorts them by default).
    cli("smooth", PLATE, "--kernel", kernel, "--max-iters", 5, "--triangle-order", "file", "-o",
        tmp_path / "k.mrm")
    theirs = mr.Mesh.read(str(tmp_path / "k.mrm"))
    assert np.array_equal(r.points, theirs.points)
    assert r.sweeps == len(r.quality) <= 5


def test_a_kernels_trace_is_the_commands(tmp_path):
    m = mr.Mesh.read(PLATE)
    a = mr.trace(m, ordering="rdr", iterations=2, kernel="assembly")
    out = cli("trace", PLATE, "--ordering", "rdr", "-k", 2, "--kernel", "assembly", "-o",
              tmp_path / "a.trace")
    assert f"{len(a):,}".replace(",", "") in out.replace(",", "")
    with pytest.raises(ValueError, match="unknown kernel"):
        mr.smooth(m, kernel="nope")
    with pytest.raises(ValueError, match="one thread only"):
        mr.trace(m, kernel="assembly", threads=2)


@pytest.mark.parametrize("mode", ["gauss-seidel", "jacobi"])
def test_smooth_equals_the_command_bit_for_bit(tmp_path, mode):
    m = mr.Mesh.read(PLATE)
    laid = m.permute(m.ordering("bfs"))
    r = mr.smooth(laid, mode=mode, max_iters=7)
    cli("smooth", PLATE, "--ordering", "bfs", "--mode", mode, "--max-iters", 7, "-o",
        tmp_path / "s.mrm")
    theirs = mr.Mesh.read(str(tmp_path / "s.mrm"))
    assert np.array_equal(r.points, theirs.points)
    assert r.sweeps == len(r.quality) <= 7
    assert r.quality_after == pytest.approx(r.quality[-1], rel=1e-12)
    assert np.array_equal(laid.points, m.points[m.ordering("bfs")])  # the input is untouched


# ---- traces and analysis ----

def test_trace_elements_analyse_as_the_mesh_does():
    m = mr.Mesh.read(PLATE)
    t = mr.trace(m, ordering="rdr", iterations=2)
    assert t.dtype == mr.ACCESS_DTYPE
    whole = mr.analyze(m, ordering="rdr", iterations=2, granularity="element")
    assert len(t) > whole.accesses  # every load and store; the touches are a part
    elements = t["element"][t["element"] != np.iinfo(np.uint64).max]
    assert len(elements) == whole.accesses
    ours = mr.analyze(elements, granularity="element")
    assert np.array_equal(ours.histogram[0], whole.histogram[0])
    assert np.array_equal(ours.histogram[1], whole.histogram[1])
    assert ours.sum == whole.sum and ours.cold == whole.cold


@pytest.mark.parametrize("extra", [[], ["--threads", "2"], ["--granularity", "line"],
                                   ["--sample-rate", "0.25"]])
def test_analyze_ids_equals_the_u64_file(tmp_path, ids, u64file, extra):
    kw = {}
    for k, v in zip(extra[::2], extra[1::2]):
        kw[k[2:].replace("-", "_")] = v
    r = mr.analyze(ids, **kw)
    theirs = cli_csv("analyze", u64file, "--format", "u64", *extra, "--histogram-csv",
                     tmp_path / "h.csv", "--mrc-csv", tmp_path / "m.csv")
    same_cells(rows_of(r.table), theirs, skip=("input",))
    with open(tmp_path / "h.csv") as f:
        same_cells(rows_of(r.tables["histogram"]), list(csv.reader(f)), skip=("input",))
    with open(tmp_path / "m.csv") as f:
        same_cells(rows_of(r.tables["mrc"]), list(csv.reader(f)), skip=("input",))


def test_exact_histogram_adds_up(ids):
    r = mr.analyze(ids, granularity="element")
    d, c = r.histogram
    assert d.dtype == np.uint64 and c.dtype == np.uint64
    assert np.all(np.diff(d.astype(np.int64)) > 0) and np.all(c > 0)
    assert int(c.sum()) == r.accesses - r.cold
    assert sum(int(x) * int(y) for x, y in zip(d, c)) == r.sum
    assert r.cold == len(np.unique(ids)) == r.distinct
    assert r.q100 == int(d[-1])
    # A naive stack, the definition itself, on a prefix.
    stack, naive = [], {}
    for x in ids[:2000].tolist():
        if x in stack:
            k = len(stack) - 1 - stack.index(x)
            naive[k] = naive.get(k, 0) + 1
            stack.remove(x)
        stack.append(x)
    small = mr.analyze(ids[:2000], granularity="element")
    assert dict(zip(small.histogram[0].tolist(), small.histogram[1].tolist())) == naive


def test_int64_ids_read_without_copy_and_negative_refused():
    a = np.arange(1000, dtype=np.int64) % 37
    assert mr.analyze(a, granularity="element").cold == 37
    with pytest.raises(ValueError, match="value 3 is -1"):
        mr.analyze(np.array([1, 2, 3, -1, 5]))
    with pytest.raises(TypeError):
        mr.analyze(np.array([1.5, 2.0]))
    with pytest.raises(ValueError, match="2\\^64-1"):
        mr.analyze(np.array([1, (1 << 64) - 1], dtype=np.uint64))


def test_analyze_mesh_equals_the_command(tmp_path):
    m = mr.Mesh.read(NODE)
    r = mr.analyze(m, orderings=["ori", "bfs", "rdr"], iterations=2, profile=True)
    theirs = cli_csv("analyze", NODE, "--orderings", "ori,bfs,rdr", "--iterations", 2,
                     "--profile-csv", tmp_path / "p.csv")
    same_cells(rows_of(r.table), theirs)
    with open(tmp_path / "p.csv") as f:
        same_cells(rows_of(r.tables["profile"]), list(csv.reader(f)))
    assert len(r.streams) == 6  # 3 orderings x element, line
    s = r.stream(granularity="element", ordering="rdr")
    assert s.L1_misses == s.row["L1_misses"]
    with pytest.raises(AttributeError, match="6 streams"):
        r.cold


def test_chunks_summarized_and_merged(tmp_path, ids, u64file):
    for k in range(3):
        mr.summarize(u64file, (k, 3), tmp_path / f"s{k}", format="u64")
    merged = mr.merge([tmp_path / f"s{k}" for k in range(3)])
    whole = mr.analyze(ids)  # a u64 trace's values are addresses: lines, as the chunks
    assert np.array_equal(merged.histogram[1], whole.histogram[1])
    same_cells(rows_of(merged.table), rows_of(whole.table), skip=("input",))


# ---- simulation and timing ----

def test_simulate_mesh_equals_the_command():
    m = mr.Mesh.read(PLATE)
    r = mr.simulate(m, orderings=["ori", "rdr"], iterations=2)
    same_cells(rows_of(r.table), cli_csv("simulate", PLATE, "--orderings", "ori,rdr",
                                         "--iterations", 2))
    assert r.table["misses"].dtype == np.int64


def test_simulate_machine_and_addresses_equal_the_command(ids, u64file):
    m = mr.Mesh.read(PLATE)
    r = mr.simulate(m, ordering="bfs", machine="westmere-ex", threads=[1, 4],
                    placement="scatter")
    same_cells(rows_of(r.table), cli_csv("simulate", PLATE, "--orderings", "bfs", "--machine",
                                         "westmere-ex", "--threads", "1,4", "--placement",
                                         "scatter"))
    r = mr.simulate(ids * 64)
    theirs_file = u64file + ".addr"
    (ids * 64).tofile(theirs_file)
    same_cells(rows_of(r.table), cli_csv("simulate", theirs_file, "--format", "u64"),
               skip=("input",))


def test_compare_returns_the_tables():
    r = mr.compare(PLATE, orderings=["ori", "bfs"], repeat=3, max_iters=2)
    t = r.table
    assert list(t["ordering"]) == ["ori", "bfs"]
    assert np.all(t["sweeps"] == 2)
    assert "summary" in r.tables
    assert r.configuration["orderings"] == ["ori", "bfs"]


# ---- errors, signals, memory ----

def test_errors_are_the_commands():
    with pytest.raises(ValueError, match="granularity"):
        mr.analyze(NODE, granularity="bytes")
    with pytest.raises(TypeError, match="no-such-option"):
        mr.analyze(NODE, no_such_option=1)
    with pytest.raises(OSError, match="cannot open"):
        mr.analyze("/nonexistent/mesh.node")
    with pytest.raises(OSError, match="cannot open"):
        mr.Mesh.read("/nonexistent/x.msh")
    with pytest.raises(ValueError, match="is the command line's"):
        mr.analyze(NODE, csv=True)
    broken = os.path.join(DATA, "broken")
    bad = sorted(f for f in os.listdir(broken) if f.endswith(".node"))[0]
    with pytest.raises(ValueError, match=os.path.join(broken, bad[:-5])):
        mr.Mesh.read(os.path.join(broken, bad))


@pytest.mark.parametrize("threads", [1, 2])
def test_ctrl_c_stops_a_long_analysis(threads):
    if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:  # started in the background by a shell
        pytest.skip("SIGINT is ignored in this process: no Ctrl-C to test")
    ids = np.random.default_rng(3).integers(0, 1 << 22, 60_000_000, dtype=np.uint64)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        mr.analyze(ids, granularity="element", threads=threads)
    took = time.monotonic() - start
    timer.join()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # Python's, put back
    # Stopped at the next batch of 2^16 ids (about 0.04 s of work here; with threads, each
    # chunk's thread looks), long before the analysis would end (34 s on the 2-core host).
    assert took < 3, took


def test_gil_released_while_analysing():
    ids = np.random.default_rng(4).integers(0, 1 << 20, 4_000_000, dtype=np.uint64)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    mr.analyze(ids)
    done.set()
    t.join()
    assert len(ticks) > 10


def resident_kib():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") // 1024


def test_no_leak_over_a_thousand_calls():
    ids = (np.arange(5000, dtype=np.uint64) * 7) % 1000
    m = mr.Mesh.read(NODE)
    refs = sys.getrefcount(ids), sys.getrefcount(m)
    for _ in range(50):  # warm-up: allocator pools, caches
        mr.analyze(ids)
        m.points
    gc.collect()
    rss = resident_kib()
    for _ in range(1000):
        mr.analyze(ids)
        m.points, m.neighbours
        m.ordering("bfs")
    gc.collect()
    assert (sys.getrefcount(ids), sys.getrefcount(m)) == refs
    grown_kib = resident_kib() - rss
    assert grown_kib < 20 * 1024, grown_kib
