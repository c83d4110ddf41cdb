#!/usr/bin/env python3
"""Issue 36, classes 1, 2, 3, 5 and the long names of class 9: the attack harness on the outputs of every command
that writes.  Each case is classified as in test_cli_hostile.py (hostile.py: valid, clean error, crash, hang,
silent wrong) and the table categories x outcomes is printed; the test fails unless every crash, hang and
silent-wrong cell is 0.  Categories:

  devices and links  every writer's output given as a link to /dev/null, to /dev/full, to a file, a dangling link,
                     a FIFO, a link to /proc/self/fd/1 and (as root) a private device node made with mknod: written
                     through or into the file the link leads to, never renamed over (the node stays a device, the
                     link a link).  Real /dev entries are only reached through links in a private folder, so that a
                     regression replaces the link, never the device.
  full stdout        every command that prints, with stdout on /dev/full: one ERROR and a non-zero exit, not 0
  aliases            two outputs that are one file, an output that is an input, an input named twice (however the
                     paths are spelt: ./, .., a link): refused before any work, every file as it was
  all or nothing     a command's outputs on a nearly full disk (RLIMIT_FSIZE: the first output fits, a later one
                     does not): one ERROR and none of its files written
  long names         outputs whose name is 255 bytes (a file name's limit): their lock and temporary names fit"""
import hashlib, os, resource, shutil, signal, stat, subprocess, tempfile, threading, time

from clitest import check, cli, finish, leftovers
from hostile import TIMEOUT, classify, crashed, invoke, print_table, problems, record

tmp = tempfile.mkdtemp(prefix="archipelago-hostile-outputs-")
RUN_PARAMS = ["--T", "3000", "--M", "8", "--subsets", "2", "--q", "4", "--longest", "5", "--seed", "3"]
TAIL = ["tail", "--first", "150", "--t-max", "1000", "--population", "20", "--replicas", "3", "--min-ancestors", "4",
        "--threads", "1"]
PROFILE = ["rotation", "--line=-0.3,0:0.1,0", "--points", "5", "--iterations", "100", "--quiet"]
INDICATOR = ["indicator", "--size", "4x4", "--iterations", "100", "--quiet"]
PORTRAIT = ["portrait", "--size", "16x16", "--points", "2000", "--orbits", "4", "--quiet"]


def make_dir(name):
    d = os.path.join(tmp, name)
    os.makedirs(d, exist_ok=True)
    return d


def digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest() if os.path.isfile(path) else None


def snapshot(d):
    """Every entry of folder d: kind and content (links by their text, files by digest)."""
    out = {}
    for n in os.listdir(d):
        p = os.path.join(d, n)
        mode = os.lstat(p).st_mode
        out[n] = ("link", os.readlink(p)) if stat.S_ISLNK(mode) else ("file", digest(p)) if stat.S_ISREG(mode) \
            else ("dir", None) if stat.S_ISDIR(mode) else ("node", mode)
    return out


def is_char_device(path):
    try:
        return stat.S_ISCHR(os.lstat(path).st_mode)
    except OSError:
        return False


base = make_dir("base")
run_file = os.path.join(base, "run.json")
rc, _, err = invoke(["run", *RUN_PARAMS, "--out", run_file, "--quiet"])
check(rc == 0, f"the base run file is written ({err.strip()})")
part_a, part_b = os.path.join(base, "a.json"), os.path.join(base, "b.json")
invoke(["run", *RUN_PARAMS, "--orbits", "0:4", "--out", part_a, "--quiet"])
invoke(["run", *RUN_PARAMS, "--orbits", "4:8", "--out", part_b, "--quiet"])
# A run of the tail's process (the spec's defaults), for tail --compare.
brute = os.path.join(base, "brute.json")
rc, _, err = invoke(["run", "--M", "16", "--T", "20000", "--out", brute, "--quiet"], timeout=1200)
check(rc == 0, f"a brute-force run for tail --compare ({err.strip()})")


