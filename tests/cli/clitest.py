"""What every archipelago-cli end-to-end test shares: the executable (argv[1]), checks that print ok/FAIL and
are counted, running the tool, and the exit status."""
import subprocess, sys

cli = sys.argv[1]
_failures = 0


def check(cond, what):
    """Prints 'ok' or 'FAIL' with `what`; a failure makes finish() exit non-zero."""
    global _failures
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    _failures += 0 if cond else 1


def run(*args, timeout=300):
    """Runs archipelago-cli with `args`; stdout and stderr captured as text."""
    return subprocess.run([cli, *args], capture_output=True, text=True, timeout=timeout)


def finish():
    sys.exit(1 if _failures else 0)
