#!/usr/bin/env python3
"""Issue #12, deliverable 7: an attack harness.  Every subcommand gets hostile input by category -- numeric
options, run files, output paths, concurrent writers, signals -- and each outcome is classified:

  valid         exit 0 where success is right, and the output checked (present, no nan/inf, unchanged result)
  clean error   non-zero exit and exactly one stderr line, starting with "ERROR: "
  crash         killed by a signal, "terminate called", a sanitizer report, or an error that is not one line
  hang          no answer within the timeout
  silent wrong  exit 0 where an error was right, or wrong output

The table categories x outcomes is printed at the end; the test fails unless every crash, hang and
silent-wrong cell is 0.  Cases are tiny (T, M, points small) and random mutations use a fixed seed."""
import concurrent.futures, json, os, random, re, shutil, signal, subprocess, sys, tempfile, time

from clitest import check, cli, finish, interrupt, leftovers, wait_for_file

from hostile import OUTCOMES, TIMEOUT, classify, invoke, print_table, problems, record, table

SEED = 20261123
tmp = tempfile.mkdtemp(prefix="archipelago-hostile-")


def finite_text(text):
    return re.search(r"(?<![a-z_])(nan|inf)(?![a-z_])", text, re.IGNORECASE) is None


def folder_files(path):
    return sorted(os.listdir(path))


# ---------------------------------------------------------------------------------------------------- setup
def make_dir(name):
    d = os.path.join(tmp, name)
    os.makedirs(d, exist_ok=True)
    return d


base = make_dir("base")
RUN_PARAMS = ["--T", "3000", "--M", "8", "--subsets", "2", "--q", "4", "--longest", "5", "--seed", "3"]
run_file = os.path.join(base, "run.json")
rc, _, err = invoke(["run", *RUN_PARAMS, "--out", run_file, "--quiet"])
check(rc == 0 and os.path.exists(run_file), f"the base run file is written ({err.strip()})")
run_text = open(run_file, "rb").read()


def stats_output(path):
    rc, out, err = invoke(["stats", path])
    return rc, out.replace(path, "RUN"), err


_, stats_reference, _ = stats_output(run_file)
replay_reference_path = os.path.join(base, "replay.csv")
invoke(["replay", run_file, "--out", replay_reference_path])
replay_reference = open(replay_reference_path).read()


def subcommands():
    _, out, _ = invoke(["--help"])
    names = []
    section = False
    for line in out.splitlines():
        if line.strip().lower().startswith("subcommands"):
            section = True
            continue
        m = re.match(r"\s+([a-z][a-z0-9-]*)\s", line)
        if section and m:
            names.append(m.group(1))
    return names


def numeric_options(command):
    """{option: 'INT' | 'FLOAT' | 'TEXT'} from the command's --help (numbers and number lists only)."""
    _, out, _ = invoke([command, "--help"])
    options = {}
    for line in out.splitlines():
        m = re.match(r"\s+(?:-\w,)?(--[A-Za-z][\w-]*)\s+(INT|UINT|FLOAT|TEXT)\b", line)
        if m:
            options[m.group(1)] = "INT" if m.group(2) in ("INT", "UINT") else m.group(2)
    return options