# ------------------------------------------------------------------------------------------ devices and links
def writers(d):
    """(command, args with {} for the output)."""
    return [
        ("run --out", ["run", *RUN_PARAMS, "--quiet", "--out", "{}"]),
        ("run --checkpoint", ["run", *RUN_PARAMS, "--quiet", "--out", os.path.join(d, "ok.json"), "--checkpoint", "{}"]),
        ("merge --out", ["merge", part_a, part_b, "--quiet", "--out", "{}"]),
        ("replay --out", ["replay", run_file, "--out", "{}"]),
        ("portrait --out", [*PORTRAIT, "--out", "{}"]),
        ("portrait --npy", [*PORTRAIT, "--npy", "{}"]),
        ("stochastic-area --json", ["stochastic-area", "--iterations", "20000", "--orbits", "4", "--json", "{}"]),
        ("markov --csv", ["markov", "--m", "3", "--N", "100", "--csv", "{}"]),
        ("rotation --csv", [*PROFILE, "--csv", "{}"]),
        ("indicator --npy", [*INDICATOR, "--npy", "{}"]),
        ("indicator --out", [*INDICATOR, "--out", "{}"]),
        ("indicator --verdicts", [*INDICATOR, "--npy", os.path.join(d, "ok.npy"), "--verdicts", "{}"]),
        ("manifold --out", ["manifold", "--length", "0.5", "--out", "{}"]),
        ("flux --out", ["flux", "--vertices", "64", "--out", "{}"]),
        ("tail --out", [*TAIL, "--quiet", "--out", "{}"]),
        ("tail --csv", [*TAIL, "--quiet", "--out", os.path.join(d, "t.json"), "--csv", "{}"]),
    ]


class FifoReader:
    """Reads the FIFO `path` in a thread, each writer's opening in turn, until stop()."""

    def __init__(self, path):
        self.path, self.data, self.stopping = path, b"", False
        self.thread = threading.Thread(target=self.loop, daemon=True)  # a regression leaves it blocked: never joined
        self.thread.start()

    def loop(self):
        while not self.stopping:
            with open(self.path, "rb") as f:  # waits for a writer
                self.data += f.read()

    def stop(self):
        self.stopping = True
        try:  # wake the reader blocked in open(): a writer that writes nothing
            fd = os.open(self.path, os.O_WRONLY | os.O_NONBLOCK)
            os.close(fd)
        except OSError:
            pass
        self.thread.join(5)


def attacks(d):
    """(name, output path, expected error, what the target must still be, what a success must have written) for the
    attacks this user can make; the private device nodes need root (mknod)."""
    real = make_dir(os.path.relpath(os.path.join(d, "real"), tmp))
    link = lambda n: os.path.islink(os.path.join(d, n))
    anything = lambda: True
    result = []
    os.symlink("/dev/null", os.path.join(d, "null.out"))
    result.append(("a link to /dev/null", os.path.join(d, "null.out"), False,
                   lambda: link("null.out") and is_char_device("/dev/null"), anything))
    if os.path.exists("/dev/full"):
        os.symlink("/dev/full", os.path.join(d, "full.out"))
        result.append(("a link to /dev/full", os.path.join(d, "full.out"), True,
                       lambda: link("full.out") and is_char_device("/dev/full"), anything))
    target = os.path.join(real, "target.out")
    open(target, "w").write("old")
    os.symlink("real/target.out", os.path.join(d, "file.out"))
    result.append(("a link to a file", os.path.join(d, "file.out"), False,
                   lambda: link("file.out") and os.path.isfile(target) and not leftovers(real),
                   lambda: open(target, "rb").read() not in (b"", b"old")))
    created = os.path.join(real, "created.out")
    os.symlink("real/created.out", os.path.join(d, "dangling.out"))
    result.append(("a dangling link", os.path.join(d, "dangling.out"), False,
                   lambda: link("dangling.out") and not leftovers(real),
                   lambda: os.path.isfile(created) and os.path.getsize(created) > 0))
    os.symlink("/proc/self/fd/1", os.path.join(d, "stdout.out"))
    result.append(("a link to /proc/self/fd/1", os.path.join(d, "stdout.out"), False, lambda: link("stdout.out"),
                   anything))
    os.mkfifo(os.path.join(d, "fifo.out"))
    result.append(("a FIFO", os.path.join(d, "fifo.out"), False,
                   lambda: stat.S_ISFIFO(os.lstat(os.path.join(d, "fifo.out")).st_mode), anything))
    for name, minor, error in [("null", 3, False), ("full", 7, True)]:
        node = os.path.join(d, f"private-{name}.out")
        try:
            os.mknod(node, 0o666 | stat.S_IFCHR, os.makedev(1, minor))
        except OSError:
            continue  # not root: the links above reach the same devices
        result.append((f"a private /dev/{name} node", node, error, lambda node=node: is_char_device(node), anything))
    return result


