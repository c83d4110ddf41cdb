"""What the MPI end-to-end tests share (test_mpi.py, test_mpi_tail.py): the command line, an environment for one
node, and the checks' bookkeeping."""
import json, os, subprocess, sys, tempfile

mpiexec, mpi, cli = sys.argv[1:4]
failures = 0
tmp = tempfile.mkdtemp(prefix="archipelago-mpi-")
env = dict(os.environ, OMPI_MCA_plm_rsh_agent="false",  # one node: no ssh needed
           OMPI_MCA_btl_vader_single_copy_mechanism="none", OMPI_MCA_rmaps_base_oversubscribe="1")
VOLATILE = ("elapsedSeconds", "checksum", "kernel", "program")


def check(cond, what):
    global failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    failures += 0 if cond else 1


def finish():
    print(f"{failures} failure(s)")
    sys.exit(1 if failures else 0)


def p(name):
    return os.path.join(tmp, name)


def content(path):
    return {k: v for k, v in json.load(open(path)).items() if k not in VOLATILE}


def launcher(n, *command):
    return [mpiexec, "-n", str(n), "--oversubscribe", "--allow-run-as-root", mpi, *command]


def error_lines(r):
    return [l for l in r.stderr.splitlines() if l.startswith("ERROR: ")]
