"""Issue 35: for a CLI command and its Python function, the same bad value gives the same message — core's, from
the request's validation and the one table of limits (core/limits), never a second copy in a front end."""
import json
import subprocess

import pytest

import archipelago as ap

TOO_MANY_THREADS = 257  # the table's limit is 256


def cli_error(cli, args):
    r = subprocess.run([cli, *args], capture_output=True, text=True, timeout=600)
    assert r.returncode != 0, r.stdout
    lines = [l for l in r.stderr.splitlines() if l.startswith("ERROR: ")]
    assert len(lines) == 1, r.stderr
    return lines[0][len("ERROR: "):]


def py_error(call):
    with pytest.raises(ValueError) as e:
        call()
    return str(e.value)


def test_orbit_length(cli):
    # One orbit loop, one length limit (it was 10^8 in core and the GUI, 2^28 in Python, none in the CLI).
    steps = 100_000_001
    c = cli_error(cli, ["orbit", "--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--x", "0", "--y", "0",
                        "--steps", str(steps)])
    p = py_error(lambda: ap.orbit(0.1, -0.8, 0.5, x0=0.0, y0=0.0, steps=steps))
    assert c == p == "steps = 100000001 must lie in [0, 100000000]"


def test_run_threads(cli, tmp_path):
    c = cli_error(cli, ["run", "--preset", "k0.1-minute", "--threads", str(TOO_MANY_THREADS),
                        "--out", str(tmp_path / "r.json")])
    p = py_error(lambda: ap.start(ap.presets()["k0.1-minute"]).advance(threads=TOO_MANY_THREADS))
    assert c == p == "threads = 257 must lie in [0, 256] (0: one per core)"


def test_flux_threads(cli):
    # The Kac check took 4096 threads, runs 256: one table now.
    c = cli_error(cli, ["flux", "--K", "0.1", "--kac", "--threads", str(TOO_MANY_THREADS)])
    p = py_error(lambda: ap.flux(0.1, kac=True, threads=TOO_MANY_THREADS))
    assert c == p == "threads = 257 must lie in [0, 256] (0: one per core)"


@pytest.mark.parametrize("cli_args, call, message", [
    (["--branch", "sideways"], dict(branch="sideways"), "branch 'sideways' must be stable or unstable"),
    (["--stable-from", "mirror"], dict(stable_from="mirror"), "stable_from 'mirror' must be inverse or symmetry"),
])
def test_manifold_enum_names(cli, cli_args, call, message):
    # The branch and the stable construction are parsed by core's one table of names (two if/else copies before).
    c = cli_error(cli, ["manifold", "--K", "0.1", *cli_args])
    p = py_error(lambda: ap.manifold(0.1, **call))
    assert c == p == message


@pytest.mark.parametrize("begin, end", [(4, 2), (0, 65), (3, 3)])
def test_orbit_range(cli, tmp_path, begin, end):
    # Core clamped a range beyond M silently while the CLI and Python refused it with two wordings; one rule now.
    c = cli_error(cli, ["run", "--preset", "k0.1-minute", "--M", "64", "--T", "10", "--orbits", f"{begin}:{end}",
                        "--out", str(tmp_path / "r.json")])
    p = py_error(lambda: ap.start_range(begin, end, ap.presets()["k0.1-minute"], M=64, T=10))
    assert c == p == f"orbits [{begin}, {end}) must satisfy begin < end ≤ M = 64"


def test_markov_tau_max(cli):
    # Python accepted any tau_max >= 0 and failed later with core's "tauMax" words; the CLI had a third wording.
    c = cli_error(cli, ["markov", "--m", "10", "--N", "100", "--tau-max", "999999999999"])
    p = py_error(lambda: ap.markov([10], 100, tau_max=999999999999))
    assert c == p == "tau_max = 999999999999 must lie in [0, 45454544] (5e8/(m + 1) - 1 for m = 10)"


def test_rotation_start_outside_the_box(cli):
    # The chain request's recipe (measure rules, then the start's) was written out by the CLI, Python and the GUI.
    # 0.75 is exact in binary: the CLI reads a long double and Python a double, and both print it the same.
    c = cli_error(cli, ["rotation", "--K", "0.1", "--x", "0.75", "--y", "0"])
    p = py_error(lambda: ap.rotation(0.75, 0.0, 0.1))
    assert c == p and c.startswith("the start (x, y) = (0.75, 0) must lie in the box")