def device_cases():
    results, mknod_ok = [], None
    for index, (label, template) in enumerate(writers(tmp)):
        d = make_dir(f"dev-{index}")
        for attack, target, error, intact, wrote in attacks(d):
            mknod_ok = mknod_ok or "private" in attack
            args = [a.replace("{}", target) for a in writers(d)[index][1]]
            reader = FifoReader(target) if attack == "a FIFO" else None
            start = time.monotonic()
            rc, out, err = invoke(args, timeout=600)
            seconds = time.monotonic() - start
            if reader:
                reader.stop()
            # A run writes its checkpoint only every --checkpoint-interval: a short one may never write it.
            checkpoint = label == "run --checkpoint"
            expected = None if error and checkpoint else error
            # The tail's state path holds "old", not a tail file: refused, the file kept (issue 54, item 8).
            foreign_state = label == "tail --out" and attack == "a link to a file"
            if foreign_state:
                expected = True
            outcome = classify(rc, err, expected,
                               lambda: checkpoint or ((reader is None or len(reader.data) > 0) and wrote()))
            if outcome in ("valid", "clean error") and not intact():
                outcome = "silent wrong"  # the node, FIFO or link was replaced
            if foreign_state and outcome == "clean error" and open(os.path.join(d, "real", "target.out")).read() != "old":
                outcome = "silent wrong"  # refused, but the file it holds was replaced
            results.append(("devices and links", f"{label} <{attack}>", outcome, f"{err.strip()[:160]} ({seconds:.2f} s)"))
    if not mknod_ok:
        print("private device nodes skipped: mknod needs root (the links to /dev/null and /dev/full were tried)")
    return results


# ------------------------------------------------------------------------------------------------- full stdout
def full_stdout_cases():
    d = make_dir("stdout")
    commands = [
        ("flux --json", ["flux", "--vertices", "64", "--json"]),
        ("flux (text)", ["flux", "--vertices", "64"]),
        ("rotation --json", ["rotation", "--x=-0.3", "--y", "0", "--iterations", "1000", "--json"]),
        ("rotation (text)", ["rotation", "--x=-0.3", "--y", "0", "--iterations", "1000"]),
        ("manifold (CSV on stdout)", ["manifold", "--length", "0.5"]),
        ("tail --print-levels", ["tail", "--print-levels"]),
        ("tail (the table)", [*TAIL, "--out", os.path.join(d, "t.json")]),
        ("indicator (the summary)", [*INDICATOR, "--out", os.path.join(d, "i.png")]),
        ("portrait (the summary)", [*PORTRAIT, "--out", os.path.join(d, "p.png")]),
        ("orbit", ["orbit", "--x", "0.1", "--y", "0.05", "--steps", "50"]),
        ("stats", ["stats", run_file]),
        ("markov (CSV on stdout)", ["markov", "--m", "3", "--N", "100"]),
        ("presets", ["presets"]),
        ("run --print-spec", ["run", "--print-spec"]),
        ("--help", ["--help"]),
    ]
    results = []
    for label, args in commands:
        with open("/dev/full", "w") as full:
            try:
                r = subprocess.run([cli, *args], stdout=full, stderr=subprocess.PIPE, text=True, errors="replace",
                                   timeout=600, stdin=subprocess.DEVNULL)
                rc, err = r.returncode, r.stderr
            except subprocess.TimeoutExpired:
                rc, err = None, ""
        errors = [l for l in err.splitlines() if l.startswith("ERROR: ")]
        if rc is None:
            outcome = "hang"
        elif crashed(rc, err):
            outcome = "crash"
        elif rc == 0:
            outcome = "silent wrong"  # exit 0 having written nothing
        else:  # progress lines may precede it; the one error must say what failed
            outcome = "clean error" if len(errors) == 1 and "standard output" in errors[0] else "crash"
        results.append(("full stdout", label, outcome, err.strip()[-160:]))
    return results


