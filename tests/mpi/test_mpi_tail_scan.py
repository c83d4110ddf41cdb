#!/usr/bin/env python3
"""archipelago-mpi tail-scan (issue 55): the K of a tail scan over MPI ranks.  mpirun -n 2 and 3 (more ranks than K)
write every K's tail file as archipelago-cli tail-scan does (all but timing and the kernel's name), and rank 0 prints
the same summary, byte for byte; a bad K list is one ERROR with nothing written."""
import os, subprocess

from mpitest import check, cli, content, env, error_lines, finish, launcher, p

small = ["--K", "0.1,0.15", "--t-max", "3e4", "--first", "100", "--population", "40", "--replicas", "4",
         "--min-ancestors", "4", "--threads", "1", "--quiet"]
r = subprocess.run([cli, "tail-scan", *small, "--dir", p("one"), "--quiet"], capture_output=True, text=True)
check(r.returncode == 0, "the single-process scan " + r.stderr[-300:])
r = subprocess.run([cli, "tail-scan", *small[:-1], "--dir", p("one")], capture_output=True, text=True)
summary = r.stdout
for n in (2, 3):
    folder = p(f"mpi{n}")
    r = subprocess.run(launcher(n, "tail-scan", *small[:-1], "--dir", folder), capture_output=True, text=True,
                       env=env, timeout=300)
    same = all(content(os.path.join(folder, f)) == content(os.path.join(p("one"), f))
               for f in ("tail-K0.1.json", "tail-K0.15.json"))
    check(r.returncode == 0 and same and r.stdout == summary,
          f"{n} ranks: every K's file and the summary of one process " + r.stderr.strip()[-300:])
r = subprocess.run(launcher(2, "tail-scan", "--K", "0.1,nan", *small[2:], "--dir", p("bad")), capture_output=True,
                   text=True, env=env, timeout=120)
check(r.returncode != 0 and len(error_lines(r)) == 1 and "--K: 'nan'" in error_lines(r)[0] and not os.path.exists(p("bad")),
      "a bad K list: one ERROR, nothing written " + r.stderr.strip()[-300:])
finish()
