"""A run from Python is bit-identical to `archipelago-cli run` for the same spec (histograms, segments, states)."""
import json
import math
import re
import subprocess

import numpy as np
import pytest

import archipelago as ap

SPEC = {"format": "archipelago-spec", "version": 1,
        "parameters": {"K": 0.1, "xmin": -0.8, "xmax": 0.5, "Xr": 0.02, "q": 16, "T": 3000, "M": 24,
                       "seed": 7, "subsets": 4, "longestKept": 10}}

# What depends on how and when a run was computed, not on its result.
VOLATILE = {"elapsedSeconds", "kernel", "checksum", "program", "version", "created", "timing"}


def strip(doc):
    if isinstance(doc, dict):
        return {k: strip(v) for k, v in doc.items() if k not in VOLATILE}
    if isinstance(doc, list):
        return [strip(v) for v in doc]
    return doc


def test_run_file_matches_cli(tmp_path, cli):
    spec = tmp_path / "spec.json"
    spec.write_text(json.dumps(SPEC))
    cli_out = tmp_path / "cli.json"
    subprocess.run([cli, "run", "--spec", str(spec), "--out", str(cli_out), "--quiet", "--threads", "2"],
                   check=True, timeout=600)
    # Python: another kernel, another thread count, small chunks, stopped nowhere: the result must not change.
    run = ap.start(json.dumps(SPEC))
    run.advance(threads=1, kernel="scalar", max_chunk=250)
    py_out = tmp_path / "py.json"
    run.save(py_out)
    a = json.loads(cli_out.read_text())
    b = json.loads(py_out.read_text())
    assert strip(a) == strip(b)
    # The arrays the module returns are those of the file.
    loaded = ap.load(cli_out)
    assert np.array_equal(loaded.histogram()["counts"], run.histogram()["counts"])
    assert np.array_equal(loaded.orbit_states(), run.orbit_states())
    assert np.array_equal(loaded.longest()["length_steps"], run.longest()["length_steps"])
    assert loaded.histogram()["counts"].sum() > 0


def test_keyword_arguments_equal_spec():
    a = ap.start(json.dumps(SPEC))
    b = ap.start(**SPEC["parameters"])
    assert a.parameters == b.parameters


def test_merge_of_orbit_ranges_equals_whole_run():
    p = dict(SPEC["parameters"], T=1000)
    whole = ap.start(**p)
    whole.advance(threads=2)
    left = ap.start_range(0, 10, **p)
    right = ap.start_range(10, 24, **p)
    left.advance(threads=1)
    right.advance(threads=1)
    merged = ap.merge(left, right)
    assert np.array_equal(merged.orbit_states(), whole.orbit_states())
    assert np.array_equal(merged.histogram()["counts"], whole.histogram()["counts"])
    assert np.array_equal(merged.longest()["length_steps"], whole.longest()["length_steps"])


def test_replay_reproduces_recorded_segment_exactly():
    run = ap.start(**dict(SPEC["parameters"], T=2000))
    run.advance(threads=2)
    rec = run.longest()
    seg = run.replay(0)
    assert len(seg["X"]) == rec["length_steps"][0] + 1
    assert seg["X"][0] == rec["X"][0] and seg["Y"][0] == rec["Y"][0]
    # Independent check: the replay is an orbit of N^-1 from the recorded start (module's plain orbit).
    orb = ap.orbit(0.1, -0.8, 0.5, X0=int(rec["X"][0]), Y0=int(rec["Y"][0]), steps=16, backward=True)
    # Randomization happens only between blocks, so the first block (q = 16 steps) is plain N^-1.
    assert np.array_equal(orb["X"][:17], seg["X"][:17])


def _csv_values(path):
    """quantity -> (value, error-or-lo) of a quantity,value,... CSV file; empty and "nan" cells are NaN."""
    values = {}
    for line in path.read_text().splitlines():
        if not line or line.startswith("#") or line.startswith("quantity,"):
            continue
        cells = line.split(",")
        values[cells[0]] = [float(c) if c else math.nan for c in cells[1:]]
    return values


def _same(a, b):
    return (math.isnan(a) and math.isnan(b)) or a == b


@pytest.mark.parametrize("K, dominated", [(0.3, False), (0.1, True)])
def test_D_error_is_the_supported_error_of_cli_stats(tmp_path, cli, K, dominated):
    # statistics()["D_error"] is D's error as `stats` gives it (the bootstrap over segments; NaN when the longest
    # segments dominate D), "D_error_subsets" the subsets' error of its summary.csv.  At K = 0.3 the segments are
    # short and the bootstrap error stands; at K = 0.1 (the paper's case) a few long segments carry D.
    xmin, xmax = ap.scan_box(K)
    run = ap.start(K=K, xmin=xmin, xmax=xmax, T=20000, M=16, seed=5)
    run.advance(threads=2)
    path = tmp_path / "run.json"
    run.save(path)
    subprocess.run([cli, "stats", str(path), "--csv", str(tmp_path / "csv"), "--tail-csv", str(tmp_path / "tail")],
                   check=True, timeout=1200, stdout=subprocess.DEVNULL)
    tail = _csv_values(tmp_path / "tail" / "tail_summary.csv")
    summary = _csv_values(tmp_path / "csv" / "summary.csv")
    s = run.statistics()
    assert s["D"] == summary["D"][0]
    assert s["D_dominated"] == dominated == (tail["dominated"][0] == 1)
    assert _same(s["D_error"], tail["D_bootstrap_error"][0])
    # Issue 51, item 6: summary.csv's D error is the run summary's (empty, read as NaN, when D has none); the subsets'
    # error stands in its own row under Python's name.
    assert _same(s["D_error"], summary["D"][1])
    assert s["D_error_subsets"] == summary["D_error_subsets"][0] > 0
    if dominated:
        assert math.isnan(s["D_error"])
        assert s["D_verdict"].startswith("D is dominated by its longest segments")
    else:
        assert 0 < s["D_error"] < s["D"] and s["D_verdict"] == ""
    p = ap.scan_point(run)
    assert _same(p["D_error"], s["D_error"]) and p["D_error_subsets"] == s["D_error_subsets"]