# ----------------------------------------------------------------------------------------------------- aliases
def alias_cases():
    results = []
    cases = [
        # (name, files to make: name -> source path or None for "old", args with {d} for the folder)
        ("tail --out o.json --csv o.json", [*TAIL, "--quiet", "--out", "{d}/o.json", "--csv", "{d}/o.json"]),
        ("tail --out o.json --csv ./o.json (spelt otherwise)", [*TAIL, "--quiet", "--out", "{d}/o.json", "--csv",
                                                                "{d}/./sub/../o.json"]),
        ("tail --compare R --out R", [*TAIL, "--quiet", "--compare", "{d}/R.json", "--out", "{d}/R.json"]),
        ("tail --compare R --out a link to R", [*TAIL, "--quiet", "--compare", "{d}/R.json", "--out", "{d}/R-link.json"]),
        ("tail --compare R --checkpoint R", [*TAIL, "--quiet", "--compare", "{d}/R.json", "--out", "{d}/t.json",
                                             "--checkpoint", "{d}/R.json"]),
        ("tail --compare R --csv R", [*TAIL, "--quiet", "--compare", "{d}/R.json", "--out", "{d}/t.json", "--csv",
                                      "{d}/R.json"]),
        ("tail --compare R R", [*TAIL, "--quiet", "--compare", "{d}/R.json", "{d}/R.json", "--out", "{d}/t.json"]),
        ("tail --compare R link-to-R", [*TAIL, "--quiet", "--compare", "{d}/R.json", "{d}/R-link.json", "--out",
                                        "{d}/t.json"]),
        ("tail --csv c --compare-csv c", [*TAIL, "--quiet", "--compare", "{d}/R.json", "--out", "{d}/t.json", "--csv",
                                          "{d}/c.csv", "--compare-csv", "{d}/c.csv"]),
        ("indicator --npy i.npy --verdicts i.npy", [*INDICATOR, "--npy", "{d}/i.npy", "--verdicts", "{d}/i.npy"]),
        ("indicator --out i.npy --npy i.npy", [*INDICATOR, "--npy", "{d}/i.npy", "--out", "{d}/i.npy"]),
        ("indicator --out i.json --npy i.npy (the sidecar)", [*INDICATOR, "--npy", "{d}/i.npy", "--out", "{d}/i.json"]),
        ("indicator --verdicts i.json --npy i.npy (the sidecar)", [*INDICATOR, "--npy", "{d}/i.npy", "--verdicts",
                                                                   "{d}/i.json"]),
        ("portrait --out p.json --npy p.npy (the sidecar)", [*PORTRAIT, "--npy", "{d}/p.npy", "--out", "{d}/p.json"]),
        ("merge A B --out A", ["merge", "{d}/A.json", "{d}/B.json", "--out", "{d}/A.json"]),
        ("merge A A B --out M", ["merge", "{d}/A.json", "{d}/A.json", "{d}/B.json", "--out", "{d}/M.json"]),
        ("replay R --out R", ["replay", "{d}/R.json", "--out", "{d}/R.json"]),
        ("run --spec S --out S", ["run", "--spec", "{d}/S.json", "--quiet", "--out", "{d}/S.json"]),
        ("stats R R", ["stats", "{d}/R.json", "{d}/R.json"]),
    ]
    spec = '{"format": "archipelago-spec", "version": 1, "parameters": {"T": 3000, "M": 8, "q": 4, "subsets": 2}}\n'
    for index, (name, template) in enumerate(cases):
        d = make_dir(f"alias-{index}")
        os.makedirs(os.path.join(d, "sub"))
        shutil.copy(brute if name.startswith("tail") else run_file, os.path.join(d, "R.json"))
        os.symlink("R.json", os.path.join(d, "R-link.json"))
        shutil.copy(part_a, os.path.join(d, "A.json"))
        shutil.copy(part_b, os.path.join(d, "B.json"))
        open(os.path.join(d, "S.json"), "w").write(spec)
        before = snapshot(d)
        rc, out, err = invoke([a.replace("{d}", d) for a in template], timeout=1200)
        outcome = classify(rc, err, True, lambda: False)
        if outcome == "clean error" and (snapshot(d) != before or leftovers(d)):
            outcome = "silent wrong"  # refused, but a file was written or changed
        if outcome == "clean error" and "one file" not in err and "is also an input" not in err:
            outcome = "silent wrong"  # refused for another reason: the case did not test the rule
        results.append(("aliases", name, outcome, err.strip()[:200]))
    # What stays allowed: one run's state files are one file; different outputs.
    valid = [
        ("tail --out t.json --checkpoint t.json", [*TAIL, "--quiet", "--out", "{d}/t.json", "--checkpoint", "{d}/t.json"],
         ["t.json"]),
        ("run --out r.json --checkpoint ./r.json", ["run", *RUN_PARAMS, "--quiet", "--out", "{d}/r.json",
                                                    "--checkpoint", "{d}/./r.json"], ["r.json"]),
        ("indicator --npy i.npy --verdicts v.npy --out i.png", [*INDICATOR, "--npy", "{d}/i.npy", "--verdicts",
                                                                "{d}/v.npy", "--out", "{d}/i.png"],
         ["i.npy", "i.json", "v.npy", "i.png"]),
    ]
    for index, (name, template, made) in enumerate(valid):
        d = make_dir(f"alias-valid-{index}")
        rc, out, err = invoke([a.replace("{d}", d) for a in template], timeout=1200)
        outcome = classify(rc, err, False, lambda: all(os.path.getsize(os.path.join(d, n)) > 0 for n in made)
                           and not leftovers(d))
        results.append(("aliases", name + " (allowed)", outcome, err.strip()[:200]))
    return results