def test_replay_rank(cli, tmp_path):
    # The rank of a longest segment: three wordings before (the CLI's "is out of range: the run file keeps", Python's
    # "rank out of range (longest segments kept: …)", the GUI's own bound of 10^6 while a run keeps at most 10^5).
    run = str(tmp_path / "r.json")
    made = subprocess.run([cli, "run", "--T", "3000", "--M", "8", "--subsets", "2", "--q", "4", "--longest", "5",
                           "--seed", "3", "--out", run, "--quiet"], capture_output=True, text=True, timeout=600)
    assert made.returncode == 0, made.stderr
    c = cli_error(cli, ["replay", run, "--segment", "7", "--out", str(tmp_path / "s.csv")])
    p = py_error(lambda: ap.load(run).replay(7))
    rule = "must lie in [0, 4] (a rank among the 5 longest segments the run keeps; 0 is the longest)"
    assert c == "--segment = 7 " + rule and p == "rank = 7 " + rule


def test_manifold_period_and_point(cli):
    # The manifold's period and point: the CLI checked them with its own copies ("must be in"), core with another.
    c = cli_error(cli, ["manifold", "--K", "0.1", "--period", "0"])
    p = py_error(lambda: ap.manifold(0.1, period=0))
    assert c == p == "period = 0 must lie in [1, 2000]"
    c = cli_error(cli, ["manifold", "--K", "0.1", "--point", "3"])
    p = py_error(lambda: ap.manifold(0.1, point=3))
    assert c == p == "point = 3 must lie in [0, 0] (a point of the orbit)"


def test_box_invariant_fraction(cli):
    # The visited fraction given back to compute b2 (Python) and the area (the CLI's stats --b2): core's rules.
    p = py_error(lambda: ap.box_invariant(0.1, -0.8, 0.5, 1.5, 100.0, 1.0))
    assert p == "fraction = 1.5 must lie in [0, 1] (the visited fraction stochastic_area gives)"


def test_box_cutting_the_island_warns_with_cores_words(cli, tmp_path):
    # Issue 39, deliverable 4: K = 0.3 in the paper's K = 0.1 box (-0.8, 0.5) cuts the central island.  Python warns
    # (warnings.warn, UserWarning) with the text the CLI prints after "WARNING: "; K = 0.1 does not warn.
    r = subprocess.run([cli, "run", "--K", "0.3", "--T", "100", "--M", "4", "--subsets", "4", "--quiet",
                        "--out", str(tmp_path / "k03.json")], capture_output=True, text=True, timeout=600)
    lines = [l[len("WARNING: "):] for l in r.stderr.splitlines() if l.startswith("WARNING: ")]
    assert r.returncode == 0 and len(lines) == 1, r.stderr
    with pytest.warns(UserWarning) as caught:
        ap.start(K=0.3, T=100, M=4, subsets=4)
    texts = [str(w.message) for w in caught]
    assert texts == [lines[0]], texts
    assert "central island at K = 0.3" in texts[0]
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning fails
        ap.start(K=0.1, T=100, M=4, subsets=4)


def test_each_front_end_names_its_own_setting(cli, tmp_path):
    # Issue 51: core names a setting by its role and each front end by its own name.  The same bad clone rule gives
    # the CLI's ERROR line with its flag and Python's ValueError with its keyword, in core's one wording (the tail's
    # plan, core/tail/TailPlan.hpp); and an edited run file is refused with how that front end reads it anyway.
    c = cli_error(cli, ["tail", "--clones", "magic", "--out", str(tmp_path / "t.json")])
    p = py_error(lambda: ap.tail(clones="magic", t_max=100))
    assert c == "--clones 'magic' must be perturb or metropolis", c
    assert p == "clones 'magic' must be perturb or metropolis", p
    run = ap.start(T=200, M=16)
    run.advance(threads=1)
    path = tmp_path / "run.json"
    run.save(path)
    document = json.loads(path.read_text())
    document["parameters"]["seed"] += 1  # an edit: the checksum no longer matches
    path.write_text(json.dumps(document, indent=1))
    c = cli_error(cli, ["stats", str(path)])
    assert "checksum does not match" in c and "; --allow-modified reads it anyway" in c, c
    with pytest.raises(OSError) as e:
        ap.load(path)
    assert "; allow_modified=True reads it anyway" in str(e.value) and "--" not in str(e.value), str(e.value)
    r = subprocess.run([cli, "replay", str(path), "--out", str(tmp_path / "r.csv")], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode != 0 and "--allow-modified" not in r.stderr, r.stderr  # replay has no such option