def test_spliced_statistics_are_the_cli_stats_short(tmp_path, cli):
    # Issue #26: statistics(short=…) splices a run of q = 16 with its q = 1 companion exactly as
    # `archipelago-cli stats RUN --short SHORT` does (summary.csv's D, f_t.csv's rows), from a Run or a file; the
    # series carry the statistics table's keys; without the companion the times below 10 q are marked.
    out = tmp_path / "k01.json"
    subprocess.run([cli, "run", "--preset", "k0.1-minute", "--T", "50000", "--out", str(out), "--quiet"],
                   check=True, timeout=300, stdout=subprocess.DEVNULL)
    short = tmp_path / "k01.short.json"
    assert short.exists(), "run writes the preset's companion beside the run"
    subprocess.run([cli, "stats", str(out), "--short", str(short), "--csv", str(tmp_path / "csv")],
                   check=True, timeout=1200, stdout=subprocess.DEVNULL)
    run = ap.load(out)
    spliced = run.statistics(short=short)
    for other in (run.statistics(short=str(short)), run.statistics(short=ap.load(short))):
        assert other["D"] == spliced["D"] and np.array_equal(other["C_tau"]["value"], spliced["C_tau"]["value"])
    summary = _csv_values(tmp_path / "csv" / "summary.csv")
    assert spliced["D"] == summary["D"][0]
    assert spliced["spliced_at"] >= 160 and spliced["blocks_affected_below"] == 0
    rows = [line.split(",") for line in (tmp_path / "csv" / "f_t.csv").read_text().splitlines()
            if line and not line.startswith("#")]
    assert rows[0] == ["t", "f_t", "f_t_error"]  # spliced: no time carries the blocks, no blocks_affected column
    assert [float(r[1]) for r in rows[1:]] == list(spliced["f_t"]["value"])  # the CSV's values, exactly
    alone = run.statistics()
    assert alone["blocks_affected_below"] == 160 and alone["spliced_at"] == 0
    assert alone["D"] != spliced["D"]
    assert set(spliced) >= {"f_t", "p_t", "P_t", "C_tau", "local_exponent", "S_t", "S_t_compensated", "D_t"}
    with pytest.raises(ValueError):  # not its companion: a run of q = 16 is not a q = 1 companion
        run.statistics(short=out)


def test_spliced_D_error_is_the_cli_stats_short(tmp_path, cli):
    # Issue 35: statistics(short=…)["D_error"] paired the spliced D with the bootstrap error of the run alone, while
    # `stats --short` prints the spliced D with the subsets' error of the spliced statistics.  Both now print core's
    # one run summary.  At K = 0.3 the segments are short, so the tail does not dominate and an error is given.
    xmin, xmax = ap.scan_box(0.3)
    out = tmp_path / "k03.json"
    subprocess.run([cli, "run", "--preset", "k0.1-minute", "--K", "0.3", "--xmin", repr(xmin), "--xmax", repr(xmax),
                    "--T", "20000", "--M", "32", "--out", str(out), "--quiet"],
                   check=True, timeout=600, stdout=subprocess.DEVNULL)
    short = tmp_path / "k03.short.json"
    assert short.exists()
    printed = subprocess.run([cli, "stats", str(out), "--short", str(short), "--csv", str(tmp_path / "csv")],
                             check=True, timeout=600, capture_output=True, text=True).stdout
    line = next(l for l in printed.splitlines() if l.startswith("D ") and "spliced" in l)
    value, error = (float(v) for v in re.match(r"D\s+(\S+) \+- (\S+)", line).groups())
    s = ap.load(out).statistics(short=short)
    assert not s["D_dominated"] and s["spliced_at"] > 0
    assert f"{s['D']:.6g}" == f"{value:.6g}" and f"{s['D_error']:.2g}" == f"{error:.2g}"
    assert s["D_error_source"] == "subsets" and "subsets of orbits" in line
    summary = _csv_values(tmp_path / "csv" / "summary.csv")
    assert s["D_error"] == summary["D"][1] == s["D_error_subsets"]  # the spliced statistics' subsets, exactly
    assert summary["D_error_subsets"][0] == s["D_error_subsets"]
    # The run alone keeps the bootstrap over segments, which differs from the spliced subsets' error.
    alone = ap.load(out).statistics()
    assert alone["D_error_source"] == "bootstrap" and s["D_run_error"] == alone["D_error"] != s["D_error"]
    assert s["D_run"] == alone["D"]
