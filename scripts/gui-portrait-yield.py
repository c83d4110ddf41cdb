#!/usr/bin/env python3
"""Benchmark (not a test): do the phase portrait and the segment panel's chain identification yield the cores to a run?
(Issue 25, finding 15, deliverable 5; issue 41, deliverable 4.)

Runs `archipelago --measure SECONDS` on the K = 0.1 preset under Xvfb (or Qt's offscreen platform) alternately
with the portrait accumulating on the first screen (a budget it cannot reach) and with it hidden on the Statistics
tab (where it pauses), ROUNDS times each, and prints the run's rate in each case, their ratio, the points the
portrait added, and the event latency (the menu latency a user would see).  Targets: the run keeps at least 80 %
of its rate beside the visible portrait; event latency under 100 ms.

With --chains, both cases have the portrait hidden (on the Statistics tab, paused) and differ in the segment panel:
its chain identification of the top 10 segments as they appear (the default of the GUI) or none (`--chains 0`);
it prints the run's rate in each case, their ratio (target >= 0.80), and the fraction of the time the segment
panel's jobs were running (so that a ratio near 1 is seen to come with chains actually being identified).

The machine should be otherwise idle: other processes on the cores change both rates.

Usage: scripts/gui-portrait-yield.py [--app build/default/app/gui/archipelago] [--seconds 20] [--rounds 2] [--chains]
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

RATIO_TARGET = 0.80
LATENCY_TARGET_MS = 100.0


def measure(app: str, seconds: float, hidden: bool, offscreen: bool, chains: int = None) -> dict:
    command = [app, "--preset", "K = 0.1, under a minute", "--threads", "0", "--budget", "1000000000000",
               "--measure", str(seconds)]
    if hidden:
        command += ["--tab", "Statistics"]
    if chains is not None:
        command += ["--chains", str(chains)]
    env = dict(os.environ)
    home = tempfile.mkdtemp(prefix="archipelago-yield-")
    env.update(XDG_CONFIG_HOME=os.path.join(home, "config"), XDG_DATA_HOME=os.path.join(home, "data"),
               XDG_RUNTIME_DIR=home)
    if offscreen or not shutil.which("xvfb-run"):
        env["QT_QPA_PLATFORM"] = "offscreen"
    else:
        command = ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24"] + command
    try:
        out = subprocess.run(command, env=env, capture_output=True, text=True, timeout=seconds + 180)
    finally:
        shutil.rmtree(home, ignore_errors=True)
    lines = [l for l in out.stdout.splitlines() if l.startswith("{")]
    if out.returncode != 0 or not lines:
        sys.stderr.write(out.stdout + out.stderr)
        raise SystemExit("ERROR: the application did not report a measurement")
    return json.loads(lines[-1])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--app", default="build/default/app/gui/archipelago")
    parser.add_argument("--seconds", type=float, default=20.0)
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--offscreen", action="store_true", help="Qt's offscreen platform, not Xvfb")
    parser.add_argument("--chains", action="store_true",
                        help="compare the run with the segment panel identifying chains and without (portrait hidden)")
    args = parser.parse_args()
    if args.chains:
        return compare_chains(args)
    visible, hidden = [], []
    for r in range(args.rounds):
        for is_hidden, into in ((False, visible), (True, hidden)):
            m = measure(args.app, args.seconds, is_hidden, args.offscreen)
            into.append(m)
            print(f"round {r + 1}, portrait {'hidden ' if is_hidden else 'visible'}: run "
                  f"{m['run_steps_per_second'] / 1e6:.1f} M steps/s, portrait +{m['portrait_points_added']:.3g} points, "
                  f"latency median {m['latency_ms_median']:.1f} ms, max {m['latency_ms_max']:.1f} ms", flush=True)
    rate_visible = statistics.median(m["run_steps_per_second"] for m in visible)
    rate_hidden = statistics.median(m["run_steps_per_second"] for m in hidden)
    ratio = rate_visible / rate_hidden if rate_hidden > 0 else float("nan")
    latency = max(m["latency_ms_max"] for m in visible + hidden)
    p99 = max(m["latency_ms_p99"] for m in visible + hidden)
    print(f"run rate beside the visible portrait / with it hidden: {rate_visible / 1e6:.1f} / {rate_hidden / 1e6:.1f} "
          f"M steps/s = {ratio:.2f}   (target >= {RATIO_TARGET:.2f}: {'met' if ratio >= RATIO_TARGET else 'MISSED'})")
    print(f"portrait while hidden: +{max(m['portrait_points_added'] for m in hidden):.3g} points (paused: 0 expected)")
    print(f"event latency during the runs: p99 {p99:.1f} ms, max {latency:.1f} ms   "
          f"(target <= {LATENCY_TARGET_MS:.0f} ms: {'met' if latency <= LATENCY_TARGET_MS else 'MISSED'})")
    return 0


def compare_chains(args) -> int:
    identifying, alone = [], []
    for r in range(args.rounds):
        for rows, into in ((10, identifying), (0, alone)):
            m = measure(args.app, args.seconds, True, args.offscreen, rows)
            into.append(m)
            print(f"round {r + 1}, chains of the top {rows:2d} segments: run "
                  f"{m['run_steps_per_second'] / 1e6:.1f} M steps/s, segment jobs running "
                  f"{100 * m['segment_jobs_busy']:.0f} % of the time, latency max {m['latency_ms_max']:.1f} ms",
                  flush=True)
    rate_identifying = statistics.median(m["run_steps_per_second"] for m in identifying)
    rate_alone = statistics.median(m["run_steps_per_second"] for m in alone)
    ratio = rate_identifying / rate_alone if rate_alone > 0 else float("nan")
    busy = statistics.median(m["segment_jobs_busy"] for m in identifying)
    print(f"run rate with the segment panel identifying chains / alone: {rate_identifying / 1e6:.1f} / "
          f"{rate_alone / 1e6:.1f} M steps/s = {ratio:.2f}   (target >= {RATIO_TARGET:.2f}: "
          f"{'met' if ratio >= RATIO_TARGET else 'MISSED'}); chains being identified {100 * busy:.0f} % of the time")
    return 0


if __name__ == "__main__":
    sys.exit(main())
