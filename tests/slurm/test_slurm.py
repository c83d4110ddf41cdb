#!/usr/bin/env python3
"""The cluster guide (docs/cluster.md) on a real one-node Slurm (issue 31): the batch scripts of docs/cluster/,
submitted as they are (the files the page includes, never copies), give the run file of `archipelago-cli run`
with the same spec (all but timing and kernel name):
  * k01-mpi.sbatch as the MPI job (2 tasks of archipelago-mpi under srun);
  * k01-array.sbatch (2 array tasks of `archipelago-cli run --orbits`), then k01-merge.sbatch (afterok);
  * the time limit: k01-mpi.sbatch with a 1-minute limit and a run that outlasts it; Slurm's signal before the
    limit makes the run checkpoint, the script requeues the job, it resumes (--resume), and its k01.json is the
    uninterrupted run's;
  * tail-scan-array.sbatch (2 array tasks of `archipelago-cli tail-scan --task`, after the merge): every K's tail file
    and the summary's CSVs are those of the one-process `archipelago-cli tail-scan` (issue 55).
The cluster: munged, slurmctld and slurmd started here as this test's own processes, with a slurm.conf for this
host (2 CPUs) in a temporary folder (their own ports, state, spool and munge socket there), stopped by PID at the
end.  Nothing is installed here (scripts/install-deps.sh installs slurm-wlm and munge).  When Slurm is missing,
archipelago-mpi was not built, or a port is taken (a real Slurm or another run of this test), the test is skipped
(exit 77) with the reason -- or fails, when ARCHIPELAGO_REQUIRE_SLURM=1 (CI).

Slurm's own delays, and what is done about them: slurmctld checks time limits and sends the warning signal every
30 s, and a requeued job may start again only when the launch credentials of its last run have expired (cred_expire,
120 s by default).  The cluster's cred_expire is 10 s and its scheduler runs every 2 s; the time-limit job is
released from a hold 6 s before one of slurmctld's checks (seen in its log), its run sized (from the measured CPU
rate) to outlast that first signal, and once requeued its limit is raised to 10 minutes, so that its second run
goes to the end (a second stop would only add time).  The scripts stop, checkpoint, requeue and resume by
themselves."""
import ctypes, datetime, json, os, pwd, re, resource, shutil, signal, socket, subprocess, sys, tempfile, time

cli, mpi, docs = (os.path.abspath(a) if a else a for a in sys.argv[1:4])
REQUIRE = os.environ.get("ARCHIPELAGO_REQUIRE_SLURM") == "1"
PORT = int(os.environ.get("ARCHIPELAGO_SLURM_PORT", "16817"))  # slurmctld; slurmd on PORT + 1
VOLATILE = ("elapsedSeconds", "checksum", "kernel", "program")
DEADLINE = 210  # seconds for all the jobs; the whole test stays under 4 minutes
T0 = time.monotonic()
failures = 0


def now():
    return time.monotonic() - T0


def check(cond, what):
    global failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    failures += 0 if cond else 1


def skip(reason):
    if REQUIRE:
        print(f"FAIL not run: {reason} (ARCHIPELAGO_REQUIRE_SLURM=1: a skipped Slurm test is a failure)")
        sys.exit(1)
    print(f"SKIP: {reason}")
    sys.exit(77)


def tool(name):
    return shutil.which(name, path=os.environ.get("PATH", "") + ":/usr/sbin:/sbin")


# --- what the test needs, found or skipped ------------------------------------------------------------------------
tools = {n: tool(n) for n in ("munged", "slurmctld", "slurmd", "sbatch", "scontrol", "scancel", "sinfo")}
missing = [n for n, p in tools.items() if not p]
if missing:
    skip(f"no {', '.join(missing)} (Debian packages slurm-wlm and munge: bash scripts/install-deps.sh)")
if not mpi or not os.access(mpi, os.X_OK):
    skip("archipelago-mpi was not built (no MPI found by CMake: Debian libopenmpi-dev openmpi-bin)")
for port in (PORT, PORT + 1):
    with socket.socket() as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # a TIME_WAIT left by an earlier run is no owner
        try:
            s.bind(("", port))
        except OSError as e:
            skip(f"TCP port {port} is taken ({e.strerror}): a Slurm or another run of this test is using it; this "
                 f"test never touches another Slurm (another base port: ARCHIPELAGO_SLURM_PORT)")
scripts = {n: os.path.join(docs, n) for n in ("k01-mpi.sbatch", "k01-array.sbatch", "k01-merge.sbatch",
                                              "tail-scan-array.sbatch")}
