"""report.quiet (issue 54, finding 7): a command-line run of archipelago-reproduce prints nothing on stderr, even for
a user without a login session (no XDG_RUNTIME_DIR: `nobody`, cron, a batch job), where Qt's start once printed
"QStandardPaths: XDG_RUNTIME_DIR not set, defaulting to '/tmp/runtime-…'".  Run as `nobody` when the test runs as root
(runuser), else as the user running it; the folder Qt was given is gone afterwards."""
import glob, os, shutil, subprocess, sys, tempfile

exe = os.path.abspath(sys.argv[1])
failures = 0


def check(cond, what):
    global failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    failures += 0 if cond else 1


env = {k: v for k, v in os.environ.items() if k not in ("XDG_RUNTIME_DIR", "DISPLAY", "WAYLAND_DISPLAY")}
as_nobody = os.geteuid() == 0 and shutil.which("runuser") is not None
with tempfile.TemporaryDirectory() as work:
    os.chmod(work, 0o777)
    out = os.path.join(work, "report")
    before = set(glob.glob(os.path.join(tempfile.gettempdir(), "archipelago-runtime-*")))
    command = [exe, "--only", "tmax", out]
    if as_nobody:
        command = ["runuser", "-u", "nobody", "--", "env", "-u", "XDG_RUNTIME_DIR"] + command
    r = subprocess.run(command, capture_output=True, text=True, timeout=300, env=env, cwd=work)
    who = "nobody" if as_nobody else "this user"
    check(r.returncode == 0 and "mark: agrees" in r.stdout, f"--only tmax as {who} without XDG_RUNTIME_DIR: exit 0 "
          f"({r.returncode}: {r.stdout.strip()[-200:]})")
    check(r.stderr == "", f"... and nothing on stderr ({r.stderr.strip()!r})")
    after = set(glob.glob(os.path.join(tempfile.gettempdir(), "archipelago-runtime-*")))
    check(after <= before, f"... and the runtime folder it made is removed ({sorted(after - before)})")

print("report.quiet:", "FAILED" if failures else "passed", f"({failures} failures)")
sys.exit(1 if failures else 0)
