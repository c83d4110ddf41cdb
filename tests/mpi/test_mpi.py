#!/usr/bin/env python3
"""archipelago-mpi (issue #15, item 5): mpirun -n 1, 2, 3 write the run file of the single-process run (all but
timing); a rank killed by SIGKILL mid-run aborts the job and the run resumes from the last coordinated checkpoint
on another number of ranks to the identical result; SIGINT checkpoints and stops (its parts merge whole); array-job parts
(`archipelago-cli run --orbits`) merged equal the single run too; bad inputs (a truncated or edited manifest or
part, more ranks than orbits, NaN options) are one clear ERROR with nothing written."""
import json, os, signal, subprocess, sys, tempfile, time

from mpitest import check, cli, content, env, error_lines, finish, launcher as base_launcher, p, tmp


def launcher(n):
    return base_launcher(n)


def run_mpi(n, *args, timeout=120):
    return subprocess.run(launcher(n) + list(args), capture_output=True, text=True, timeout=timeout, env=env)




small = ["--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--q", "4", "--T", "20000", "--M", "10", "--subsets", "3",
         "--longestKept", "5", "--quiet"]
r = subprocess.run([cli, "run", *small, "--threads", "2", "--out", p("single.json")], capture_output=True, text=True)
check(r.returncode == 0, "the single-process run")
for n, threads in [(1, 2), (2, 1), (3, 1)]:
    r = run_mpi(n, *small, "--threads", str(threads), "--out", p(f"mpi{n}.json"))
    check(r.returncode == 0 and content(p(f"mpi{n}.json")) == content(p("single.json")),
          f"{n} ranks x {threads} threads: the run file of the single run " + r.stderr.strip()[-300:])

# --- array-job parts merged -------------------------------------------------------------------------------------
for b, e in [(0, 4), (4, 7), (7, 10)]:
    subprocess.run([cli, "run", *small, "--orbits", f"{b}:{e}", "--out", p(f"part{b}.json")], check=True)
r = subprocess.run([cli, "merge", p("part7.json"), p("part0.json"), p("part4.json"), "--out", p("merged.json")],
                   capture_output=True, text=True)
check(r.returncode == 0 and content(p("merged.json")) == content(p("single.json")), "array-job parts merged = single run")

# --- kill a rank mid-run, resume on another number of ranks -----------------------------------------------------
big = ["--K", "0.1", "--xmin", "-0.8", "--xmax", "0.5", "--q", "4", "--T", "6000000", "--M", "12", "--subsets", "3",
       "--longestKept", "5", "--quiet"]