page = open(os.path.join(os.path.dirname(docs), "cluster.md")).read()
check(all(f"cluster/{n}" in page for n in scripts), "docs/cluster.md includes the scripts submitted here")

tmp = tempfile.mkdtemp(prefix="archipelago-slurm-")
os.chmod(tmp, 0o755)  # munged wants its socket's folder searchable by all
user = pwd.getpwuid(os.getuid()).pw_name
host = socket.gethostname().split(".")[0]


def p(*names):
    return os.path.join(tmp, *names)


for d in ("state", "spool", "log", "mpi", "array", "timelimit", "tailscan"):
    os.mkdir(p(d))
with open(os.open(p("munge.key"), os.O_WRONLY | os.O_CREAT, 0o600), "wb") as f:
    f.write(os.urandom(1024))
# TaskPlugin task/none, ProctrackType proctrack/pgid: no cgroups needed (containers).  MpiDefault none, as
# Debian's: the script asks for PMIx itself.
open(p("slurm.conf"), "w").write(f"""\
ClusterName=archipelago-test
SlurmctldHost={host}(127.0.0.1)
SlurmctldPort={PORT}
SlurmdPort={PORT + 1}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={p("munge.socket")},cred_expire=10
SlurmUser={user}
SlurmdUser={user}
StateSaveLocation={p("state")}
SlurmdSpoolDir={p("spool")}
SlurmctldPidFile={p("slurmctld.pid")}
SlurmdPidFile={p("slurmd.pid")}
SlurmctldLogFile={p("log", "slurmctld.log")}
SlurmdLogFile={p("log", "slurmd.log")}
SlurmctldDebug=debug2
LogTimeFormat=iso8601_ms
ProctrackType=proctrack/pgid
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=2
MpiDefault=none
ReturnToService=2
MinJobAge=600
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
NodeName=localhost NodeHostname={host} NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
""")

# The jobs' environment: no variable of a Slurm job this test may itself run in; the build's tools first on PATH.
env = {k: v for k, v in os.environ.items() if not k.startswith(("SLURM_", "SBATCH_", "SALLOC_", "SRUN_"))}
env.update(SLURM_CONF=p("slurm.conf"), PATH=os.pathsep.join([os.path.dirname(cli), os.path.dirname(mpi),
                                                             env.get("PATH", "/usr/bin:/bin")]),
           OMPI_MCA_btl_vader_single_copy_mechanism="none")  # as tests/mpi: no cross-memory attach in containers

libc = ctypes.CDLL(None)


def die_with_test():
    libc.prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG: a daemon ends when this test is killed (a ctest timeout)


daemons = []  # (name, Popen), started in this order and stopped in the reverse one


def start(name, *argv):
    log = open(p("log", name + ".out"), "w")
    daemons.append((name, subprocess.Popen(list(argv), stdout=log, stderr=subprocess.STDOUT, env=env, cwd=tmp,
                                           preexec_fn=die_with_test)))


def run(*argv, cwd=None, check_ok=True):
    # A hang bound, not a speed bound (issue 36, class 10: the reference run exceeded a fixed 60 s on a busy machine
    # without IFMA): ten times what the slowest of these commands takes on the scalar kernel of a loaded machine.
    r = subprocess.run(list(argv), capture_output=True, text=True, env=env, cwd=cwd or tmp, timeout=900)
    if check_ok and r.returncode != 0:
        raise RuntimeError(f"{' '.join(argv)}: status {r.returncode}: {r.stderr.strip()}")
    return r


def show(job):
    """The records of `job` (an array: one per task) from scontrol, as dicts of their key=value fields."""
    r = run(tools["scontrol"], "show", "job", "-o", str(job), check_ok=False)
    return [dict(re.findall(r"(\w+)=(\S*)", line)) for line in r.stdout.splitlines() if "JobId=" in line]


def content(path):
    return {k: v for k, v in json.load(open(path)).items() if k not in VOLATILE}


def dump_logs():
    for root, _, files in os.walk(tmp):
        for f in sorted(files):
            if f.endswith((".out", ".log")):
                text = open(os.path.join(root, f), errors="replace").read()
                print(f"--- {os.path.relpath(os.path.join(root, f), tmp)} (last lines)\n" +
                      "\n".join(text.splitlines()[-25:]))


