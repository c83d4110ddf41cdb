"""What every archipelago-cli end-to-end test shares: the executable (argv[1]), checks that print ok/FAIL and
are counted, running the tool, parsing its "# key: value" + CSV reports, and the exit status."""
import csv, hashlib, io, json, os, re, signal, subprocess, sys, time

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


def parse_report(stdout):
    """A report on stdout: '# key: value' header lines, then CSV.  Returns (header dict, list of row dicts)."""
    header, body = {}, []
    for line in stdout.splitlines():
        if line.startswith("# ") and ": " in line:
            key, value = line[2:].split(": ", 1)
            header[key] = value
        elif not line.startswith("#"):
            body.append(line)
    return header, list(csv.DictReader(io.StringIO("\n".join(body))))


def options_with(settings, args):
    """The options of `settings` (a dict of option to value), those that `args` gives replaced by `args`."""
    given = {a for a in args if a.startswith("--")}
    return [x for k, v in settings.items() if k not in given for x in (k, v)] + list(args)


def tail_results(path):
    """What a tail file says, without what may differ between sessions (time, kernel)."""
    d = json.load(open(path))
    for key in ("elapsedSeconds", "kernel", "checksum"):
        d.pop(key)
    return d


def wait_for_file(path, process, seconds=60):
    """Waits until `path` exists (True), `process` has ended or `seconds` have passed (False)."""
    deadline = time.monotonic() + seconds
    while not os.path.exists(path) and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.02)
    return os.path.exists(path)


def interrupt(process, timeout=600):
    """SIGINT (a clean stop at a chunk boundary), then (stdout, stderr); killed and (None, None) after timeout."""
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
    try:
        return process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        return None, None


def wait_for_handler(process, signum=signal.SIGINT, seconds=120):
    """Waits until `process` catches `signum` (its bit in SigCgt of /proc/PID/status: the handler is installed, the
    event a test waits for before it interrupts) or has ended; whether it catches it."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and process.poll() is None:
        try:
            with open(f"/proc/{process.pid}/status") as status:
                caught = next(int(l.split()[1], 16) for l in status if l.startswith("SigCgt:"))
        except (OSError, StopIteration):
            return False
        if caught >> (signum - 1) & 1:
            return True
        time.sleep(0.01)
    return False


def leftovers(folder):
    """What writers left in `folder`: temporaries ".NAME.XXXXXX" (io::AtomicOutputFile) and locks ".NAME.lock"."""
    return sorted(n for n in os.listdir(folder) if re.fullmatch(r"\..+\.(lock|[A-Za-z0-9]{6})", n))


def finish():
    sys.exit(1 if _failures else 0)


def signed(document):
    """An edited run, tail or atlas document signed again (io::jsonChecksum: SHA-256 of the document without its
    checksum, keys sorted, indent 1): a test that edits a file on purpose gets past the checksum to the rule it tests."""
    d = dict(document)
    d.pop("checksum", None)
    text = json.dumps(d, indent=1, sort_keys=True, ensure_ascii=False)
    d["checksum"] = "sha256:" + hashlib.sha256(text.encode()).hexdigest()
    return d
