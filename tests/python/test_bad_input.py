"""Bad input from Python: ValueError with core's (the CLI's) message, OSError for files, never a crash."""
import math
import resource
import subprocess
import sys

import numpy as np
import pytest

import archipelago as ap

NAN, INF = float("nan"), float("inf")


@pytest.mark.parametrize("kw, words", [
    (dict(K=NAN), "K = nan"),
    (dict(K=INF), "K"),
    (dict(xmin=-0.2), "xmin = -0.2 must be <"),
    (dict(xmax=-1.0), "xmax"),
    (dict(Xr=1.5), "Xr = 1.5 must lie in [0, 1)"),
    (dict(Xr=NAN), "Xr"),
    (dict(M=-1), "M = -1"),
    (dict(M=0), "M = 0"),
    (dict(M=2 ** 70), "M = "),
    (dict(q=0), "q = 0"),
    (dict(T=1.5), "T = 1.5 must be a whole number"),
    (dict(T=float("inf")), "T = inf must be a whole number"),
    (dict(subsets=100, M=10), "subsets = 100 must be ≤ M = 10"),
    (dict(bogus=1), "unknown parameter bogus"),
    (dict(xmin=-1e308, xmax=1e308), "x"),
])
def test_bad_parameters_raise_value_error(kw, words):
    with pytest.raises(ValueError, match=None) as e:
        ap.start(**kw)
    assert words in str(e.value)


# Issue #23: wrong types are TypeError (not pybind11's RuntimeError "Unable to cast"), NumPy numbers are numbers.
@pytest.mark.parametrize("kw, words", [
    (dict(T=True), "T must be a whole number"),
    (dict(K="0.1"), "K must be a real number"),
    (dict(M="4"), "M must be a whole number"),
    (dict(K=None), "K must be a real number"),
])
def test_wrong_types_raise_type_error(kw, words):
    with pytest.raises(TypeError) as e:
        ap.start(**kw)
    assert words in str(e.value)


def test_numpy_numbers_and_whole_floats_are_accepted():
    a = ap.start(M=np.int64(4), T=np.uint32(100), K=np.float32(0.125), subsets=np.int8(2))
    b = ap.start(M=4, T=1e2, K=0.125, subsets=2)
    assert a.parameters == b.parameters and a.parameters["M"] == 4 and a.parameters["T"] == 100


def test_bad_spec_text():
    with pytest.raises(ValueError):
        ap.start("{not json")
    with pytest.raises(ValueError, match="Kx"):
        ap.start('{"format": "archipelago-spec", "version": 1, "parameters": {"Kx": 1}}')


def test_bad_run_options():
    run = ap.start(T=100, M=2, subsets=1)
    with pytest.raises(ValueError, match="threads = -1"):
        run.advance(threads=-1)
    with pytest.raises(ValueError, match="threads = 100000"):
        run.advance(threads=100000)
    with pytest.raises(ValueError):
        run.advance(kernel="nonesuch")
    with pytest.raises(ValueError):
        run.advance(chunk_seconds=NAN)
    with pytest.raises((ValueError, OverflowError, TypeError)):
        run.advance(max_chunk=-5)
    run.advance()
    assert run.finished
    with pytest.raises(ValueError):
        run.replay(10 ** 6)