# ------------------------------------------------------------------------------------------ numeric options
# Each command's tiny valid call; the attacked option's value replaces (or is added to) it.  TEXT options
# listed here hold numbers (lists); the others (paths, names) are attacked in their own categories.
def baseline(command, d):
    return {
        "orbit": ["orbit", "--x", "0.1", "--y", "0", "--steps", "10"],
        "run": ["run", *RUN_PARAMS, "--out", os.path.join(d, "r.json"), "--quiet", "--threads", "1"],
        "replay": ["replay", run_file, "--out", os.path.join(d, "s.csv")],
        "periodic": ["periodic", "--period", "1", "--near=-0.31,0"],
        "portrait": ["portrait", "--size", "16x16", "--points", "2000", "--orbits", "4", "--seeds", "2x2",
                     "--out", os.path.join(d, "p.png"), "--quiet"],
        "stochastic-area": ["stochastic-area", "--iterations", "20000", "--orbits", "4",
                            "--json", os.path.join(d, "a.json")],
        "markov": ["markov", "--m", "3", "--N", "100", "--csv", os.path.join(d, "m.csv")],
        "rotation": ["rotation", "--x=-0.3", "--y", "0", "--iterations", "100"],
        "indicator": ["indicator", "--kind", "dig", "--size", "4x4", "--iterations", "100",
                      "--npy", os.path.join(d, "i.npy"), "--quiet"],
        "manifold": ["manifold", "--length", "0.5", "--out", os.path.join(d, "w.csv")],
        "cantorus": ["cantorus", "--convergents", "5/31", "--out", os.path.join(d, "c.json")],
        "flux": ["flux", "--vertices", "64", "--kac-samples", "50", "--kac-zone-samples", "50", "--kac-steps", "100",
                 "--out", os.path.join(d, "f.json")],
        "atlas": ["atlas", "--depth", "0", "--scan-points", "16", "--scan-steps", "0", "--iterations", "100",
                  "--json", os.path.join(d, "at.json"), "--quiet"],
        "tail": ["tail", "--first", "16", "--t-max", "100", "--population", "4", "--replicas", "2", "--warmup", "8",
                 "--min-ancestors", "1", "--out", os.path.join(d, "t.json"), "--quiet", "--threads", "1"],
        "tail-scan": ["tail-scan", "--K", "0.1", "--first", "16", "--t-max", "100", "--population", "4", "--replicas", "2",
                      "--warmup", "8", "--min-ancestors", "1", "--dir", os.path.join(d, "ts"), "--quiet", "--threads",
                      "1"],
    }.get(command)


# The rotation profile, attacked separately (--x/--y and --line exclude each other).
PROFILE = ["rotation", "--line=-0.3,0:0.1,0", "--points", "5", "--iterations", "100", "--quiet"]


NUMBER_TEXT = {"--near", "--view", "--size", "--seeds", "--m", "--N", "--tau-max", "--radius", "--line"}
HOSTILE = ["nan", "inf", "-inf", "1e308", "-1e308", "1e300", "-1", "-5", "0", "1.5", "18446744073709551616",
           "99999999999999999999999", "", "abc", "0x10", " 1"]
# Reals are read as strtod reads them (CliCommon.hpp): "0x10" is the hexadecimal real 16, a valid spelling.
NEVER_A_NUMBER = {"nan", "inf", "-inf", "", "abc", " 1"}
NEVER_AN_INTEGER = NEVER_A_NUMBER | {"0x10", "1e308", "-1e308", "1e300", "-1", "-5", "1.5", "18446744073709551616",
                                     "99999999999999999999999"}
# Options whose 0 or other finite value may legitimately be refused or accepted: the oracle is then the output.
LONG_IF_VALID = {("portrait", "--points"), ("stochastic-area", "--iterations"), ("orbit", "--steps")}


def with_value(args, option, value):
    args = list(args)
    joined = f"{option}={value}"
    for i, a in enumerate(args):
        if a == option:
            return args[:i] + [joined] + args[i + 2:]
        if a.startswith(option + "="):
            return args[:i] + [joined] + args[i + 1:]
    return args + [joined]



def numeric_case(command, option, kind, value, index):
    d = make_dir(f"num-{command}-{index}")
    if command == "rotation" and option in ("--line", "--points", "--max-denominator"):
        args = with_value([*PROFILE, "--csv", os.path.join(d, "p.csv")], option, value)
    else:
        args = with_value(baseline(command, d), option, value)
    if kind == "INT":
        expected = True if value in NEVER_AN_INTEGER else None
    elif kind == "FLOAT":
        expected = True if value in NEVER_A_NUMBER else None
    else:
        expected = True if value in {"nan", "inf", "-inf", "", "abc"} else None
    if (command, option) in LONG_IF_VALID and value not in NEVER_AN_INTEGER and value not in ("0", "-1", "-5"):
        expected = True  # only huge or invalid values reach here: accepted, they could not finish
    rc, out, err = invoke(args)

    def ok():
        produced = [os.path.join(d, n) for n in os.listdir(d)]
        texts = [out] + [open(p, errors="replace").read() for p in produced if p.endswith((".csv", ".json"))]
        return all(finite_text(t) for t in texts) and not leftovers(d)

    outcome = classify(rc, err, expected, ok)
    if rc not in (None, 0) and outcome == "clean error" and leftovers(d):
        outcome = "silent wrong"  # an error that leaves debris behind
    return "numeric options", f"{command} {option}={value!r}", outcome, err.strip()[:200]


