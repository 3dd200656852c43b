#!/usr/bin/python3
"""Plot the choices of `atssim run --tolerance` / `--budget`: y and ms per frame.

Top: the relative energy error y of the choice in force at every probe and
re-check (/decisions/y; hollow where the state did not resolve the goal,
i.e. y is float32 rounding), the float32 floor of each state, and the
tolerance. Bottom: the wall time of every frame (/timing/frame_ms), the
frame time the cost model predicted for the choice in force, and the
budget. A vertical line and a label mark every change of method,
iterations or schedule.

usage: scripts/plot_decisions.py run.h5 [-o decisions.png]
Needs Debian's python3-h5py and python3-matplotlib (scripts/setup.sh).
"""
import argparse
import re
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def text(values):
    return [v.decode(errors="replace").rstrip("\0") if isinstance(v, bytes) else str(v) for v in values]


def goal(f):
    """(tolerance, budget_ms) from the resolved scene; None where absent."""
    resolved = f["scene/resolved"][()]
    resolved = resolved.decode() if isinstance(resolved, bytes) else str(resolved)
    found = {}
    for key in ("tolerance", "budget_ms"):
        m = re.search(rf"^\s+{key}:\s*([0-9.eE+-]+)\s*$", resolved, re.M)
        found[key] = float(m.group(1)) if m else None
    return found["tolerance"], found["budget_ms"]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("-o", "--output", default="decisions.png")
    args = ap.parse_args()
    try:
        f = h5py.File(args.result, "r")
    except OSError as e:
        print(f"{args.result}: cannot open ({e})", file=sys.stderr)
        return 2
    with f:
        if "decisions" not in f:
            print(f"{args.result}: no /decisions (a run with --tolerance or --budget writes it)", file=sys.stderr)
            return 2
        d = f["decisions"]
        frame = d["frame"][:]
        y, floor = d["y"][:], d["y_floor"][:]
        predicted = d["predicted_ms"][:]
        method, schedule = text(d["method"][:]), text(d["schedule"][:])
        iterations, changed = d["iterations"][:], d["changed"][:]
        frame_ms = f["timing/frame_ms"][:]
        tolerance, budget = goal(f)
    # Frame k of /timing is simulated frame k (0: the initial state, no time).
    frames = np.arange(len(frame_ms))
    resolution = tolerance if tolerance else 1e-2
    resolved = np.isfinite(floor) & (4 * floor <= resolution)

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(10, 7), sharex=True)
    top.semilogy(frame[resolved], y[resolved], "o-", color="C0", label="y of the choice in force")
    top.semilogy(frame[~resolved], y[~resolved], "o", mfc="none", color="C0", label="y (state below float32 resolution)")
    top.semilogy(frame, floor, ":", color="C7", label="float32 floor of y")
    if tolerance:
        top.axhline(tolerance, color="C3", ls="--", label=f"tolerance {tolerance:g}")
    top.set_ylabel("relative energy error y")
    top.legend(fontsize=8, loc="best")

    bottom.plot(frames[1:], frame_ms[1:], ".", color="C1", ms=4, label="measured ms per frame")
    # The prediction holds from the frame after its decision to the next one.
    edges = list(frame) + [frames[-1]]
    for i in range(len(frame)):
        bottom.hlines(predicted[i], edges[i] + 0.5, edges[i + 1] + 0.5, color="C2", lw=2,
                      label="predicted ms per frame" if i == 0 else None)
    if budget:
        bottom.axhline(budget, color="C3", ls="--", label=f"budget {budget:g} ms")
    bottom.set_xlabel("frame")
    bottom.set_ylabel("ms per frame")
    bottom.legend(fontsize=8, loc="best")

    for i in range(len(frame)):
        if not changed[i]:
            continue
        for ax in (top, bottom):
            ax.axvline(frame[i] + 0.5, color="C4", lw=0.8, alpha=0.6)
        top.annotate(f"{method[i]} {iterations[i]} {schedule[i]}", (frame[i] + 0.5, 1.0),
                     xycoords=("data", "axes fraction"), rotation=90, va="top", ha="right", fontsize=7)
    top.set_title(args.result)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
