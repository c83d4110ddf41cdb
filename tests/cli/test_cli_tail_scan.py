#!/usr/bin/env python3
"""archipelago-cli tail-scan, end to end (issue 55): a tail file per K, each the run of `tail` in the scan's box; the
summary and its CSVs; a rerun from the files giving the same bytes; a scan killed (SIGKILL) and stopped (SIGINT, exit
130) whose resumes give the uninterrupted scan's files bit for bit; the K shared over tasks; and hostile input (one
ERROR line, a non-zero exit, nothing written).  The figure gamma(t, K), PREFIX_gamma.png: a valid PNG of a column
per K and a band of rows per window, grey exactly where the gamma CSV has no gamma, written only with the summary."""
import csv, json, math, os, shutil, signal, struct, subprocess, tempfile, time, zlib

from clitest import check, cli, finish, interrupt, run, wait_for_handler, options_with, tail_results

SETTINGS = {"--K": "0.1,0.15", "--t-max": "3e4", "--first": "100", "--population": "40", "--replicas": "4",
            "--min-ancestors": "4", "--threads": "2"}
SMALL = [x for kv in SETTINGS.items() for x in kv]


def small_with(args):
    """SMALL with the options of `args` replacing its own."""
    return options_with(SETTINGS, args)


results = tail_results