# ------------------------------------------------------------------------------------- presets and specs
def preset_case(args, value, expected, index):
    d = make_dir(f"preset-{index}")
    args = [a.replace("{}", value).replace("{d}", d) for a in args]
    rc, out, err = invoke(args)
    outcome = classify(rc, err, expected, lambda: finite_text(out) and not leftovers(d))
    return "presets and specs", f"{' '.join(args[:2])} {value!r}", outcome, err.strip()[:200]


def spec_file_case(name, path, index):
    """A run file's mutations (and folders, FIFOs, devices) given as a run spec: never a spec."""
    d = make_dir(f"spec-{index}")
    rc, out, err = invoke(["run", "--spec", path, "--out", os.path.join(d, "r.json"), "--quiet"])
    outcome = classify(rc, err, True, lambda: False)
    if outcome == "clean error" and os.listdir(d):
        outcome = "silent wrong"
    return "presets and specs", f"run --spec <{name}>", outcome, err.strip()[:200]


# ---------------------------------------------------------------------------------------------- run files
def run_file_variants():
    rng = random.Random(SEED)
    d = make_dir("runfiles")
    variants = []  # (name, path, may be equivalent to the original)
    for k in range(8):
        cut = rng.randrange(0, len(run_text))
        p = os.path.join(d, f"truncated-{k}.json")
        open(p, "wb").write(run_text[:cut])
        variants.append((f"truncated at {cut}", p, False))
    for k in range(10):
        data = bytearray(run_text)
        at = rng.randrange(0, len(data))
        data[at] = rng.randrange(0, 256)
        p = os.path.join(d, f"edited-{k}.json")
        open(p, "wb").write(bytes(data))
        variants.append((f"byte {at} set to {data[at]}", p, True))
    text = run_text.decode()
    for key in ['"M"', '"T"', '"seed"', '"blocksDone"']:
        m = re.search(r'\n(\s*)' + key + r': ([^,\n]+),', text)
        if not m:
            continue
        line = m.group(0)
        for dup, label in [(line + line, "same value"), (line + line.replace(m.group(2), "1", 1), "other value after"),
                           (line.replace(m.group(2), "1", 1) + line, "other value before")]:
            p = os.path.join(d, f"duplicate-{key.strip(chr(34))}-{len(variants)}.json")
            open(p, "w").write(text.replace(line, dup, 1))
            variants.append((f"duplicated key {key} ({label})", p, True))
    folder = make_dir("runfiles/a-folder.json")
    variants.append(("a folder", folder, False))
    fifo = os.path.join(d, "fifo.json")
    os.mkfifo(fifo)
    variants.append(("a FIFO", fifo, False))
    variants.append(("/dev/zero", "/dev/zero", False))
    empty = os.path.join(d, "empty.json")
    open(empty, "w").close()
    variants.append(("an empty file", empty, False))
    sparse = os.path.join(d, "sparse.json")
    with open(sparse, "wb") as f:
        f.truncate(64 << 30)  # 64 GiB of holes
    variants.append(("a 64 GiB sparse file", sparse, False))
    variants.append(("a missing file", os.path.join(d, "missing.json"), False))
    return variants


def run_file_case(command, name, path, may_be_same, index):
    d = make_dir(f"rf-{command}-{index}")
    if command == "stats":
        rc, out, err = stats_output(path)
        ok = lambda: may_be_same and out == stats_reference
    elif command == "replay":
        target = os.path.join(d, "s.csv")
        rc, out, err = invoke(["replay", path, "--out", target])
        ok = lambda: may_be_same and os.path.exists(target) and open(target).read() == replay_reference
    else:  # run --resume: the base run is finished, so a faithful copy must be refused as finished
        rc, out, err = invoke(["run", "--resume", path, "--out", os.path.join(d, "r.json"), "--quiet"])
        ok = lambda: False
    outcome = classify(rc, err, None if may_be_same else True, ok)
    if outcome == "clean error" and os.listdir(d):
        outcome = "silent wrong"
    return "run files", f"{command} <{name}>", outcome, err.strip()[:200]


