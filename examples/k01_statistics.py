#!/usr/bin/env python3
"""The paper's K = 0.1 trapping statistics (Karney 1983, fig. 6 "expense": f_t, P_t, C_tau and the local
exponent -d log C_tau / d log tau), computed from Python with the archipelago module and drawn with matplotlib.

    PYTHONPATH=build/default/python python3 examples/k01_statistics.py --out k01.png

By default it runs the preset "k0.1-minute" (M = 128 orbits of qT = 3.2e8 steps: seconds with AVX-512, about a
minute on the portable path); --preset k0.1-paper-fig6 is the paper's size (hours).  Ctrl-C stops the run at a
chunk boundary and writes the checkpoint given by --run-file, from which the next call resumes.
"""
import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import archipelago as ap  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--preset", default="k0.1-minute", choices=sorted(ap.presets()))
    parser.add_argument("--run-file", default="k01-run.json", help="run file: resumed when it exists, written at the end")
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--out", default="k01_statistics.png")
    args = parser.parse_args()

    if os.path.exists(args.run_file):
        run = ap.load(args.run_file)
    else:
        run = ap.start(ap.presets()[args.preset])
    if not run.finished:
        def progress(p):
            print(f"\r{100 * p['fraction']:5.1f}%  {p['steps_per_second']:.3g} steps/s  "
                  f"ETA {p['eta_seconds']:.0f} s", end="", file=sys.stderr, flush=True)
        try:
            run.advance(threads=args.threads, progress=progress, checkpoint=args.run_file)
        except KeyboardInterrupt:
            print(f"\ninterrupted: resume with the same command ({args.run_file})", file=sys.stderr)
            return 130
        print(file=sys.stderr)
        run.save(args.run_file)

    s = run.statistics()
    p = run.parameters
    fig, ax = plt.subplots(2, 2, figsize=(10, 8))
    panels = [
        (ax[0, 0], "f_t", r"$f_t$", True),
        (ax[0, 1], "P_t", r"$P_t$", True),
        (ax[1, 0], "C_tau", r"$C_\tau$", True),
        (ax[1, 1], "local_exponent", r"$-d\log C_\tau/d\log\tau$", False),
    ]
    for a, key, label, logy in panels:
        x, y, e = (np.asarray(s[key][k]) for k in ("x", "value", "error"))
        keep = (x > 0) & (y > 0) if logy else (x > 0)
        a.errorbar(x[keep], y[keep], yerr=e[keep], fmt=".", ms=3, elinewidth=0.6, capsize=0)
        a.set_xscale("log")
        if logy:
            a.set_yscale("log")
        a.set_xlabel(r"$t$ (steps)" if key in ("f_t", "P_t") else r"$\tau$ (steps)")
        a.set_ylabel(label)
        a.grid(True, which="major", alpha=0.3)
    # Guides of the paper's section 5: P_t ~ t^(-5/4) for t <~ 1e4 (local exponent 1/4).
    x = np.array([1e2, 1e5])
    ax[0, 1].plot(x, 0.5 * (x / 1e2) ** -1.25, "k--", lw=0.8, label=r"$t^{-5/4}$")
    ax[0, 1].legend()
    ax[1, 1].axhline(0.25, color="k", ls="--", lw=0.8)
    ax[1, 1].set_ylim(0, 2)
    # D's error only where the run supports one (the bootstrap over segments); none when its longest segments
    # dominate it (s["D_verdict"] says why; s["D_error_subsets"], the paper's error, is far too small then).
    D_text = (f"D = {s['D']:.4g} ± {s['D_error']:.2g}" if np.isfinite(s["D_error"])
              else f"D = {s['D']:.4g} (dominated by its longest segments: no error)")
    fig.suptitle(f"K = {p['K']}: M = {p['M']} orbits of qT = {p['q'] * p['T']:.3g} steps; "
                 f"α = {s['alpha']:.4g} ± {s['alpha_error']:.2g}, {D_text} "
                 f"(Karney 1983, fig. 6)")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