r = subprocess.run([cli, "run", *big, "--threads", "2", "--out", p("bigsingle.json")], capture_output=True, text=True)
check(r.returncode == 0, "the single-process run of the long spec")
os.mkdir(p("ck"))
ck = p("ck/run.ckpt")
proc = subprocess.Popen(launcher(3) + big + ["--threads", "1", "--max-chunk", "20000", "--checkpoint-interval", "0",
                                             "--out", p("big.json"), "--checkpoint", ck],
                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
deadline = time.monotonic() + 60
while not os.path.exists(ck) and proc.poll() is None and time.monotonic() < deadline:
    time.sleep(0.02)
time.sleep(0.05)


def children(parent):
    """The archipelago-mpi processes started by `parent` (mpirun forks the ranks of its own node)."""
    found = []
    for d in filter(str.isdigit, os.listdir("/proc")):
        try:
            argv0 = open(f"/proc/{d}/cmdline", "rb").read().split(b"\0")[0]
            ppid = [l for l in open(f"/proc/{d}/status") if l.startswith("PPid:")][0].split()[1]
        except (OSError, IndexError):
            continue
        if argv0.endswith(b"archipelago-mpi") and int(ppid) == parent:
            found.append(int(d))
    return sorted(found)


ranks = children(proc.pid)
check(len(ranks) == 3 and proc.poll() is None, f"3 ranks running ({ranks}), a checkpoint written")
if ranks:
    os.kill(ranks[1], signal.SIGKILL)
try:
    proc.communicate(timeout=60)
except subprocess.TimeoutExpired:
    proc.kill()
    proc.communicate()
check(proc.returncode != 0 and not os.path.exists(p("big.json")), "a rank killed: the job aborts, no run file")
done = json.load(open(ck))["blocksDone"]
check(0 < done < 6000000, f"the manifest holds a checkpoint at {done} blocks")
r = run_mpi(2, "--resume", ck, "--threads", "1", "--out", p("big.json"), "--checkpoint", ck, "--quiet")
check(r.returncode == 0 and content(p("big.json")) == content(p("bigsingle.json")),
      "resumed on 2 ranks: the run file of the single run " + r.stderr.strip()[-300:])
check(sorted(os.listdir(p("ck"))) == [], f"the finished run removed its checkpoint {os.listdir(p('ck'))}")

# --- SIGINT to mpirun: checkpoint and stop; resume on 1 rank; a cli checkpoint resumes too ----------------------
longer = [x if x != "6000000" else "1000000000" for x in big]  # never finishes here: it must be interrupted
proc = subprocess.Popen(launcher(2) + longer + ["--threads", "1", "--max-chunk", "2000", "--checkpoint-interval", "1000",
                                             "--out", p("int.json"), "--checkpoint", p("int.ckpt")],
                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                        # ctest may start tests with SIGINT ignored, which mpirun would inherit and keep
                        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
deadline = time.monotonic() + 30


def catching(pid):
    """Whether process `pid` has installed its SIGTERM handler (mpirun forwards SIGINT as SIGTERM)."""
    try:
        mask = int([l for l in open(f"/proc/{pid}/status") if l.startswith("SigCgt:")][0].split()[1], 16)
    except (OSError, IndexError):
        return False
    return bool(mask & (1 << (signal.SIGTERM - 1)))


while not (len(children(proc.pid)) == 2 and all(map(catching, children(proc.pid)))) and proc.poll() is None \
        and time.monotonic() < deadline:
    time.sleep(0.01)
time.sleep(0.1)
proc.send_signal(signal.SIGINT)
out, err = proc.communicate(timeout=60)
check(os.path.exists(p("int.ckpt")) and not os.path.exists(p("int.json")) and "interrupted" in err,
      f"SIGINT: a checkpoint written, no run file (status {proc.returncode}, {sorted(f for f in os.listdir(tmp) if f.startswith('int'))}) " + err.strip()[-300:] + " " +
      [l for l in open("/proc/self/status") if l.startswith("SigIgn")][0].strip())
if os.path.exists(p("int.ckpt")):
    m = json.load(open(p("int.ckpt")))
    parts = [p(x["file"]) for x in m["parts"]]
    r = subprocess.run([cli, "merge", *parts, "--out", p("int-merged.json")], capture_output=True, text=True)
    check(r.returncode == 0 and json.load(open(p("int-merged.json")))["blocksDone"] == m["blocksDone"] > 0,
          "the interrupted run's parts are whole and merge at the manifest's blocks " + r.stderr.strip())

# --- attacks: one ERROR, nothing written -------------------------------------------------------------------------
proc = subprocess.Popen(launcher(3) + longer + ["--threads", "1", "--max-chunk", "20000", "--checkpoint-interval", "0",
                                                "--out", p("x.json"), "--checkpoint", p("a.ckpt")],
                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
while not os.path.exists(p("a.ckpt")) and proc.poll() is None:
    time.sleep(0.02)
time.sleep(0.3)
proc.send_signal(signal.SIGINT)
proc.communicate(timeout=60)
manifest = json.load(open(p("a.ckpt")))
text = open(p("a.ckpt")).read()
first = os.path.join(tmp, manifest["parts"][0]["file"])
part_text = open(first).read()


def attack(what, args, words, n=2):
    out = p("never.json")
    r = run_mpi(n, *args, "--out", out, "--checkpoint", p("never.ckpt"))
    errors = error_lines(r)
    check(r.returncode != 0 and len(errors) == 1 and all(w in errors[0] for w in words) and not os.path.exists(out),
          f"{what}: one ERROR naming {words}: " + (errors[0] if errors else r.stderr.strip()[-300:]))


open(p("trunc.ckpt"), "w").write(text[: len(text) // 2])
attack("a truncated manifest", ["--resume", p("trunc.ckpt")], ["trunc.ckpt"])
open(p("edit.ckpt"), "w").write(text.replace(f'"blocksDone": {manifest["blocksDone"]}', '"blocksDone": 7'))
attack("a manifest with another blocksDone", ["--resume", p("edit.ckpt")], ["'blocksDone'"])
shifted = json.loads(text)
shifted["parts"][0]["orbitEnd"] += 1
open(p("shift.ckpt"), "w").write(json.dumps(shifted))
attack("a manifest with another range", ["--resume", p("shift.ckpt")], ["'orbitBegin'/'orbitEnd'"])
dropped = json.loads(text)
dropped["parts"].pop(1)
open(p("drop.ckpt"), "w").write(json.dumps(dropped))
attack("a manifest missing a part", ["--resume", p("drop.ckpt")], ["are in no file"])
escaped = json.loads(text)
escaped["parts"][0]["file"] = "../etc/passwd"
open(p("esc.ckpt"), "w").write(json.dumps(escaped))
attack("a manifest naming a file elsewhere", ["--resume", p("esc.ckpt")], ["'parts[].file'"])
open(first, "w").write(part_text.replace('"blocksDone": ', '"blocksDone": 1', 1))
attack("an edited part", ["--resume", p("a.ckpt")], [os.path.basename(first), "modified"])
open(first, "w").write(part_text[:1000])
attack("a truncated part", ["--resume", p("a.ckpt")], [os.path.basename(first)])
open(first, "w").write(part_text)
attack("more ranks than orbits", [{"10": "2", "3": "1"}.get(x, x) for x in small], ["3 ranks", "M = 2"], n=3)
attack("a NaN option", [*small, "--checkpoint-interval", "nan"], ["--checkpoint-interval"])
attack("K = NaN", [x if x != "0.1" else "nan" for x in small], ["K"])
attack("--orbits", [*small, "--orbits", "0:3"], ["--orbits"])
attack("--seeds", [*small, "--seeds", "1..2"], ["--seed"])
r = subprocess.run([cli, "merge", *[p(x["file"]) for x in manifest["parts"]], "--out", p("a.json")],
                   capture_output=True, text=True)
check(r.returncode == 0 and json.load(open(p("a.json")))["blocksDone"] == manifest["blocksDone"],
      "the attacked checkpoint, restored, is whole again " + r.stderr.strip())
finish()
