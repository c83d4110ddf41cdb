"""What the attack harnesses share (test_cli_hostile.py, issue #12; test_cli_hostile_files.py, issue #23): running
the tool, classifying each outcome, and the table of categories x outcomes:

  valid         exit 0 where success is right, and the output checked (present, no nan/inf, unchanged result)
  clean error   non-zero exit and exactly one stderr line, starting with "ERROR: "
  crash         killed by a signal, "terminate called", a sanitizer report, or an error that is not one line
  hang          no answer within the timeout
  silent wrong  exit 0 where an error was right, or wrong output

A harness fails unless every crash, hang and silent-wrong cell is 0."""
import subprocess, time

from clitest import check, cli

TIMEOUT = 200  # a hang bound, ten times the slowest case on a loaded machine (issue 36, class 10)
OUTCOMES = ["clean error", "valid", "crash", "hang", "silent wrong"]
table = {}
problems = []


def invoke(args, timeout=TIMEOUT, env=None, preexec_fn=None):
    """(returncode or None on timeout, stdout, stderr)."""
    try:
        r = subprocess.run([cli, *args], capture_output=True, text=True, errors="replace", timeout=timeout,
                           stdin=subprocess.DEVNULL, env=env, preexec_fn=preexec_fn)
        return r.returncode, r.stdout, r.stderr
    except subprocess.TimeoutExpired:
        return None, "", ""


def crashed(rc, err):
    return rc is not None and (rc < 0 or "terminate called" in err or "Sanitizer" in err or "runtime error:" in err)


def clean_error(rc, err):
    lines = err.splitlines()
    return rc not in (None, 0) and len(lines) == 1 and lines[0].startswith("ERROR: ")


def classify(rc, err, error_expected, output_ok):
    """error_expected: True (must fail), False (must succeed) or None (either).  output_ok() checks a success."""
    if rc is None:
        return "hang"
    if crashed(rc, err):
        return "crash"
    if rc == 0:
        if error_expected is True:
            return "silent wrong"
        return "valid" if output_ok() else "silent wrong"
    if error_expected is False:
        return "silent wrong"
    # A failure that is not one "ERROR: " line is an unhandled path: counted with the crashes.
    return "clean error" if clean_error(rc, err) else "crash"


def record(category, what, outcome, detail=""):
    row = table.setdefault(category, {k: 0 for k in ["tried", *OUTCOMES]})
    row["tried"] += 1
    row[outcome] += 1
    if outcome in ("crash", "hang", "silent wrong"):
        problems.append(f"{category}: {what}: {outcome} {detail}".strip())



def print_table(started):
    """Prints the table and fails the test for any crash, hang or silent wrong answer."""
    print()
    print(f"{'category':<22}" + "".join(f"{h:>14}" for h in ["tried", *OUTCOMES]))
    for category, row in table.items():
        print(f"{category:<22}" + "".join(f"{row[h]:>14}" for h in ["tried", *OUTCOMES]))
    print(f"({time.monotonic() - started:.0f} s)")
    for p in problems:
        print("PROBLEM " + p)
    for category, row in table.items():
        check(row["crash"] == 0 and row["hang"] == 0 and row["silent wrong"] == 0,
              f"{category}: no crash, hang or silent wrong answer")
