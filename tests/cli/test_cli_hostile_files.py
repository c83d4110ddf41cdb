#!/usr/bin/env python3
"""Issue #23, deliverable 2: the attack harness extended to the newer surfaces of files.  Each case is classified
as in test_cli_hostile.py (hostile.py: valid, clean error, crash, hang, silent wrong) and the table categories x
outcomes is printed; the test fails unless every crash, hang and silent-wrong cell is 0.  Categories:

  deep and wide JSON  every reader of the CLI (stats, stats --allow-modified, replay, run --resume, merge,
                      run --spec, a scan folder's run file) given a 60,000-level array (finding 1: SIGSEGV in
                      every reader), 33 levels, a deep known value, a million-entry array, a megabyte key, and
                      200,000 empty objects (nlohmann's quadratic callback parser)
  locale              every command's output (stdout and files) under a decimal-comma locale made with localedef
                      is byte-identical to the C locale's (finding 2)
  full disk           every writer with RLIMIT_FSIZE (writes fail with EFBIG as with ENOSPC): one ERROR, no file
                      cut short, nothing half-written left (finding 3)
  version downgrade   the checksum deleted and "version": 1 declared, with and without an edit: refused unless
                      --allow-modified, and never laundered into a checksummed file by run --resume (finding 4)
  huge counts         sizes whose work or memory cannot fit: refused before work starts (findings 6, 8)"""
import json, os, re, resource, shutil, signal, subprocess, tempfile, time

from clitest import check, cli, finish, leftovers
from hostile import classify, invoke, print_table, problems, record

tmp = tempfile.mkdtemp(prefix="archipelago-hostile-files-")
RUN_PARAMS = ["--T", "3000", "--M", "8", "--subsets", "2", "--q", "4", "--longest", "5", "--seed", "3"]


def make_dir(name):
    d = os.path.join(tmp, name)
    os.makedirs(d, exist_ok=True)
    return d


base = make_dir("base")
run_file = os.path.join(base, "run.json")
rc, _, err = invoke(["run", *RUN_PARAMS, "--out", run_file, "--quiet"])
check(rc == 0, f"the base run file is written ({err.strip()})")
run_text = open(run_file).read()
run_json = json.loads(run_text)
_, stats_reference, _ = invoke(["stats", run_file])
stats_reference = stats_reference.replace(run_file, "RUN")
# Two parts of one run, for merge.
part_a, part_b = os.path.join(base, "a.json"), os.path.join(base, "b.json")
invoke(["run", *RUN_PARAMS, "--orbits", "0:4", "--out", part_a, "--quiet"])
invoke(["run", *RUN_PARAMS, "--orbits", "4:8", "--out", part_b, "--quiet"])


def deep(n):
    return "[" * n + "]" * n


# ---------------------------------------------------------------------------------------- deep and wide JSON
def json_variants():
    """(name, run-file text, spec text): the attack in the run file (and, where it applies, in a run spec)."""
    body = run_text.rstrip()
    assert body.endswith("}")
    spec = '{"format": "archipelago-spec", "version": 1, "parameters": {"T": 3000, "M": 8}}'
    with_key = lambda value: body[:-1].rstrip() + ',\n "zzz": ' + value + "\n}\n"
    spec_key = lambda value: spec[:-1] + ', "threads": ' + value + "}"
    return [
        ("a 60,000-level array in an extra key", with_key(deep(60000)), spec_key(deep(60000))),
        ("33 levels in an extra key", with_key(deep(33)), spec_key(deep(33))),
        ("a 60,000-level value of a known key", body.replace('"blocksDone": 3000', '"blocksDone": ' + deep(60000), 1),
         spec.replace('"T": 3000', '"T": ' + deep(60000))),
        ("a million-entry array", with_key("[" + ",".join(["0"] * 1000000) + "]"),
         spec_key("[" + ",".join(["0"] * 1000000) + "]")),
        ("a megabyte key", body[:-1].rstrip() + ',\n "' + "k" * (1 << 20) + '": 0\n}\n',
         spec[:-1] + ', "' + "k" * (1 << 20) + '": 0}'),
        ("200,000 empty objects", with_key("[" + ",".join(["{}"] * 200000) + "]"),
         spec_key("[" + ",".join(["{}"] * 200000) + "]")),
        ("a repeated key 2,000 levels down", with_key(deep(2000)[:2000] + '{"a":1,"a":2}' + deep(2000)[2000:]),
         spec_key('{"a":1,"a":2}')),
    ]


