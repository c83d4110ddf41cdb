"""archipelago-cli scan (issue #14, item 3; Karney 1983, sec. 5): a run file per K in the box of the rule
xmin = -2 sqrt(K) - 0.2, xmax = sqrt(K) + 0.2 (core/scan/ScanBox.hpp), the same file `run` makes with that spec
(byte-identical statistics), resumable after SIGKILL, summaries over K, and one ERROR line for each bad option."""
import re, csv, io, math, os, signal, subprocess, tempfile, time

from clitest import check, cli, finish, leftovers, run, wait_for_file

tmp = tempfile.mkdtemp(prefix="cli-scan-")
PARAMS = ["--T", "3000", "--M", "4", "--subsets", "2", "--seed", "7", "--threads", "1"]
STATS_FILES = ["f_t.csv", "P_t.csv", "C_tau.csv", "local_exponent.csv", "S_t.csv", "D_t.csv", "summary.csv"]


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(io.StringIO("".join(l for l in f if not l.startswith("#")))))


def stats_csv(run_file, folder):
    r = run("stats", run_file, "--csv", folder)
    assert r.returncode == 0, r.stderr
    return {name: open(os.path.join(folder, name), "rb").read() for name in sorted(os.listdir(folder))}


def box(K):  # the documented rule, computed independently
    return -2 * math.sqrt(K) - 0.2, math.sqrt(K) + 0.2


# --- a tiny scan over a range: files, boxes, summaries --------------------------------------------------------
d = os.path.join(tmp, "range")
r = run("scan", "--K", "0:0.1:0.05", "--dir", d, *PARAMS, "--quiet")
check(r.returncode == 0, f"scan --K 0:0.1:0.05 succeeds ({r.stderr.strip()[:200]})")
expected = ["K0.json", "K0.05.json", "K0.1.json", "scan_f_t.csv", "scan_local_exponent.csv",
            "scan_local_exponent.png", "scan_summary.csv"]
check(sorted(os.listdir(d)) == sorted(expected), f"a run file per K and the summaries: {sorted(os.listdir(d))}")
summary = rows(os.path.join(d, "scan_summary.csv"))
check([s["K"] for s in summary] == ["0", "0.05", "0.1"], f"the range gives K = 0, 0.05, 0.1: {[s['K'] for s in summary]}")
check(all(float(s["xmin"]) == box(float(s["K"]))[0] and float(s["xmax"]) == box(float(s["K"]))[1] for s in summary),
      "each K runs in the box of the rule -2 sqrt(K) - 0.2 ... sqrt(K) + 0.2")
check(all(s["blocks_done"] == s["T"] == "3000" and float(s["D"]) > 0 and int(s["longest_steps"]) > 0 and
          0 <= float(s["time_fraction_ge_1e4"]) <= 1 and s["b2_area"] == "" for s in summary),
      "scan_summary.csv: finished runs, D > 0, a longest segment, a time fraction in [0, 1], no b2 unless asked")
# D's error is the one `stats` gives for the same run file (the bootstrap over segments), or none where the
# longest segments dominate D; never the 16-subset error (issue #14, item 2).
for s in summary:
    st = run("stats", os.path.join(d, f"K{s['K']}.json"))
    dline = next(l for l in st.stdout.splitlines() if l.startswith("D "))
    m = re.match(r"D\s+(\S+)\s+\+-\s+(\S+)", dline)
    agrees = (m is not None and s["D_error"] != "" and f"{float(s['D_error']):.2g}" == f"{float(m.group(2)):.2g}") or \
             (m is None and "no error" in dline and s["D_error"] == "")
    check(st.returncode == 0 and agrees, f"K = {s['K']}: D_error {s['D_error']!r} is stats' ({dline.strip()[:90]})")
ft = rows(os.path.join(d, "scan_f_t.csv"))
check(sorted({f["K"] for f in ft}) == ["0", "0.05", "0.1"] and all(float(f["f_t"]) > 0 for f in ft),
      f"scan_f_t.csv holds f_t of every K in long format ({len(ft)} rows)")
q = 16  # run's default q: no --q in PARAMS
check(all(f["blocks_affected"] == ("1" if float(f["t"]) < 10 * q else "0") for f in ft)
      and any(f["blocks_affected"] == "1" for f in ft), f"scan_f_t.csv marks t < 10 q = {10 * q} as blocks of q steps")
heat = rows(os.path.join(d, "scan_local_exponent.csv"))
check(list(heat[0].keys()) == ["tau", "0", "0.05", "0.1"] and len(heat) > 20,
      f"scan_local_exponent.csv: tau by K ({len(heat)} rows, columns {list(heat[0].keys())})")
png = open(os.path.join(d, "scan_local_exponent.png"), "rb").read()
check(png[:8] == b"\x89PNG\r\n\x1a\n", "scan_local_exponent.png is a PNG")

# --- the run file of one K is what `run` makes with the same spec ---------------------------------------------
xmin, xmax = box(0.05)
ref = os.path.join(tmp, "run-0.05.json")
r = run("run", "--K", "0.05", f"--xmin={xmin!r}", f"--xmax={xmax!r}", *PARAMS, "--out", ref, "--quiet")
check(r.returncode == 0, "run with the scan's spec of K = 0.05")
a = stats_csv(ref, os.path.join(tmp, "stats-run"))
b = stats_csv(os.path.join(d, "K0.05.json"), os.path.join(tmp, "stats-scan"))
check(a == b and len(a) >= len(STATS_FILES), "stats --csv of the scan's K0.05.json and of run's file are byte-identical")

