#!/usr/bin/env python3
"""archipelago-mpi tail (issue #29): the sampler's replicas over MPI ranks.  mpirun -n 1, 2, 3 write the tail file of
the single-process run (all but timing and the kernel's name); SIGINT stops every rank with its slice written, and
--resume on the same number of ranks finishes to the identical result; bad inputs (more ranks than replicas, a
resume on another number of ranks, a slice file edited) are one clear ERROR with no tail file written."""
import json, os, signal, subprocess, sys, tempfile, time

from mpitest import check, cli, content, env, error_lines, finish, launcher as base_launcher, p, tmp


def launcher(n):
    return base_launcher(n, "tail")


def run_mpi(n, *args, timeout=180):
    return subprocess.run(launcher(n) + list(args), capture_output=True, text=True, timeout=timeout, env=env)




small = ["--K", "0.1", "--population", "60", "--replicas", "5", "--t-max", "1e5", "--threads", "1", "--quiet"]
r = subprocess.run([cli, "tail", *small, "--out", p("single.json")], capture_output=True, text=True)
check(r.returncode == 0, "the single-process sampler run " + r.stderr[-300:])
for n in (1, 2, 3):
    r = run_mpi(n, *small, "--out", p(f"mpi{n}.json"))
    leftovers = [f for f in os.listdir(tmp) if ".slice-" in f]
    check(r.returncode == 0 and content(p(f"mpi{n}.json")) == content(p("single.json")) and not leftovers,
          f"{n} ranks: the tail file of the single run, slice files removed {leftovers} " + r.stderr.strip()[-300:])

# --- SIGINT: every rank writes its slice; resume on the same ranks finishes to the same file ----------------------
longer = ["--K", "0.1", "--population", "300", "--replicas", "3", "--t-max", "3e7", "--threads", "1", "--quiet",
          "--checkpoint-interval", "0"]
r = subprocess.run([cli, "tail", *longer, "--out", p("long-single.json")], capture_output=True, text=True, timeout=600)
check(r.returncode == 0, "the single-process run of the longer sampler " + r.stderr[-300:])
proc = subprocess.Popen(launcher(3) + longer + ["--out", p("long.json")], stdout=subprocess.PIPE,
                        stderr=subprocess.PIPE, text=True, env=env,
                        # ctest may start tests with SIGINT ignored, which mpirun would inherit and keep
                        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
slices = [p(f"long.slice-{r}-of-3.json") for r in range(3)]
deadline = time.monotonic() + 60
while not all(map(os.path.exists, slices)) and proc.poll() is None and time.monotonic() < deadline:
    time.sleep(0.01)
proc.send_signal(signal.SIGINT)
out, err = proc.communicate(timeout=120)
if proc.returncode == 0:
    print("note: the run finished before SIGINT arrived; the interruption was not exercised")
else:
    check(proc.returncode != 0 and all(map(os.path.exists, slices)) and not os.path.exists(p("long.json"))
          and "interrupted" in err, f"SIGINT: each rank's slice written, no tail file (status {proc.returncode}) "
          + err.strip()[-300:])
    r = run_mpi(2, "--resume", p("long.json"), "--threads", "1", "--quiet", "--out", p("long.json"))
    check(r.returncode != 0 and len(error_lines(r)) == 1 and "number of ranks" in error_lines(r)[0]
          and not os.path.exists(p("long.json")), "resume on another number of ranks: one ERROR " + r.stderr[-300:])
    r = run_mpi(3, "--resume", p("long.json"), "--threads", "1", "--quiet", "--out", p("long.json"), timeout=600)
    check(r.returncode == 0 and content(p("long.json")) == content(p("long-single.json"))
          and not any(map(os.path.exists, slices)),
          "resumed on 3 ranks: the tail file of the single run, slices removed " + r.stderr.strip()[-300:])

# --- attacks: one ERROR, no tail file ---------------------------------------------------------------------------
r = run_mpi(3, "--K", "0.1", "--replicas", "2", "--t-max", "1e4", "--out", p("x.json"))
check(r.returncode != 0 and len(error_lines(r)) == 1 and "at most 2" in error_lines(r)[0] and not os.path.exists(p("x.json")),
      "3 ranks for 2 replicas: one ERROR " + r.stderr[-300:])
r = run_mpi(2, "--K", "nan", "--out", p("x.json"))
check(r.returncode != 0 and len(error_lines(r)) == 1 and not os.path.exists(p("x.json")), "--K nan: one ERROR " + r.stderr[-300:])
# `archipelago-cli tail --slice i/2` writes what rank i of 2 would: resumed there, the finished slices merge.
for i in range(2):
    subprocess.run([cli, "tail", *small, "--slice", f"{i}/2", "--out", p(f"e.slice-{i}-of-2.json")], check=True)
saved = {i: open(p(f"e.slice-{i}-of-2.json")).read() for i in range(2)}
r = run_mpi(2, "--resume", p("e.json"), "--quiet", "--out", p("e.json"))
check(r.returncode == 0 and content(p("e.json")) == content(p("single.json")),
      "the CLI's slices resumed on 2 ranks: merged, the single run " + r.stderr[-300:])
os.remove(p("e.json"))
for i in range(2):
    open(p(f"e.slice-{i}-of-2.json"), "w").write(saved[i])
edited = p("e.slice-1-of-2.json")
open(edited, "w").write(saved[1].replace('"trials": ', '"trials": 1', 1))
r = run_mpi(2, "--resume", p("e.json"), "--out", p("e.json"))
check(r.returncode != 0 and len(error_lines(r)) == 1 and "rank 1" in error_lines(r)[0] and not os.path.exists(p("e.json")),
      "an edited slice file: one ERROR naming its rank " + r.stderr[-300:])

finish()