def json_case(reader, name, text, spec_text, index):
    d = make_dir(f"json-{index}")
    path = os.path.join(d, "attacked.json")
    open(path, "w").write(spec_text if reader == "run --spec" else text)
    expected, ok = True, lambda: False
    if reader == "stats":
        args = ["stats", path]
    elif reader == "stats --allow-modified":
        args = ["stats", path, "--allow-modified"]
        # An extra key within the depth limit is an edit that --allow-modified may read: the statistics unchanged.
        expected = None
        ok = lambda: out.replace(path, "RUN") == stats_reference
    elif reader == "replay":
        args = ["replay", path, "--out", os.path.join(d, "s.csv")]
    elif reader == "run --resume":
        args = ["run", "--resume", path, "--out", os.path.join(d, "r.json"), "--quiet"]
    elif reader == "merge":
        args = ["merge", part_a, path, "--out", os.path.join(d, "m.json")]
    elif reader == "run --spec":
        args = ["run", "--spec", path, "--out", os.path.join(d, "r.json"), "--quiet"]
    elif reader == "tail --compare":  # the run file a tail is compared with (issue 29)
        args = ["tail", "--first", "16", "--t-max", "100", "--population", "4", "--replicas", "2", "--q", "4",
                "--compare", path, "--out", os.path.join(d, "t.json"), "--quiet"]
    elif reader == "tail --resume":  # the attacked document given as a tail file
        args = ["tail", "--resume", path, "--out", os.path.join(d, "t.json"), "--quiet"]
    else:  # a scan folder whose run file for K = 0.1 was attacked
        scan = make_dir(f"json-{index}/scan")
        shutil.copy(path, os.path.join(scan, "K0.1.json"))
        args = ["scan", "--K", "0.1", "--T", "3000", "--M", "8", "--q", "4", "--dir", scan]
    start = time.monotonic()
    rc, out, err = invoke(args, timeout=300)
    seconds = time.monotonic() - start
    outcome = classify(rc, err, expected, ok)
    if outcome == "clean error" and (len(err) > 400 or leftovers(d)):
        outcome = "silent wrong"  # a 40-KB error line, or debris
    return "deep and wide JSON", f"{reader} <{name}>", outcome, f"{err.strip()[:160]} ({seconds:.2f} s)"


