#!/usr/bin/env python3
"""Measures how responsive the GUI stays while a trapping run uses every core (issue 5; not a test).

Starts `archipelago --measure SECONDS` (a K = 0.1 run on all cores; the app posts a timestamped event every
20 ms and times its delivery, and counts plot redraws) under Xvfb when available, else on Qt's offscreen
platform, and prints the numbers with the targets: event latency <= 100 ms, plot refresh >= 5 Hz.

Usage: scripts/gui-latency.py [--app build/app/gui/archipelago] [--seconds 15] [--preset NAME]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

LATENCY_TARGET_MS = 100.0
REFRESH_TARGET_HZ = 5.0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--app", default="build/app/gui/archipelago")
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--preset", default="K = 0.1, under a minute")
    parser.add_argument("--offscreen", action="store_true", help="use Qt's offscreen platform, not Xvfb")
    args = parser.parse_args()

    command = [args.app, "--preset", args.preset, "--threads", "0", "--measure", str(args.seconds)]
    env = dict(os.environ)
    home = tempfile.mkdtemp(prefix="archipelago-latency-")
    env.update(XDG_CONFIG_HOME=os.path.join(home, "config"), XDG_DATA_HOME=os.path.join(home, "data"))
    if args.offscreen or not shutil.which("xvfb-run"):
        env["QT_QPA_PLATFORM"] = "offscreen"
        platform = "offscreen"
    else:
        command = ["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24"] + command
        platform = "xvfb"
    out = subprocess.run(command, env=env, capture_output=True, text=True, timeout=args.seconds + 120)
    shutil.rmtree(home, ignore_errors=True)
    lines = [l for l in out.stdout.splitlines() if l.startswith("{")]
    if out.returncode != 0 or not lines:
        print(out.stdout, out.stderr, file=sys.stderr)
        print("ERROR: the application did not report a measurement", file=sys.stderr)
        return 1
    r = json.loads(lines[-1])
    print(f"platform: {platform}, cores: {r['cores']}, run still computing at the end: {r['status_running']}")
    print(f"measured {r['seconds']:.1f} s, {r['events']} probe events")
    print(f"event latency: median {r['latency_ms_median']:.2f} ms, p99 {r['latency_ms_p99']:.2f} ms, "
          f"max {r['latency_ms_max']:.2f} ms   (target <= {LATENCY_TARGET_MS:.0f} ms: "
          f"{'met' if r['latency_ms_max'] <= LATENCY_TARGET_MS else 'MISSED'})")
    print(f"plot refresh: {r['refresh_hz']:.1f} Hz ({r['refreshes']:.0f} redraws of all six plots, {r['refresh_ms_mean']:.1f} ms each)   "
          f"(target >= {REFRESH_TARGET_HZ:.0f} Hz: {'met' if r['refresh_hz'] >= REFRESH_TARGET_HZ else 'MISSED'})")
    print(f"snapshots skipped by the worker while the GUI was busy: {r['skipped_snapshots']:.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