# -------------------------------------------------------------------------------------------- output paths
def output_targets(d):
    """(command, args with {} for the target, what the target is: 'file' or 'folder')."""
    return [
        ("run --out", ["run", *RUN_PARAMS, "--quiet", "--out", "{}"], "file"),
        ("run --checkpoint", ["run", *RUN_PARAMS, "--quiet", "--out", os.path.join(d, "ok.json"), "--checkpoint", "{}"],
         "file"),
        ("replay --out", ["replay", run_file, "--out", "{}"], "file"),
        ("portrait --out", ["portrait", "--size", "16x16", "--points", "2000", "--orbits", "4", "--quiet", "--out", "{}"],
         "file"),
        ("portrait --npy", ["portrait", "--size", "16x16", "--points", "2000", "--orbits", "4", "--quiet", "--npy", "{}"],
         "file"),
        ("stats --csv", ["stats", run_file, "--csv", "{}"], "folder"),
        ("stochastic-area --json", ["stochastic-area", "--iterations", "20000", "--orbits", "4", "--json", "{}"], "file"),
        ("markov --csv", ["markov", "--m", "3", "--N", "100", "--csv", "{}"], "file"),
        ("rotation --csv", [*PROFILE, "--csv", "{}"], "file"),
        ("indicator --npy", ["indicator", "--size", "4x4", "--iterations", "100", "--quiet", "--npy", "{}"], "file"),
        ("indicator --out", ["indicator", "--size", "4x4", "--iterations", "100", "--quiet", "--out", "{}"], "file"),
        ("indicator --verdicts", ["indicator", "--size", "4x4", "--iterations", "100", "--quiet", "--npy",
                                  os.path.join(d, "ok.npy"), "--verdicts", "{}"], "file"),
        ("manifold --out", ["manifold", "--length", "0.5", "--out", "{}"], "file"),
        ("flux --out", ["flux", "--vertices", "64", "--out", "{}"], "file"),
    ]


def output_case(label, template, kind, attack, index):
    d = make_dir(f"out-{index}")
    if attack == "missing folder":
        target = os.path.join(d, "no-such-folder", "x.out")
    elif attack == "a folder as target":
        target = make_dir(f"out-{index}/a-folder")
    elif attack == "a file as folder":
        target = os.path.join(d, "plain-file")
        open(target, "w").write("keep")
    else:  # a 0444 file
        target = os.path.join(d, "readonly.out")
        open(target, "w").write("keep")
        os.chmod(target, 0o444)
    if kind == "file" and attack == "a file as folder":
        target = os.path.join(target, "x.out")
    if kind == "folder" and attack == "a 0444 file":
        target = os.path.join(make_dir(f"out-{index}/csv"), "summary.csv")
        open(target, "w").write("keep")
        os.chmod(target, 0o444)
        target = os.path.dirname(target)
    before = {n: open(os.path.join(d, n), "rb").read() for n in os.listdir(d) if os.path.isfile(os.path.join(d, n))}
    args = [a.replace("{}", target) for a in template]
    start = time.monotonic()
    rc, out, err = invoke(args)
    seconds = time.monotonic() - start
    outcome = classify(rc, err, True, lambda: False)
    after = {n: open(os.path.join(d, n), "rb").read() for n in os.listdir(d) if os.path.isfile(os.path.join(d, n))}
    if outcome == "clean error" and (after != before or leftovers(d)):
        outcome = "silent wrong"  # the protected file changed, or debris was left
    return "output paths", f"{label} <{attack}>", outcome, f"{err.strip()[:160]} ({seconds:.2f} s)"


# ------------------------------------------------------------------------------------ concurrency, signals
LONG_RUN = ["--T", "1000000000000", "--M", "8", "--subsets", "2", "--q", "4", "--threads", "1"]