# ---------------------------------------------------------------------------------------------------- locale
def locale_cases():
    """Each command under C and under de_DE.UTF-8 (made with localedef): the same bytes out."""
    locales = make_dir("locales")
    made = subprocess.run(["localedef", "-i", "de_DE", "-f", "UTF-8", os.path.join(locales, "de_DE.UTF-8")],
                          capture_output=True, text=True)
    if not os.path.isdir(os.path.join(locales, "de_DE.UTF-8")):
        return [("locale", "localedef de_DE.UTF-8", "crash", made.stderr.strip()[:160])]
    envs = {"C": dict(os.environ, LC_ALL="C"),
            "de": dict(os.environ, LOCPATH=locales, LC_ALL="de_DE.UTF-8", LANG="de_DE.UTF-8")}
    commands = {
        "orbit": lambda d: ["orbit", "--x", "0.1", "--y", "0.05", "--steps", "50"],
        "run + stats --csv": lambda d: ["stats", run_file, "--csv", os.path.join(d, "csv")],
        "portrait --npy": lambda d: ["portrait", "--size", "16x16", "--points", "20000", "--quiet",
                                     "--npy", os.path.join(d, "p.npy"), "--out", os.path.join(d, "p.png")],
        "stochastic-area --json": lambda d: ["stochastic-area", "--iterations", "20000", "--orbits", "4",
                                             "--json", os.path.join(d, "b2.json")],
        "periodic": lambda d: ["periodic", "--period", "1", "--near=-0.31,0", "--K", "0.1"],
        "markov --csv": lambda d: ["markov", "--m", "3", "--N", "100", "--csv", os.path.join(d, "m.csv")],
        "replay": lambda d: ["replay", run_file, "--out", os.path.join(d, "s.csv")],
        "scan": lambda d: ["scan", "--K", "0.1,0.2", "--T", "2000", "--M", "8", "--q", "4", "--dir",
                           os.path.join(d, "scan")],
    }
    results = []
    for name, args in commands.items():
        outputs = {}
        for loc, env in envs.items():
            d = make_dir(f"locale-{loc}-{name.split()[0]}")
            rc, out, err = invoke(args(d), env=env, timeout=600)
            files = {}
            for root, _, names in os.walk(d):
                for n in names:
                    p = os.path.join(root, n)
                    data = open(p, "rb").read().replace(d.encode(), b"D")
                    if n.endswith(".json") and b"archipelago-run" in data:  # run files: their wall time differs
                        data = re.sub(rb'"(elapsedSeconds|checksum)": [^,\n]+', b"", data)
                    files[os.path.relpath(p, d)] = data
            out = re.sub(r"(seconds|rate)=[0-9.e+-]+", r"\1=T", out.replace(d, "D"))  # wall times differ
            outputs[loc] = (rc, out, err, files)
        (rc_c, out_c, err_c, files_c), (rc_d, out_d, err_d, files_d) = outputs["C"], outputs["de"]
        if rc_d is None:
            outcome = "hang"
        elif rc_d != 0 or rc_c != 0:
            outcome = classify(rc_d, err_d, None, lambda: False)
        else:
            outcome = "valid" if (out_c == out_d and files_c == files_d) else "silent wrong"
        diff = [k for k in set(files_c) | set(files_d) if files_c.get(k) != files_d.get(k)]
        results.append(("locale", f"{name} under de_DE.UTF-8", outcome, f"{err_d.strip()[:120]} differs: {diff[:3]}"))
    return results


# ------------------------------------------------------------------------------------------------- full disk
def full_disk(limit):
    def setup():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # then a write past the limit fails with EFBIG
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return setup


def complete(path):
    data = open(path, "rb").read()
    if path.endswith(".png"):
        return data.startswith(b"\x89PNG") and data.endswith(b"IEND\xaeB`\x82")
    if path.endswith(".json"):
        try:
            json.loads(data)
            return True
        except ValueError:
            return False
    return data.endswith(b"\n")


def full_disk_case(name, args_of, limit, index):
    d = make_dir(f"full-{index}")
    env = dict(os.environ, TMPDIR=d, HOME=d)  # the run's rescue folders are on the same small disk
    rc, out, err = invoke(args_of(d), timeout=600, env=env, preexec_fn=full_disk(limit))
    # A run warns about each checkpoint it could not write and goes on: WARNING lines before the one ERROR.
    err = "\n".join(line for line in err.splitlines() if not line.startswith("WARNING: checkpoint not written"))
    outcome = classify(rc, err, True, lambda: False)
    written = [os.path.join(r, n) for r, _, ns in os.walk(d) for n in ns]
    cut = [p for p in written if not complete(p)]
    if outcome == "clean error" and (cut or leftovers(d) or "libpng" in err):
        outcome = "silent wrong"
    return "full disk", f"{name} (files ≤ {limit} B)", outcome, f"{err.strip()[:160]} cut: {cut[:2]}"