def test_bad_files(tmp_path):
    with pytest.raises(OSError):
        ap.load(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "archipelago-run", "version": 2')
    with pytest.raises(OSError, match="bad.json"):
        ap.load(bad)
    bad.write_bytes(b"\0\xff" * 100)
    with pytest.raises(OSError):
        ap.load(bad)
    with pytest.raises(OSError):
        ap.load(tmp_path)  # a folder
    run = ap.start(T=10, M=1, subsets=1)
    with pytest.raises(OSError):
        run.save(tmp_path / "no" / "such" / "folder" / "r.json")


def test_bad_map_and_orbit_input():
    with pytest.raises(ValueError):
        ap.coefficients(NAN, -0.8, 0.5)
    with pytest.raises(ValueError):
        ap.orbit(0.1, -0.8, 0.5, NAN, 0.0)
    with pytest.raises(ValueError):
        ap.orbit(0.1, -0.8, 0.5, X0=2 ** 52, Y0=0)
    with pytest.raises(ValueError):
        ap.orbit(0.1, -0.8, 0.5, 0.0, 0.0, steps=2 ** 40)
    with pytest.raises((ValueError, TypeError)):
        ap.orbit(0.1, -0.8, 0.5, X0=-1, Y0=0)
    with pytest.raises(ValueError):
        ap.involution(np.array([2 ** 60], dtype=np.uint64), np.array([0], dtype=np.uint64))
    with pytest.raises(ValueError):
        ap.periodic_orbit(NAN, 1, -0.3, 0.0)
    with pytest.raises(ValueError):
        ap.periodic_orbit(0.1, 0, -0.3, 0.0)
    with pytest.raises(ValueError):
        ap.periodic_orbit(0.1, 1, INF, 0.0)
    with pytest.raises(ValueError):
        ap.island_chain(0.1, np.array([NAN] * 100), np.zeros(100))
    with pytest.raises(ValueError):
        ap.portrait(mode="nonesuch")
    with pytest.raises(ValueError):
        ap.portrait(width=0)
    with pytest.raises(ValueError):
        ap.portrait(K=NAN)


def test_merge_of_misfits():
    a = ap.start_range(0, 4, M=8, T=10, subsets=1)
    b = ap.start_range(5, 8, M=8, T=10, subsets=1)
    with pytest.raises(ValueError):
        ap.merge(a, b)
    with pytest.raises(ValueError):
        ap.start_range(4, 2, M=8)


# Issue #23, finding 9: paths, arrays and sizes from Python are checked, never cut or truncated silently.
def test_paths_are_checked_Issue23(tmp_path):
    run = ap.start(T=100, M=2, subsets=1)
    run.advance()
    with pytest.raises(TypeError):
        run.save(None)  # once wrote a file named "None"
    assert not (tmp_path / "None").exists()
    with pytest.raises(ValueError, match="NUL"):
        run.save(str(tmp_path / "a\0b.json"))
    with pytest.raises(ValueError, match="NUL"):
        ap.load(str(tmp_path / "run.json") + "\0x")
    run.save(tmp_path / "run.json")  # os.PathLike
    assert ap.load(tmp_path / "run.json").finished


def test_involution_needs_integers_Issue23():
    with pytest.raises(TypeError, match="integers"):
        ap.involution(np.array([0.7]), np.array([0.2]))  # was truncated to 0 silently
    with pytest.raises(ValueError):
        ap.involution(np.array([-1]), np.array([0]))
    X, Y = ap.involution(np.array([5], dtype=np.int64), np.array([7], dtype=np.uint64))
    X2, Y2 = ap.involution(X, Y)
    assert X2[0] == 5 and Y2[0] == 7


def test_huge_requests_are_refused_before_work_Issue23():
    # In a process limited to 3 GB of address space (RLIMIT_AS, which the check reads), as on a smaller machine:
    # MemoryError naming the size at once, never an allocation that takes the machine down.  The orbit asks for the
    # longest the one table of limits allows (10^8 steps: 3.3 GB of arrays).
    code = """
import archipelago as ap, time
for name, call in [("orbit", lambda: ap.orbit(0.1, -0.8, 0.5, 0.0, 0.0, steps=10 ** 8)),
                   ("markov", lambda: ap.markov([1], 1000, tau_max=249999999))]:
    t = time.monotonic()
    try:
        call()
        print(name, "no error")
    except MemoryError as e:
        print(name, "MemoryError", round(time.monotonic() - t, 2), str(e)[:80])
"""
    limit = 3 << 30
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=1200,
                       preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (limit, limit)))
    lines = r.stdout.splitlines()
    assert len(lines) == 2 and all(" MemoryError " in line and "needs about" in line for line in lines), r.stdout + r.stderr
    assert all(float(line.split()[2]) < 1 for line in lines)
    with pytest.raises(ValueError):
        ap.periodic_orbit(0.1, 100001, 0.0, 0.0)  # beyond kMaxPeriod