submitted = []
try:
    # --- the cluster ------------------------------------------------------------------------------------------------
    start("munged", tools["munged"], "--foreground", "--force", f"--socket={p('munge.socket')}",
          f"--key-file={p('munge.key')}", f"--pid-file={p('munged.pid')}", f"--seed-file={p('munged.seed')}",
          f"--log-file={p('log', 'munged.log')}")
    deadline = time.monotonic() + 10
    while not os.path.exists(p("munge.socket")) and time.monotonic() < deadline:
        time.sleep(0.05)
    ctld_started = time.time()
    start("slurmctld", tools["slurmctld"], "-D", "-i", "-f", p("slurm.conf"))
    start("slurmd", tools["slurmd"], "-D", "-f", p("slurm.conf"), "-N", "localhost")
    state, deadline = "", time.monotonic() + 30
    while state != "idle" and time.monotonic() < deadline:
        time.sleep(0.25)
        state = run(tools["sinfo"], "-h", "-N", "-o", "%T", check_ok=False).stdout.strip()
        if any(d.poll() is not None for _, d in daemons):
            break
    check(state == "idle", f"munged, slurmctld and slurmd up, the node idle ({now():.1f} s; node state '{state}', "
          f"daemons {[(n, d.pid, d.poll()) for n, d in daemons]})")
    if state != "idle":
        raise RuntimeError("no cluster")

    # --- the specs and the single-process runs they must equal --------------------------------------------------------
    # small: the MPI and array jobs (≈ 1.5 CPU-seconds here when idle).  Its reference run measures the CPU rate,
    # by which the time-limit run is sized to 30 CPU-seconds per core: it runs on every core ("threads": 0), so that
    # is ≈ 30 s of wall time at the measured rate, and it is stopped ≈ 6 s after its start (below) — at least once
    # even on a machine 4 times faster than measured (a loaded machine measures up to 2.4 times slower; 20 CPU-seconds
    # in all were too few on two cores: the run once ended before the signal).
    def spec(T):
        return {"format": "archipelago-spec", "version": 1, "kernel": "auto", "threads": 0,
                "parameters": {"K": 0.1, "xmin": -0.8, "xmax": 0.5, "Xr": 0.02, "M": 16, "q": 16, "T": T,
                               "seed": 1, "subsets": 16, "longestKept": 100}}

    def spec_steps(s):
        return s["parameters"]["M"] * s["parameters"]["q"] * s["parameters"]["T"]

    small = spec(20_000_000)
    for d in ("mpi", "array"):
        json.dump(small, open(p(d, "k01.spec.json"), "w"), indent=2)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    run(cli, "run", "--spec", p("mpi", "k01.spec.json"), "--threads", "1", "--out", p("ref-small.json"), "--quiet")
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    rate = spec_steps(small) / cpu
    # The jobs' deadline grows with this machine's time for the small run (issue 36, class 10): the MPI and array jobs
    # run it, and the scalar kernel or a loaded machine makes it several times slower than where 210 s was measured.
    DEADLINE = max(DEADLINE, 210 + 20 * cpu)
    cpu_seconds = 30 * (os.cpu_count() or 1)
    long = spec(max(1000, round(cpu_seconds * rate / (16 * 16))))
    json.dump(long, open(p("timelimit", "k01.spec.json"), "w"), indent=2)
    print(f"     the small run: {spec_steps(small):.3g} steps in {cpu:.2f} CPU-s ({rate:.3g} steps/CPU-s); the "
          f"time-limit run: {spec_steps(long):.3g} steps (≈ {cpu_seconds} CPU-s), T = {long['parameters']['T']}", flush=True)

    # --- the jobs, as docs/cluster.md submits them; sbatch's options override the scripts' cluster size --------------
    def sbatch(folder, *args):
        job = run(tools["sbatch"], "--parsable", *args, cwd=p(folder)).stdout.strip().split(";")[0]
        submitted.append(job)
        return job

    # --time=10 and more: the scripts' --signal=TERM@300 comes at slurmctld's first 30-s check after
    # now + 300 + 30 >= the job's end, i.e. at once for limits under 5.5 minutes.
    jobs = {}
    jobs["MPI job, 2 tasks"] = sbatch("mpi", "--nodes=1", "--ntasks-per-node=2", "--cpus-per-task=1", "--time=10",
                                      scripts["k01-mpi.sbatch"])
    # The time limit: --time=1, Slurm's least, and --signal=TERM@25 instead of 300, so that the signal comes at the
    # first check from 5 s after the job (or its requeued run) starts, when the run has surely started; the limit's
    # kill would come 30 s later.  Held, and released 6 s before a check: its first run is stopped ≈ 6 s in.
    jobs["time limit, 1 task"] = sbatch("timelimit", "--hold", "--nodes=1", "--ntasks-per-node=1",
                                        "--cpus-per-task=1", "--time=1", "--signal=TERM@25", scripts["k01-mpi.sbatch"])
    # The array waits (held) for the time-limit job to start, then runs beside it on the other CPU.
    jobs["array, 2 tasks"] = sbatch("array", "--hold", "--array=0-1", "--cpus-per-task=1", "--time=10",
                                    scripts["k01-array.sbatch"])
    jobs["merge (afterok)"] = sbatch("array", f"--dependency=afterok:{jobs['array, 2 tasks']}", "--time=10",
                                     scripts["k01-merge.sbatch"])
    # The tail scan over K (issue 55): two K, two tasks, after the merge; its reference is the one-process scan.
    scan_args = ["--K", "0.1,0.15", "--t-max", "3e4", "--first", "100", "--population", "40", "--replicas", "4",
                 "--min-ancestors", "4"]
    open(p("tailscan", "tail-scan.args"), "w").write(" ".join(scan_args) + "\n")
    run(cli, "tail-scan", *scan_args, "--dir", p("ref-scan"), "--csv", p("ref-scan", "tail-scan"), "--threads", "1",
        "--quiet")
    jobs["tail-scan array, 2 tasks"] = sbatch("tailscan", f"--dependency=afterok:{jobs['merge (afterok)']}",
                                              "--array=0-1", "--cpus-per-task=1", "--time=10",
                                              scripts["tail-scan-array.sbatch"])
    submitted_at = now()
    reference = subprocess.Popen([cli, "run", "--spec", p("timelimit", "k01.spec.json"), "--threads", "1",
                                  "--out", p("ref-long.json"), "--quiet"], env=env)

    def checks():
        """The wall-clock times of slurmctld's time-limit checks so far (its log at debug2)."""
        found = re.findall(r"^\[(\S+)\] debug2: Testing job time limits", open(p("log", "slurmctld.log")).read(), re.M)
        return [datetime.datetime.strptime(t, "%Y-%m-%dT%H:%M:%S.%f").timestamp() for t in found]

    # --- wait; release the held jobs; note every state seen -----------------------------------------------------------
    FINAL = {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY", "PREEMPTED", "DEADLINE",
             "BOOT_FAIL"}
    history = {}  # scontrol JobId -> [(seconds since submission, state)], the changes
    events = []
    tl_released = array_released = extended = False
    while now() < submitted_at + DEADLINE:
        records = {name: show(job) for name, job in jobs.items()}
        for r in (r for rs in records.values() for r in rs):
            h = history.setdefault(r["JobId"], [])
            if not h or h[-1][1] != r["JobState"]:
                h.append((now() - submitted_at, r["JobState"]))
        mpi_done = all(r["JobState"] in FINAL for r in records["MPI job, 2 tasks"])
        if mpi_done and not tl_released:
            seen = checks()
            next_check = (seen[-1] if seen else ctld_started) + 30
            while next_check - time.time() < 5.5:
                next_check += 30.06  # the checks' period, measured: 30 s and the loop's own time
            if next_check - time.time() <= 6.5:
                run(tools["scontrol"], "release", jobs["time limit, 1 task"])
                tl_released = True
                events.append(f"time-limit job released {next_check - time.time():.1f} s before a check, "
                              f"at {now() - submitted_at:.1f} s")
        if tl_released and not array_released and any(r["JobState"] == "RUNNING"
                                                       for r in records["time limit, 1 task"]):
            run(tools["scontrol"], "release", jobs["array, 2 tasks"])
            array_released = True
        tl = records["time limit, 1 task"]
        if tl and tl[0]["JobState"] == "PENDING" and int(tl[0].get("Restarts", 0)) > 0 and not extended:
            run(tools["scontrol"], "update", f"JobId={jobs['time limit, 1 task']}", "TimeLimit=10")
            extended = True
            events.append(f"time-limit job requeued; its limit raised to 10 minutes at {now() - submitted_at:.1f} s")
        every = [r for rs in records.values() for r in rs]
        if every and all(r["JobState"] in FINAL or r.get("Reason") == "DependencyNeverSatisfied" for r in every):
            break
        time.sleep(0.25)
    records = {name: show(job) for name, job in jobs.items()}
    reference.wait(timeout=max(1, submitted_at + DEADLINE + 60 - now()))

    print(f"     Slurm jobs (seconds from submission, as polled every 0.25 s), all done {now() - submitted_at:.1f} s "
          "after submission:")
    for name, job in jobs.items():
        for r in records[name]:
            task = f"_{r['ArrayTaskId']}" if r.get("ArrayTaskId", "N/A") != "N/A" else ""
            states = ", ".join(f"{s} {t:.1f}" for t, s in history.get(r["JobId"], []))
            print(f"     {name:20} {job}{task:3} restarts {r.get('Restarts')}, run time of its last run "
                  f"{r.get('RunTime')}: {states}")
    for e in events:
        print("     " + e)
    epoch = time.time() - now() + submitted_at
    print("     slurmctld's time-limit checks at " + ", ".join(f"{c - epoch:.1f}" for c in checks() if c >= epoch))

    every = [r for rs in records.values() for r in rs]
    check(len(every) == 7 and all(r["JobState"] == "COMPLETED" and r["ExitCode"] == "0:0" for r in every),
          "every job COMPLETED with status 0: " + ", ".join(f"{r['JobId']} {r['JobState']} {r['ExitCode']} "
                                                             f"({r.get('Reason')})" for r in every))
    ref_small = content(p("ref-small.json"))
    ok = os.path.exists(p("mpi", "k01.json")) and content(p("mpi", "k01.json")) == ref_small
    check(ok, "k01-mpi.sbatch, 2 tasks: k01.json is archipelago-cli run's file of the same spec (all but timing)")
    check(not os.path.exists(p("mpi", "k01.checkpoint")), "the finished MPI run removed its checkpoint")
    ok = os.path.exists(p("array", "k01.json")) and content(p("array", "k01.json")) == ref_small
    check(ok and all(os.path.exists(p("array", f"part-{i}.json")) for i in (0, 1)),
          "k01-array.sbatch (2 tasks) + k01-merge.sbatch: k01.json is archipelago-cli run's file of the same spec")
    merge, array = records["merge (afterok)"], records["array, 2 tasks"]
    check(merge and array and all(merge[0].get("StartTime", "") >= a.get("EndTime", "~") for a in array),
          "the merge ran after every array task ended")

    scan_files = ["tail-K0.1.json", "tail-K0.15.json"]
    same = all(os.path.exists(p("tailscan", "tail-scan", f)) and
               content(p("tailscan", "tail-scan", f)) == content(p("ref-scan", f)) for f in scan_files)
    csvs = [f"tail-scan_{n}.csv" for n in ("P", "gamma", "average")]
    same_csv = all(os.path.exists(p("tailscan", f)) and
                   open(p("tailscan", f), "rb").read() == open(p("ref-scan", f), "rb").read() for f in csvs)
    check(same and same_csv, "tail-scan-array.sbatch (2 tasks): every K's tail file and the summary's CSVs are "
          "archipelago-cli tail-scan's of the same settings")

    tl = records["time limit, 1 task"]
    restarts = int(tl[0].get("Restarts", 0)) if tl else 0
    log = open(p("timelimit", f"slurm-{jobs['time limit, 1 task']}.out"), errors="replace").read() if tl else ""
    why = " (none: the run ended before the signal, faster than the rate measured)" if restarts == 0 else ""
    check(restarts == 1 and log.count("interrupted: checkpoint written") == 1,
          f"the time-limit job was stopped by Slurm's signal, checkpointed and requeued once (restarts: {restarts}"
          f"{why})")
    check(reference.returncode == 0 and os.path.exists(p("timelimit", "k01.json")) and
          content(p("timelimit", "k01.json")) == content(p("ref-long.json")),
          "the time-limit job, resumed after its requeue: k01.json is the uninterrupted archipelago-cli run's")
except Exception as e:  # noqa: BLE001: any error is a failure, reported with the cluster's logs
    check(False, f"{type(e).__name__}: {e}")
finally:
    if failures:
        dump_logs()
    # Our jobs cancelled and ended before slurmd stops (its job steps would outlive it), then the daemons by PID.
    if submitted and tools["scancel"]:
        run(tools["scancel"], *submitted, check_ok=False)
        deadline = time.monotonic() + 30
        active = ("RUNNING", "COMPLETING", "PENDING", "CONFIGURING")
        while time.monotonic() < deadline and any(r["JobState"] in active for j in submitted for r in show(j)):
            time.sleep(0.25)
    for name, d in reversed(daemons):
        d.terminate()
        try:
            d.wait(timeout=15)
        except subprocess.TimeoutExpired:
            d.kill()
            d.wait()
    if failures:
        print(f"the cluster's folder is kept: {tmp}")
    else:
        shutil.rmtree(tmp, ignore_errors=True)

print(f"{failures} failed" if failures else "all passed", f"({now():.1f} s)")
sys.exit(1 if failures else 0)