FULL_DISK = [
    ("run --out", lambda d: ["run", *RUN_PARAMS, "--quiet", "--out", os.path.join(d, "r.json")], 4096),
    ("run --out --checkpoint", lambda d: ["run", *RUN_PARAMS, "--quiet", "--out", os.path.join(d, "r.json"),
                                          "--checkpoint", os.path.join(d, "ck.json"), "--checkpoint-interval", "0"], 4096),
    ("stats --csv", lambda d: ["stats", run_file, "--csv", os.path.join(d, "csv")], 2048),
    ("replay --out", lambda d: ["replay", run_file, "--out", os.path.join(d, "s.csv")], 1024),
    ("portrait --out", lambda d: ["portrait", "--size", "64x64", "--points", "20000", "--quiet",
                                  "--out", os.path.join(d, "p.png")], 512),
    ("portrait --npy", lambda d: ["portrait", "--size", "64x64", "--points", "20000", "--quiet",
                                  "--npy", os.path.join(d, "p.npy")], 4096),
    ("stochastic-area --json", lambda d: ["stochastic-area", "--iterations", "20000", "--orbits", "4",
                                          "--json", os.path.join(d, "b2.json")], 256),
    ("markov --csv", lambda d: ["markov", "--m", "3", "--N", "100", "--csv", os.path.join(d, "m.csv")], 512),
    ("merge --out", lambda d: ["merge", part_a, part_b, "--out", os.path.join(d, "m.json")], 4096),
    ("scan --dir", lambda d: ["scan", "--K", "0.1", "--T", "2000", "--M", "8", "--q", "4", "--dir",
                              os.path.join(d, "scan")], 4096),
]


# ----------------------------------------------------------------------------------------- version downgrade
def downgraded(edit):
    j = json.loads(run_text)
    del j["checksum"]
    j["version"] = 1
    edit(j)
    return json.dumps(j, indent=1) + "\n"


def downgrade_cases():
    variants = [
        ("version 1, unedited", downgraded(lambda j: None)),
        ("version 1, seed edited", downgraded(lambda j: j["parameters"].__setitem__("seed", 4))),
        ("version 1, T edited", downgraded(lambda j: j["parameters"].__setitem__("T", 4000))),
        ("version 3", run_text.replace('"version": 2', '"version": 3')),
        ("version 0", run_text.replace('"version": 2', '"version": 0')),
        ('version "2"', run_text.replace('"version": 2', '"version": "2"')),
    ]
    results = []
    for index, (name, text) in enumerate(variants):
        d = make_dir(f"downgrade-{index}")
        path = os.path.join(d, "old.json")
        open(path, "w").write(text)
        for reader, args in [
            ("stats", ["stats", path]),
            ("replay", ["replay", path, "--out", os.path.join(d, "s.csv")]),
            ("run --resume", ["run", "--resume", path, "--out", os.path.join(d, "new.json"), "--quiet"]),
            ("merge", ["merge", path, part_b, "--out", os.path.join(d, "m.json")]),
        ]:
            rc, out, err = invoke(args)
            outcome = classify(rc, err, True, lambda: False)
            laundered = [n for n in ("new.json", "m.json", "s.csv") if os.path.exists(os.path.join(d, n))]
            if outcome == "clean error" and laundered:
                outcome = "silent wrong"
            results.append(("version downgrade", f"{reader} <{name}>", outcome, f"{err.strip()[:140]} {laundered}"))
        # Inspection on request: stats --allow-modified reads a version-1 file (with its warning), no more.
        rc, out, err = invoke(["stats", path, "--allow-modified"])
        v1 = name.startswith("version 1")
        outcome = classify(rc, err, None if v1 else True,
                           lambda: "segments" in out and "--allow-modified" in err and
                           (name != "version 1, unedited" or out.replace(path, "RUN") == stats_reference))
        if rc == 0 and outcome == "crash":  # a warning line besides the output is expected with the flag
            outcome = "valid"
        results.append(("version downgrade", f"stats --allow-modified <{name}>", outcome, err.strip()[:140]))
    return results