# ---------------------------------------------------------------------------------------------- all or nothing
def file_size_limit(limit):
    def setup():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # then a write past the limit fails with EFBIG, as ENOSPC
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return setup


def all_or_nothing_cases():
    results = []
    big = ["--size", "64x64", "--quiet"]  # the .npy: 64 x 64 x 8 bytes + its header
    commands = [
        ("indicator --out PNG --npy", ["indicator", *big, "--iterations", "200"], ["i.png", "i.npy", "i.json"]),
        ("portrait --out PNG --npy", ["portrait", *big, "--points", "20000"], ["i.png", "i.npy", "i.json"]),
    ]
    for name, args, made in commands:
        d = make_dir("whole-" + name.split()[0])
        outputs = ["--out", os.path.join(d, "i.png"), "--npy", os.path.join(d, "i.npy")]
        rc, _, err = invoke([*args, *outputs], timeout=600)  # unlimited: the sizes of the files
        sizes = {n: os.path.getsize(os.path.join(d, n)) for n in made if os.path.exists(os.path.join(d, n))}
        if rc != 0 or len(sizes) != len(made):
            results.append(("all or nothing", name + " (unlimited)", "silent wrong", err.strip()[:160]))
            continue
        for n in made:
            os.remove(os.path.join(d, n))
        limit = max(sizes["i.png"], sizes["i.json"]) + 1024  # the PNG and sidecar fit, the .npy does not
        if limit >= sizes["i.npy"]:
            print(f"{name}: skipped (the PNG, {sizes['i.png']} B, is not smaller than the .npy)")
            continue
        rc, _, err = invoke([*args, *outputs], timeout=600, preexec_fn=file_size_limit(limit))
        outcome = classify(rc, err, True, lambda: False)
        written = [n for n in os.listdir(d)]
        if outcome == "clean error" and written:
            outcome = "silent wrong"  # half the outputs, or debris
        results.append(("all or nothing", f"{name} (files <= {limit} B)", outcome, f"{err.strip()[:160]} left: {written}"))
    return results


# -------------------------------------------------------------------------------------------------- long names
def long_name_cases():
    d = make_dir("long")
    name = lambda ext: os.path.join(d, "n" * (255 - len(ext)) + ext)
    cases = [
        ("tail --out", [*TAIL, "--quiet", "--out", name(".json")], name(".json")),
        ("run --out", ["run", *RUN_PARAMS, "--quiet", "--out", name(".JSON")], name(".JSON")),
        ("indicator --out", [*INDICATOR, "--out", name(".png")], name(".png")),
        ("flux --out", ["flux", "--vertices", "64", "--out", name(".flux")], name(".flux")),
    ]
    results = []
    for label, args, path in cases:
        assert len(os.path.basename(path)) == 255
        rc, out, err = invoke(args, timeout=600)
        outcome = classify(rc, err, False, lambda: os.path.getsize(path) > 0 and not leftovers(d))
        results.append(("long names", f"{label} <a 255-byte name>", outcome, err.strip()[:160]))
    return results


# ------------------------------------------------------------------------------------------------------ main
started = time.monotonic()
for case in [*device_cases(), *full_stdout_cases(), *alias_cases(), *all_or_nothing_cases(), *long_name_cases()]:
    record(*case)
check(is_char_device("/dev/null") and is_char_device("/dev/full"), "/dev/null and /dev/full are still devices")
print_table(started)
if not problems:
    shutil.rmtree(tmp, ignore_errors=True)
finish()
