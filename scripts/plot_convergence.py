#!/usr/bin/python3
"""Plot `atssim converge` results: relative energy error vs iterations and vs time.

y_k = (E_k - E*) / (E_0 - E*) per variant (method / schedule / merge
strategy), in the style of Fig. 4 of He et al. 2025: left, error against the
iteration count; right, error against the measured substep time.

usage: scripts/plot_convergence.py convergence.h5 [-o convergence.png]
Needs Debian's python3-h5py and python3-matplotlib (scripts/setup.sh).
"""
import argparse
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("-o", "--output", default="convergence.png")
    args = ap.parse_args()
    try:
        f = h5py.File(args.result, "r")
    except OSError as e:
        print(f"{args.result}: cannot open ({e})", file=sys.stderr)
        return 2
    with f:
        if "convergence" not in f:
            print(f"{args.result}: no /convergence group (write it with atssim converge)", file=sys.stderr)
            return 2
        c = f["convergence"]
        fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.5))
        for name in c["variants"][:]:
            name = name.decode() if isinstance(name, bytes) else str(name)
            g = c[name.replace("/", ":")]
            k = g["iterations"][:]
            y = np.maximum(g["relative_error"][:], 1e-7)  # log axis: clamp the float floor
            t = g["time_ms"][:]
            style = "--" if "async" not in name else "-"
            left.plot(k, y, style, marker="o", label=name)
            right.plot(t, y, style, marker="o", label=name)
        left.set_xscale("log", base=2)
        for ax in (left, right):
            ax.set_yscale("log")
            ax.set_ylabel("relative energy error y")
            ax.grid(True, which="both", alpha=0.3)
        left.set_xlabel("iterations per substep")
        right.set_xlabel("measured substep time (ms)")
        left.legend(fontsize=8)
        e0, es = c["energy_start"][0], c["energy_reference"][0]
        fig.suptitle(f"{args.result}: E0 = {e0:.6g}, E* = {es:.6g} (Newton), "
                     f"after {c.attrs['frames_before']} frames", fontsize=10)
        fig.tight_layout()
        fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