# --- a finished scan is not redone; a scan of other parameters in the same folder is refused ---------------------
before = {n: os.stat(os.path.join(d, n)).st_mtime_ns for n in ("K0.json", "K0.05.json", "K0.1.json")}
r = run("scan", "--K", "0:0.1:0.05", "--dir", d, *PARAMS, "--quiet")
after = {n: os.stat(os.path.join(d, n)).st_mtime_ns for n in before}
check(r.returncode == 0 and before == after, "rerunning a finished scan leaves its run files alone")
r = run("scan", "--K", "0.05", "--dir", d, "--T", "4000", "--M", "4", "--subsets", "2", "--seed", "7", "--quiet")
check(r.returncode != 0 and r.stderr.count("\n") == 1 and r.stderr.startswith("ERROR: ") and "other parameters" in r.stderr,
      f"a scan of other parameters over an existing run file: one ERROR line ({r.stderr.strip()})")

# --- SIGKILL mid-scan, then the same scan again: the uninterrupted result -------------------------------------
k = os.path.join(tmp, "killed")
for T in ("200000", "2000000", "20000000"):  # killed while running, whatever the machine's speed
    params = ["--T", T, "--M", "4", "--subsets", "2", "--q", "4", "--seed", "5", "--threads", "1"]
    args = ["scan", "--K", "0.1,0.2", "--dir", k, *params, "--quiet", "--checkpoint-interval", "0", "--max-chunk", "2000"]
    p = subprocess.Popen([cli, *args], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_for_file(os.path.join(k, "K0.1.json"), p)
    time.sleep(0.05)
    alive = p.poll() is None
    p.send_signal(signal.SIGKILL)
    p.wait()
    if alive:
        break
    for n in os.listdir(k):
        os.remove(os.path.join(k, n))
killed_state = sorted(n for n in os.listdir(k) if n.endswith(".json"))
check(alive and "scan_summary.csv" not in os.listdir(k), f"scan killed mid-way (T = {T}; files {killed_state})")
r = run("scan", "--K", "0.1,0.2", "--dir", k, *params, "--quiet", timeout=600)
check(r.returncode == 0 and not leftovers(k), f"the same scan again resumes and finishes ({r.stderr.strip()[:200]})")
full = os.path.join(tmp, "full")
r = run("scan", "--K", "0.1,0.2", "--dir", full, *params, "--quiet", timeout=600)
same = all(stats_csv(os.path.join(k, f), os.path.join(tmp, "sk" + f)) ==
           stats_csv(os.path.join(full, f), os.path.join(tmp, "sf" + f)) for f in ("K0.1.json", "K0.2.json"))
check(r.returncode == 0 and same, "killed + resumed scan gives the statistics of an uninterrupted one, byte for byte")
check(open(os.path.join(k, "scan_summary.csv")).read() == open(os.path.join(full, "scan_summary.csv")).read(),
      "and the same scan_summary.csv")

# --- bad options: one ERROR line each, no work ----------------------------------------------------------------
a_file = os.path.join(tmp, "a-file")
open(a_file, "w").write("x")
bad = [
    (["--K", ""], "--K"),
    (["--K", "abc"], "--K"),
    (["--K", "0.1,,0.2"], "--K"),
    (["--K", "0.1,0.1"], "twice"),
    (["--K", "-0.1"], "[0, 4]"),
    (["--K", "nan"], "--K"),
    (["--K", "5"], "[0, 4]"),
    (["--K", "0.3:0.1:0.05"], "upwards"),
    (["--K", "0.1:0.2:0"], "positive"),
    (["--K", "0.1:0.2"], "FROM:TO:STEP"),
    (["--K", "0:1:1e-9"], "10^4"),
    (["--K", "0.1", "--T", "0"], "T"),
    (["--K", "0.1", "--M=-1"], "--M"),
    (["--K", "0.1", "--xmin", "-1"], "xmin"),
    (["--K", "0.1", "--b2-iterations=-1"], "--b2-iterations"),
    (["--K", "0.1", "--checkpoint-interval=-1"], "--checkpoint-interval"),
    (["--K", "0.1", "--threads", "999"], "threads"),
    (["--K", "0.1", "--kernel", "nonsense"], "nonsense"),
    (["--K", "0.1", "--preset", "nonsense"], "preset"),
    (["--K", "0.1", "--dir", a_file], "not a folder"),
    (["--K", "0.1", "--dir", os.path.join(tmp, "no", "such")], "no"),
    ([], "--K"),
]
for args, word in bad:
    folder = [] if "--dir" in args else ["--dir", os.path.join(tmp, "bad")]
    r = run("scan", *args, *folder, "--quiet", *([] if "--T" in args else ["--T", "10", "--M", "1", "--subsets", "1"]))
    lines = r.stderr.strip().splitlines()
    check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and word in lines[0],
          f"scan {' '.join(args)}: {r.stderr.strip()[:160]}")
check(not os.path.exists(os.path.join(tmp, "bad")) or not any(n.endswith(".json") for n in os.listdir(os.path.join(tmp, "bad"))),
      "no run file written by a refused scan")
finish()