def two_writers(shared):
    """A long run holds the lock of the shared file; a second run on it must fail at once and write nothing."""
    d = make_dir(f"two-{shared}")
    out1, ck = os.path.join(d, "one.json"), os.path.join(d, "ck.json")
    first = [cli, "run", *LONG_RUN, "--quiet", "--checkpoint-interval", "0"]
    if shared == "out":
        first += ["--out", out1]
        second = ["run", *RUN_PARAMS, "--quiet", "--out", out1]
        lock = os.path.join(d, ".one.json.lock")
    else:
        first += ["--out", out1, "--checkpoint", ck]
        second = ["run", *RUN_PARAMS, "--quiet", "--out", os.path.join(d, "two.json"), "--checkpoint", ck]
        lock = os.path.join(d, ".ck.json.lock")
    p = subprocess.Popen(first, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if not wait_for_file(lock, p):
        interrupt(p, TIMEOUT)
        return "concurrent writers", f"run, shared --{shared}", "silent wrong", "the first run took no lock"
    time.sleep(0.1)
    rc, out, err = invoke(second)
    outcome = classify(rc, err, True, lambda: False)
    if outcome == "clean error" and ("in use by another process" not in err or os.path.exists(os.path.join(d, "two.json"))):
        outcome = "silent wrong"
    interrupt(p, TIMEOUT)
    return "concurrent writers", f"run, shared --{shared}", outcome, err.strip()[:200]


def killed_and_resumed():
    """SIGKILL mid-run, stale temporaries planted beside the checkpoint, resume: the uninterrupted result, and
    no temporaries or locks left."""
    d = make_dir("kill")
    out = os.path.join(d, "killed.json")
    for T in ("400000", "4000000", "40000000"):  # killed while running: a longer run on a faster machine
        params = ["--T", T, "--M", "8", "--subsets", "2", "--q", "4", "--seed", "5", "--longest", "5"]
        p = subprocess.Popen([cli, "run", *params, "--out", out, "--quiet", "--checkpoint-interval", "0",
                              "--max-chunk", "2000", "--threads", "1"], stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
        wait_for_file(out, p)
        killed = p.poll() is None
        p.send_signal(signal.SIGKILL)
        p.wait()
        if killed:
            break
        os.remove(out)
    ref = os.path.join(d, "ref.json")
    rc, _, err = invoke(["run", *params, "--out", ref, "--quiet"], timeout=1200)
    results = []
    for name in (".killed.json.Ab12Cd", ".killed.json.zz99ZZ"):  # as a kill mid-write leaves them
        open(os.path.join(d, name), "w").write("partial")
    rc, _, err = invoke(["run", "--resume", out, "--out", out, "--quiet"], timeout=600)

    def same():
        a, b = json.load(open(ref)), json.load(open(out))
        keys = ["subsets", "longest", "orbits", "blocksDone"]
        return all(a[k] == b[k] for k in keys) and not leftovers(d)

    results.append(("signals", "run SIGKILL + resume (stale temporaries planted)",
                    classify(rc, err, False, same), f"{err.strip()[:160]} left: {leftovers(d)}"))
    # SIGINT: a clean stop, a checkpoint that resumes, nothing left behind.
    d2 = make_dir("int")
    out2 = os.path.join(d2, "int.json")
    p = subprocess.Popen([cli, "run", *LONG_RUN, "--out", out2, "--quiet", "--checkpoint-interval", "0"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wait_for_file(out2, p)
    _, err = interrupt(p, TIMEOUT)
    rc2, _, err2 = stats_output(out2)
    ok = p.returncode == 130 and rc2 == 0 and folder_files(d2) == ["int.json"]
    results.append(("signals", "run SIGINT", "valid" if ok else ("hang" if err is None else "silent wrong"),
                    f"exit {p.returncode}, left {folder_files(d2)}"))
    return results


# ------------------------------------------------------------------------------------------------------ main
started = time.monotonic()
commands = subcommands()
check(len(commands) >= 8, f"subcommands found: {commands}")
jobs = []
with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
    index = 0
    for command in commands:
        if baseline(command, tmp) is None:
            continue
        for option, kind in numeric_options(command).items():
            if kind == "TEXT" and option not in NUMBER_TEXT:
                continue
            for value in HOSTILE:
                index += 1
                jobs.append(pool.submit(numeric_case, command, option, kind, value, index))
    for name, path, same in run_file_variants():
        for command in ("stats", "replay", "run"):
            index += 1
            jobs.append(pool.submit(run_file_case, command, name, path, same, index))
        if "presets" in commands:
            index += 1
            jobs.append(pool.submit(spec_file_case, name, path, index))
    if "presets" in commands:
        for value in HOSTILE:
            index += 2
            jobs.append(pool.submit(preset_case, ["presets", "{}"], value, None if value == "" else True, index))
            jobs.append(pool.submit(preset_case, ["run", "--preset={}", "--out", "{d}/r.json", "--quiet"], value, True,
                                    index + 1))
    d = make_dir("targets")
    for label, template, kind in output_targets(d):
        for attack in ("missing folder", "a folder as target", "a 0444 file", "a file as folder"):
            if kind == "folder" and attack == "a folder as target":
                continue
            index += 1
            jobs.append(pool.submit(output_case, label, template, kind, attack, index))
    for job in jobs:
        record(*job.result())
# Timing-sensitive cases run alone, after the pool.
for shared in ("out", "checkpoint"):
    record(*two_writers(shared))
for result in killed_and_resumed():
    record(*result)

print_table(started)
if not problems:
    shutil.rmtree(tmp, ignore_errors=True)
finish()
