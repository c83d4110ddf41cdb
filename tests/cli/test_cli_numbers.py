#!/usr/bin/env python3
"""archipelago-cli reads every number with one strict parser (issue #12, item 2: no silent wrap).  Before, an
integer option wrapped: --steps=-1 became 2^64 - 1 and ran for ever, --seed=18446744073709551616 was cut; each
case below must now stop at once with one line naming the option, the value and the range."""
import tempfile, os

from clitest import check, finish, run

U64 = "[0, 18446744073709551615]"
tmp = tempfile.mkdtemp(prefix="archipelago-cli-numbers-")
out = os.path.join(tmp, "never-written.json")
cases = [
    # The reliability issue's cases, one regression test each.
    (["run", "--seed=18446744073709551616", "--out", out], f"--seed = 18446744073709551616 must be an integer in {U64}"),
    (["run", "--seed=99999999999999999999999", "--out", out], f"--seed = 99999999999999999999999 must be an integer in {U64}"),
    (["run", "--seed=-5", "--out", out], f"--seed = -5 must be an integer in {U64}"),
    (["orbit", "--x", "0", "--y", "0", "--steps=-1"], f"--steps = -1 must be an integer in {U64}"),
    (["replay", out, "--out", os.path.join(tmp, "seg.csv"), "--stride=-1"], f"--stride = -1 must be an integer in {U64}"),
    (["run", "--M=-1", "--out", out], f"--M = -1 must be an integer in {U64}"),
    # Narrower integer types, and integers written as reals.
    (["run", "--q=4294967296", "--out", out], "q = 4294967296 must lie in [1, 65536]"),  # the documented range
    (["periodic", "--period", "1.5e0", "--near", "0,0"], "--period = 1.5e0 must be an integer in [-2147483648, 2147483647]"),
    (["portrait", "--points", "10.5", "--out", os.path.join(tmp, "p.png")], f"--points = 10.5 must be an integer in {U64}"),
    (["portrait", "--points", "1e-3", "--out", os.path.join(tmp, "p.png")], f"--points = 1e-3 must be an integer in {U64}"),
    (["run", "--seed=1.8446744073709551616e19", "--out", out], f"--seed = 1.8446744073709551616e19 must be an integer in {U64}"),
    (["stochastic-area", "--iterations=-1"], f"--iterations = -1 must be an integer in {U64}"),
    # Reals: the whole text, finite.
    (["orbit", "--K", "inf", "--x", "0", "--y", "0"], "--K = inf must be a finite number"),
    (["orbit", "--K", "1e999", "--x", "0", "--y", "0"], "--K = 1e999 must be a finite number"),
    (["orbit", "--x", "0.1x", "--y", "0"], "--x = 0.1x must be a finite number"),
    (["orbit", "--x", "+-1", "--y", "0"], "--x = +-1 must be a finite number"),
    (["orbit", "--x", "0", "--y", "0", "--steps", "1 "], f"--steps = 1  must be an integer in {U64}"),
    (["periodic", "--period", "1", "--near", "0,0", "--radius", "nan"], "--radius = nan must be a finite number"),
    (["run", "--checkpoint-interval", "", "--out", out], "--checkpoint-interval =  must be a finite number"),
    # Lists go through the same parser.
    (["periodic", "--period", "1", "--near=0,inf"], "--near '0,inf' must be two finite numbers x,y"),
    (["periodic", "--period", "1", "--near=0,0,0"], "--near '0,0,0' must be two finite numbers x,y"),
    (["portrait", "--view=-0.8,0.5,-0.6,nan", "--out", os.path.join(tmp, "p.png")], "--view '-0.8,0.5,-0.6,nan' must be four finite numbers"),
    (["portrait", "--size", "800x-1", "--out", os.path.join(tmp, "p.png")], "--size '800x-1' must be WxH with whole numbers 1 ... 16384"),
    (["portrait", "--size", "4294967297x1", "--out", os.path.join(tmp, "p.png")], "--size '4294967297x1' must be WxH"),
    (["portrait", "--seeds", "24x24.5", "--mode", "orbits", "--out", os.path.join(tmp, "p.png")], "--seeds '24x24.5' must be WxH"),
]
for args, mention in cases:
    r = run(*args, timeout=300)
    lines = r.stderr.strip().splitlines()
    check(r.returncode > 0 and len(lines) == 1 and lines[0].startswith("ERROR: ") and mention in lines[0],
          f"{' '.join(args[:4])} -> {r.returncode}: {r.stderr.strip()}")
check(not os.path.exists(out), "no run was started by a bad number")

# Valid edge values are read exactly: the largest seed, and a '+' sign.
r = run("orbit", "--x", "0.1", "--y", "+0.05", "--steps=+3")
check(r.returncode == 0 and len(r.stdout.strip().splitlines()) == 5, f"'+' signs are accepted ({r.stderr.strip()})")
r = run("stochastic-area", "--seed=18446744073709551615", "--iterations", "1", "--orbits", "1")
check(r.returncode == 0, f"--seed = 2^64 - 1 is accepted ({r.stderr.strip()})")

# Issue #24: one rule for integers everywhere (core/io/NumberText.hpp): a decimal that is exactly whole, so the
# paper's sizes can be typed as 2e9; it is read exactly (in integers), so 2e7 gives the very run 20000000 gives.
a = run("orbit", "--x", "0.1", "--y", "0.05", "--steps=2e1")
b = run("orbit", "--x", "0.1", "--y", "0.05", "--steps=20")
check(a.returncode == 0 and a.stdout == b.stdout, f"--steps=2e1 is --steps=20 ({a.stderr.strip()})")
a = run("orbit", "--x", "0.1", "--y", "0.05", "--steps=2.0e0")
check(a.returncode == 0 and len(a.stdout.strip().splitlines()) == 4, f"--steps=2.0e0 is 2 ({a.stderr.strip()})")

finish()