def wait_for_unfinished(path, process, seconds=600):
    """Waits until `path` holds an unfinished tail file (True), or the file is finished, `process` has ended or
    `seconds` have passed (False).  Each checkpoint replaces the file whole."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and process.poll() is None:
        try:
            return not json.load(open(path))["finished"]
        except (OSError, ValueError, KeyError):
            time.sleep(0.02)
    return False


def png_image(path):
    """A PNG file's (width, height, rows of (r, g, b) pixels), its chunks' CRCs checked; 8-bit RGB, no interlace, rows
    filtered with None or Sub (what core/io/Png writes).  None when it is not such a PNG."""
    data = open(path, "rb").read() if os.path.exists(path) else b""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    i, chunks = 8, []
    while i + 12 <= len(data):
        n, kind = struct.unpack(">I4s", data[i:i + 8])
        body = data[i + 8:i + 8 + n]
        if struct.unpack(">I", data[i + 8 + n:i + 12 + n])[0] != zlib.crc32(kind + body):
            return None
        chunks.append((kind, body))
        i += 12 + n
    if not chunks or chunks[0][0] != b"IHDR" or chunks[-1][0] != b"IEND":
        return None
    width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunks[0][1])
    if (depth, colour, interlace) != (8, 2, 0):
        return None
    raw = zlib.decompress(b"".join(body for kind, body in chunks if kind == b"IDAT"))
    if len(raw) != height * (1 + 3 * width):
        return None
    rows = []
    for y in range(height):
        line = bytearray(raw[y * (1 + 3 * width) + 1:(y + 1) * (1 + 3 * width)])
        kind = raw[y * (1 + 3 * width)]
        if kind not in (0, 1):
            return None
        for x in range(3, len(line)) if kind == 1 else ():
            line[x] = (line[x] + line[x - 3]) & 0xFF
        rows.append([tuple(line[3 * x:3 * x + 3]) for x in range(width)])
    return width, height, rows


def scan(folder, *extra):
    return run("tail-scan", *SMALL, "--dir", folder, *extra)


def files(folder):
    return sorted(os.listdir(folder)) if os.path.isdir(folder) else []


with tempfile.TemporaryDirectory() as d:
    a = os.path.join(d, "a")
    r = scan(a, "--csv", os.path.join(a, "sum"), "--checkpoint-interval", "0.2")
    check(r.returncode == 0, f"tail-scan exits 0 ({r.stderr.strip()[-300:]})")
    check(files(a) == ["sum_P.csv", "sum_average.csv", "sum_gamma.csv", "sum_gamma.png", "tail-K0.1.json",
                       "tail-K0.15.json"], f"a tail file per K, the three CSVs and the figure ({files(a)})")
    check("WARNING" not in r.stderr, "K = 0.1 and 0.15: the scan's boxes hold the island (no warning)")
    check(r.stderr.count("started") == 2 and "finished" in r.stderr, "progress per K")
    summary = r.stdout
    average = list(csv.DictReader(open(os.path.join(a, "sum_average.csv"))))
    check(len(average) >= 2 and all(row["K_count"] == "2" for row in average),
          f"every window reached by both K ({[row['K_count'] for row in average]})")
    gamma = list(csv.DictReader(open(os.path.join(a, "sum_gamma.csv"))))
    for row in average:
        g = [float(x["gamma"]) for x in gamma if x["t_from"] == row["t_from"]]
        check(abs(float(row["gamma_mean"]) - sum(g) / 2) <= 1e-15 * abs(sum(g))
              and abs(float(row["gamma_spread"]) - abs(g[0] - g[1]) / 2 ** 0.5) <= 1e-12,
              f"the K-average and spread of window {row['t_from']}..{row['t_to']} from the gamma CSV")
    P = list(csv.DictReader(open(os.path.join(a, "sum_P.csv"))))
    doc = json.load(open(os.path.join(a, "tail-K0.1.json")))
    check([float(x["P"]) for x in P if x["K"] == "0.10000000000000001"] == [L["P"] for L in doc["levels"]],
          "the P CSV holds each tail file's levels")
    check(doc["finished"] and doc["parameters"]["K"] == 0.1, "a finished tail file of K = 0.1")

    # Each K's file is the run `tail` makes with the same settings in the scan's box.
    par = doc["parameters"]
    one = os.path.join(d, "one.json")
    r = run("tail", *SMALL[2:], "--K", "0.1", "--xmin", repr(par["xmin"]), "--xmax", repr(par["xmax"]), "--out", one,
            "--quiet")
    check(r.returncode == 0 and results(one) == results(os.path.join(a, "tail-K0.1.json")),
          f"K = 0.1's file is tail's run in the box of scanBox(0.1) ({r.stderr.strip()[-200:]})")

    # A rerun from the files: every K reused, the same summary, byte for byte.
    before = {n: open(os.path.join(a, n), "rb").read() for n in files(a)}
    r = scan(a, "--csv", os.path.join(a, "sum"))
    check(r.returncode == 0 and r.stderr.count("reused") == 2, f"a rerun reuses every K ({r.stderr.strip()[-200:]})")
    check(r.stdout == summary, "the rerun's summary: the same bytes")
    check(all(open(os.path.join(a, n), "rb").read() == before[n] for n in before), "the same files, byte for byte")

    # Killed (SIGKILL) once a checkpoint exists, then stopped (SIGINT): each resume goes on from the files, and the
    # end is the uninterrupted scan's, bit for bit.
    b = os.path.join(d, "b")
    # A longer scan (t_max 10^7, N = 200) than SMALL's, which can end within its first chunk: the kill comes once
    # K = 0.1's file holds an unfinished checkpoint, whatever the machine's speed.
    LONG = small_with(["--t-max", "1e7", "--population", "200"])
    ref = os.path.join(d, "ref")
    r = run("tail-scan", *LONG, "--dir", ref, "--quiet")
    check(r.returncode == 0, f"the longer scan, uninterrupted ({r.stderr.strip()[-200:]})")
    p = subprocess.Popen([cli, "tail-scan", *LONG, "--dir", b, "--checkpoint-interval", "0.05", "--quiet"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    check(wait_for_unfinished(os.path.join(b, "tail-K0.1.json"), p), "an unfinished checkpoint of K = 0.1 appears")
    p.kill()
    p.communicate()
    killed = json.load(open(os.path.join(b, "tail-K0.1.json")))
    check(not killed["finished"], "killed mid-way: K = 0.1's checkpoint is unfinished")
    p = subprocess.Popen([cli, "tail-scan", *LONG, "--dir", b, "--checkpoint-interval", "0.05"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for_handler(p)
    out, err = interrupt(p)
    check(p.returncode in (0, 130), f"the resumed scan stops on SIGINT or finishes ({p.returncode})")
    if p.returncode == 130:
        check("resumed" in err and "run the same archipelago-cli tail-scan command again to resume" in err, f"exit 130 says how ({err.strip()[-200:]})")
    r = run("tail-scan", *LONG, "--dir", b)
    check(r.returncode == 0 and r.stdout == run("tail-scan", *LONG, "--dir", ref).stdout,
          f"resumed to the end: the uninterrupted summary ({r.stderr.strip()[-200:]})")
    check(all(results(os.path.join(b, f"tail-K{k}.json")) == results(os.path.join(ref, f"tail-K{k}.json"))
              for k in ("0.1", "0.15")), "resumed: every tail file's results bit for bit")

    # Two tasks of an array: each its K; the summary once both are done.
    c = os.path.join(d, "c")
    r = scan(c, "--task", "1/2", "--csv", os.path.join(c, "s"))
    check(r.returncode == 0 and files(c) == ["tail-K0.15.json"] and "waits for K = 0.1" in r.stderr,
          f"task 1/2 runs K = 0.15 only and waits, no summary nor figure ({r.stderr.strip()[-200:]})")
    r = scan(c, "--task", "0/2", "--csv", os.path.join(c, "s"))
    check(r.returncode == 0 and r.stdout == summary, "task 0/2 ends the scan: the one-process summary")
    check(open(os.path.join(c, "s_gamma.png"), "rb").read() == open(os.path.join(a, "sum_gamma.png"), "rb").read(),
          "with the summary, its figure: the one-process scan's, byte for byte")

    # The figure of a tiny scan (two K, 10 to 10^4 steps, N = 200, R = 2: K = 0.15 reaches no window, K = 0.1 every
    # one, on this seed): PREFIX_gamma.png, a column of 240 pixels per K,
    # log t up at 30 rows of 4 pixels a decade from the first window's centre to the last's (core's heat-map PNG);
    # the band of each window grey (190, 190, 190) exactly where the gamma CSV gives no gamma.
    f = os.path.join(d, "figure")
    r = run("tail-scan", *small_with(["--t-max", "1e4", "--first", "10", "--population", "200", "--replicas", "2"]), "--dir", f,
            "--csv", os.path.join(f, "s"), "--quiet")
    check(r.returncode == 0, f"the tiny scan ({r.stderr.strip()[-200:]})")
    image = png_image(os.path.join(f, "s_gamma.png"))
    windows = [float(row["t"]) for row in csv.DictReader(open(os.path.join(f, "s_average.csv")))]
    gamma = list(csv.DictReader(open(os.path.join(f, "s_gamma.csv"))))
    check(image is not None and len(windows) >= 2, f"s_gamma.png is a valid PNG; {len(windows)} windows")
    if image is not None and len(windows) >= 2:
        width, height, rows = image
        lo, hi = math.log10(windows[0]), math.log10(windows[-1])
        check((width, height) == (2 * 240, 4 * (math.ceil((hi - lo) * 30) + 1)),
              f"s_gamma.png: 2 K x {len(windows)} windows in {width} x {height} pixels")
        cells = []
        for row in gamma:
            y = 4 * round((hi - math.log10(float(row["t"]))) * 30) + 1
            x = 240 * (0 if row["K"].startswith("0.1000") else 1) + 120
            cells.append((rows[y][x] == (190, 190, 190)) == (row["gamma"] == ""))
        check(len(cells) == 2 * len(windows) and all(cells) and "" in [row["gamma"] for row in gamma],
              f"grey exactly where no gamma: {[row['gamma'][:5] or 'none' for row in gamma]}")

    # Hostile input: one ERROR line, non-zero, nothing written.
    h = os.path.join(d, "h")
    os.makedirs(h)
    truncated = os.path.join(d, "truncated")
    os.makedirs(truncated)
    with open(os.path.join(truncated, "tail-K0.1.json"), "w") as f:
        f.write(open(os.path.join(a, "tail-K0.1.json")).read()[:5000])
    other = os.path.join(d, "other")
    shutil.copytree(a, other)
    swapped = os.path.join(d, "swapped")
    os.makedirs(swapped)
    shutil.copy(os.path.join(a, "tail-K0.1.json"), os.path.join(swapped, "tail-K0.15.json"))
    for args, folder, mention in [
        (["--K", "nan"], h, "--K: "),
        (["--K", "0.1,0.1"], h, "twice"),
        (["--t-max", "-5"], h, "--t-max = -5 must be an integer"),
        (["--task", "3/2"], h, "--task '3/2' must be I/N, whole numbers with I < N"),
        (["--task", ""], h, "--task"),
        (["--checkpoint-interval", "-1"], h, "--checkpoint-interval"),
        (["--clones", "magic"], h, "--clones 'magic'"),
        ([], truncated, "tail-K0.1.json"),
        (["--population", "41"], other, "--population differs"),
        ([], swapped, "the map or its box differs"),
    ]:
        listed = files(folder)
        r = run("tail-scan", *small_with(args), "--dir", folder)
        lines = r.stderr.strip().splitlines()
        check(r.returncode != 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0]
              and files(folder) == listed, f"{' '.join(args)[:40] or folder} -> {lines[:1]}")

    # A first level out of the map's reach, found only by stage 0's pilot while running (K = 0.3: P(1008) ~ 10^-7):
    # the K's file keeps the pilot's counts and the scan goes on without it, saying so; the summary lists it apart.
    # A scan whose every K is out of reach is one ERROR line naming the option by this front end's name.
    r = run("tail-scan", *small_with(["--K", "0.1,0.3", "--first", "1000"]), "--dir", h)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 0 and any(x.startswith("K = 0.3: out of reach, only ") for x in lines)
          and "#   K = 0.3: only " in r.stdout and files(h) == ["tail-K0.1.json", "tail-K0.3.json"],
          f"K = 0.1, 0.3 at first level 1008 -> {lines[-2:]}")
    h2 = os.path.join(d, "h2")
    r = run("tail-scan", *small_with(["--K", "0.3", "--first", "1000"]), "--dir", h2)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 1 and sum(x.startswith("ERROR") for x in lines) == 1
          and lines[-1].startswith("ERROR: no K of the scan reached its first level; K = 0.3: only ")
          and lines[-1].endswith("give a lower first level (--first)") and files(h2) == ["tail-K0.3.json"],
          f"K = 0.3 alone at first level 1008 -> {lines[-1:]}")
    out = os.path.join(d, "k03.json")
    r = run("tail", "--K", "0.3", "--xmin", "-1.3", "--xmax", "0.75", "--t-max", "1e4", "--threads", "2",
            "--out", out)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 1 and lines[-1:] and lines[-1].startswith("ERROR: only ")
          and lines[-1].endswith("give a lower first level (--first)"), f"tail at K = 0.3 -> {lines[-1:]}")

finish()
