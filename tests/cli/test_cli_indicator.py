#!/usr/bin/env python3
"""archipelago-cli indicator, end to end (issue 27): the .npy + JSON sidecar (the parameters), the verdicts array,
the PNG, each kind's values where the theory says what they must be, and bad input (one ERROR line each)."""
import json, math, os, struct, tempfile

from clitest import check, finish, run


def read_npy(path):
    """(descr, shape, values) of a 2-D little-endian .npy file (numpy.lib.format version 1.0)."""
    data = open(path, "rb").read()
    length = struct.unpack("<H", data[8:10])[0]
    header = eval(data[10:10 + length].decode("latin1"))  # a Python literal dict, by the format's definition
    code = {"<f8": "d", "<u4": "I"}[header["descr"]]
    count = header["shape"][0] * header["shape"][1]
    values = struct.unpack(f"<{count}{code}", data[10 + length:10 + length + struct.calcsize(code) * count])
    return header["descr"], header["shape"], values


with tempfile.TemporaryDirectory() as d:
    npy, verdicts, png = (os.path.join(d, n) for n in ("dig.npy", "dig-verdicts.npy", "dig.png"))
    r = run("indicator", "--kind", "dig", "--size", "24x16", "--iterations", "2000", "--npy", npy, "--verdicts",
            verdicts, "--out", png, "--quiet")
    check(r.returncode == 0, f"indicator dig exits 0 ({r.stderr.strip()})")
    check(all(os.path.exists(p) for p in (npy, verdicts, png, os.path.join(d, "dig.json"))), f"files {os.listdir(d)}")
    descr, shape, values = read_npy(npy)
    check(descr == "<f8" and shape == (16, 24), f"values float64 16 x 24 ({descr} {shape})")
    check(all(0 <= v <= 16 or v < 0 for v in values) and not any(math.isnan(v) for v in values), "digits, no NaN")
    descr, shape, codes = read_npy(verdicts)
    check(descr == "<u4" and set(codes) <= {2, 3, 4}, f"verdict codes regular/chaotic/escaping ({set(codes)})")
    meta = json.load(open(os.path.join(d, "dig.json")))
    check(meta["kind"] == "dig" and meta["request"]["iterations"] == 2000 and meta["request"]["steps_per_orbit"] == 4000,
          "the sidecar carries the parameters")
    check(meta["map"]["coefficients"]["A"] == 2927339757790823 and meta["shape"] == [16, 24], "exact map and shape")
    check(sum(meta["verdicts"]["counts"].values()) == 24 * 16 and meta["verdicts"]["file"] == "dig-verdicts.npy",
          "verdict counts and file")
    # Digits below the threshold <=> chaotic.
    check(all((v < 9) == (c == 3) for v, c in zip(values, codes)), "chaotic exactly where digits < 9")
    check(open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n", "a PNG")
    check("regular=" in r.stdout and "kernel=" in r.stdout, f"summary line ({r.stdout.strip()})")

    # Near the centre (a view inside the central island): rotation ~ alpha/2pi, MEGNO ~ 2, Lyapunov ~ 0.
    view = f"--view={-math.sqrt(0.1) - 0.01},{-math.sqrt(0.1) + 0.01},-0.01,0.01"
    # MEGNO: quasi-periodic orbits tend to 2 and the stable fixed point to 0; near it the tangent vector turns on
    # the linearization's ellipse, so at finite T the average swings about those values by a few tenths.
    expectations = {"rotation": lambda v: abs(v - 0.19) < 0.002, "megno": lambda v: abs(v) < 2.1,
                    "lyapunov": lambda v: 0 <= v < 1e-3, "fli": lambda v: v < 12}
    for kind, ok in expectations.items():
        path = os.path.join(d, f"{kind}.npy")
        r = run("indicator", "--kind", kind, view, "--size", "6x4", "--iterations", "5000", "--npy", path, "--quiet")
        _, _, values = read_npy(path) if r.returncode == 0 else (None, None, [])
        check(r.returncode == 0 and len(values) == 24 and all(ok(v) for v in values),
              f"{kind} in the central island: {[round(v, 5) for v in values[:4]]} ({r.stderr.strip()})")
    # In the sea the tangent indicators grow: Lyapunov > 0.01, MEGNO >> 2.
    for kind, ok in {"lyapunov": lambda v: v > 0.01, "megno": lambda v: v > 10}.items():
        path = os.path.join(d, f"sea-{kind}.npy")
        r = run("indicator", "--kind", kind, "--view=0.3,0.32,0.3,0.32", "--size", "3x3", "--iterations", "5000",
                "--npy", path, "--quiet")
        _, _, values = read_npy(path) if r.returncode == 0 else (None, None, [])
        check(r.returncode == 0 and values and all(ok(v) for v in values), f"{kind} in the sea: {values[:3]}")

    # Bad input: one clear line, non-zero exit, no crash, nothing written.
    out = os.path.join(d, "bad")
    os.makedirs(out)
    target = os.path.join(out, "x.npy")
    for args, mention in [
        (["--kind", "chaos"], "--kind 'chaos' must be one of dig, rotation, fli, megno, lyapunov"),
        (["--size", "0x5"], "--size '0x5' must be WxH with whole numbers 1 ... 16384"),
        (["--size", "5000x5000"], "at most 2^24"),
        (["--size", "axb"], "--size 'axb'"),
        (["--iterations", "0"], "iterations = 0 must lie in [16, 10000000]"),
        (["--iterations", "nan"], "--iterations = nan must be an integer"),
        (["--threshold", "-1"], "digits threshold = -1 must lie in [0, 16]"),
        (["--threshold", "nan"], "--threshold = nan must be a finite number"),
        (["--passes", "0"], "passes = 0 must lie in [1, 12]"),
        (["--passes", "13"], "passes = 13 must lie in [1, 12]"),
        (["--view=0,0,0,0"], "view width x1 - x0 = 0 must be > 0"),
        (["--view=nan,0,0,1"], "--view 'nan,0,0,1' must be four finite numbers"),
        (["--view=-0.5,2,0,0.1"], "view"),
        (["--kind", "rotation", "--K", "0"], "must lie in (0, 1)"),
        (["--K", "inf"], "--K = inf must be a finite number"),
        (["--colormap", "rainbow"], "--colormap 'rainbow'"),
        (["--kernel", "sse9"], "unknown kernel 'sse9'"),
    ]:
        base = {"--size": "4x4", "--iterations": "100", "--npy": target}
        for a in args:
            base.pop(a.split("=")[0], None)
        r = run("indicator", *[x for kv in base.items() for x in kv], *args)
        lines = r.stderr.strip().splitlines()
        check(r.returncode > 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0],
              f"indicator {' '.join(args)} -> {r.returncode}: {r.stderr.strip()}")
    for args, mention in [
        (["--out", os.path.join(out, "missing", "x.png")], "x.png"),
        (["--npy", os.path.join(out, "missing", "x.npy")], "x.npy"),
        (["--npy", out], out),
        (["--npy", target, "--verdicts", out], out),
        ([], "give --out FILE.png and/or --npy FILE.npy"),
        (["--out", os.path.join(out, "x.png"), "--verdicts", os.path.join(out, "v.npy")], "--verdicts needs --npy"),
    ]:
        r = run("indicator", "--size", "4x4", "--iterations", "100", "--quiet", *args)
        lines = r.stderr.strip().splitlines()
        check(r.returncode > 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0],
              f"indicator {' '.join(args)} -> {r.returncode}: {r.stderr.strip()}")
    check(os.listdir(out) == [], f"nothing written by refused calls ({os.listdir(out)})")

finish()