# ------------------------------------------------------------------------------------------------ huge counts
def huge_cases():
    # The Markov series case needs 22.9 GB, about what a 24 GB machine has free: without a limit it is refused or,
    # when the memory happens to be there, computed for minutes (the harness saw both).  Under a 4 GiB address-space
    # limit it cannot fit on any machine, so the refusal before the work is what is checked.  Under ASan (whose
    # shadow memory no address-space limit holds) that case is left out, and said so.
    under_asan = "ASAN_OPTIONS" in os.environ

    def four_gib():
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))

    d = make_dir("huge")
    spec = os.path.join(d, "huge.json")
    open(spec, "w").write('{"format": "archipelago-spec", "version": 1, "parameters": {"M": 4294967295, "T": 10}}')
    cases = [
        ("run --spec with M = 2^32 - 1", ["run", "--spec", spec, "--out", os.path.join(d, "r.json"), "--quiet"], True),
        ("run --M 2e7 (a file above the read cap)", ["run", "--M", "2e7", "--T", "10", "--out",
                                                     os.path.join(d, "r2.json"), "--quiet"], True),
        ("markov --m 1 --N 1000 --tau-max 249999999 (4 GiB address space)",
         ["markov", "--m", "1", "--N", "1000", "--tau-max", "249999999", "--csv", os.path.join(d, "m.csv")], True),
        ("portrait --size 16384x16384", ["portrait", "--size", "16384x16384", "--points", "1000", "--quiet",
                                         "--out", os.path.join(d, "p.png")], None),
    ]
    # Issue 36, class 10: the hang bound is sized on this machine, not on a fast one (a fixed 60 s failed on a busy
    # Cascade Lake without IFMA: the 16384 x 16384 portrait took longer).  The same portrait at 4096 x 4096, 1/16 of
    # its pixels, is timed first; a hang is no answer within 10 times the 16-fold of that (and never less than 60 s).
    start = time.monotonic()
    rc, _, err = invoke(["portrait", "--size", "4096x4096", "--points", "1000", "--quiet", "--out",
                         os.path.join(d, "calibration.png")], timeout=3600)
    assert rc == 0, f"the calibration portrait failed: {err.strip()[:200]}"
    hang_bound = max(60.0, 10 * 16 * (time.monotonic() - start))
    print(f"hang bound of the huge cases: {hang_bound:.0f} s (10 x 16 x the 4096^2 portrait's time here)")
    results = []
    for name, args, expected in cases:
        limited = "address space" in name
        if limited and under_asan:
            print(f"skipped under ASan: {name} (an address-space limit cannot hold ASan's shadow memory)")
            continue
        start = time.monotonic()
        rc, out, err = invoke(args, timeout=hang_bound, preexec_fn=four_gib if limited else None)
        seconds = time.monotonic() - start
        outcome = classify(rc, err, expected, lambda: True)
        if rc not in (None, 0) and outcome == "clean error" and seconds > max(20.0, hang_bound / 8):
            outcome = "silent wrong"  # refused only after the work it could not finish
        results.append(("huge counts", name, outcome, f"{err.strip()[:160]} ({seconds:.1f} s)"))
    return results


# ------------------------------------------------------------------------------------------------------ main
started = time.monotonic()
readers = ["stats", "stats --allow-modified", "replay", "run --resume", "merge", "run --spec", "scan folder",
           "tail --compare", "tail --resume"]
index = 0
for name, text, spec_text in json_variants():
    for reader in readers:
        index += 1
        record(*json_case(reader, name, text, spec_text, index))
for result in locale_cases():
    record(*result)
# libomp (clang's OpenMP runtime: the asan preset's tree) registers itself in a 1 KiB shared-memory file at its first
# parallel region; under a file-size limit below that it aborts before the program's own code runs ("OMP: Error
# #179: Can't set size of SHM").  Those cases are left out there, and said so; GCC's libgomp (the default tree) has
# no such file and runs them all.
uses_libomp = "libomp" in subprocess.run(["ldd", cli], capture_output=True, text=True).stdout
for name, args_of, limit in FULL_DISK:
    index += 1
    if uses_libomp and limit < 1024:
        print(f"skipped with libomp: {name} (files ≤ {limit} B: libomp's own 1 KiB registration file cannot be made)")
        continue
    record(*full_disk_case(name, args_of, limit, index))
for result in downgrade_cases():
    record(*result)
for result in huge_cases():
    record(*result)
print_table(started)
if not problems:
    shutil.rmtree(tmp, ignore_errors=True)
finish()
