#!/usr/bin/python3
"""Draw the recorded substep of one frame as a device-lane schedule map (PNG).

One lane per device, one box per task coloured by kind (predict, stretch,
bend, update_velocity, …), arrows for the cross-device waits; the top panel
shows the scheduler's prediction, the bottom one what the devices did
(OpenCL profiling events). In the style of Fig. 10 of He et al. 2025.

usage: scripts/plot_schedule.py OUT.h5 [--frame K] [-o map.png] [--until MS]
Needs Debian's python3-h5py and python3-matplotlib (scripts/setup.sh).
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

COLOURS = ["#4c78a8", "#f58518", "#54a24b", "#e45756", "#72b7b2", "#eeca3b", "#b279a2", "#ff9da6", "#9d755d"]


def text(values):
    return [v.decode() if isinstance(v, bytes) else str(v) for v in values]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("--frame", type=int, default=-1, help="simulated frame (default: the last recorded)")
    ap.add_argument("-o", "--output", default="schedule.png")
    ap.add_argument("--until", type=float, default=None, help="show only the first MS milliseconds")
    args = ap.parse_args()
    try:
        f = h5py.File(args.result, "r", swmr=True)
    except OSError as e:
        print(f"{args.result}: cannot open ({e})", file=sys.stderr)
        return 2
    with f:
        if "schedule/frame" not in f or len(f["schedule/frame"]) == 0:
            print(f"{args.result}: no recorded schedule (run atssim run with at least one frame)", file=sys.stderr)
            return 2
        frames = f["schedule/frame"][:]
        frame = int(frames.max()) if args.frame < 0 else args.frame
        rows = frames == frame
        if not rows.any():
            print(f"{args.result}: frame {frame} has no recorded schedule (frames {frames.min()}–{frames.max()})",
                  file=sys.stderr)
            return 2
        task = f["schedule/task"][:][rows]
        device = f["schedule/device"][:][rows]
        kinds = text(f["schedule/tasks/kind"][:])
        mode = f["schedule"].attrs.get("mode", b"?")
        mode = mode.decode() if isinstance(mode, bytes) else mode
        names = text(f["devices/name"][:])
        subs = f["devices/sub_device"][:]
        wf = f["schedule/waits/frame"][:]
        waits = list(zip(f["schedule/waits/producer"][:][wf == frame], f["schedule/waits/consumer"][:][wf == frame]))
        panels = [("predicted", f["schedule/predicted_start_ms"][:][rows], f["schedule/predicted_finish_ms"][:][rows]),
                  ("measured", f["schedule/measured_start_ms"][:][rows], f["schedule/measured_finish_ms"][:][rows])]

    kind_list = sorted(set(kinds[t] for t in task))
    colour = {k: COLOURS[i % len(COLOURS)] for i, k in enumerate(kind_list)}
    lanes = sorted(set(device))
    fig, axes = plt.subplots(2, 1, figsize=(14, 2.2 + 1.1 * len(lanes) * 2), sharex=True)
    for ax, (title, start, finish) in zip(axes, panels):
        where = {}
        for t, d, s, e in zip(task, device, start, finish):
            if args.until is not None and s > args.until:
                continue
            ax.barh(d, e - s, left=s, height=0.6, color=colour[kinds[t]], edgecolor="black", linewidth=0.3)
            where[t] = (d, s, e)
        for p, c in waits:
            if p in where and c in where:
                (dp, _, ep), (dc, sc, _) = where[p], where[c]
                ax.annotate("", xy=(sc, dc + (0.3 if dc > dp else -0.3)), xytext=(ep, dp + (0.3 if dc > dp else -0.3)),
                            arrowprops=dict(arrowstyle="->", color="black", lw=0.5, alpha=0.6))
        ax.set_yticks(lanes)
        ax.set_yticklabels([f"{d}: {names[d]}" + (f" (sub-device {subs[d]})" if subs[d] >= 0 else "")
                            for d in lanes], fontsize=8)
        ax.invert_yaxis()
        ax.set_title(f"{title}: {args.result}, frame {frame}, schedule '{mode}'", fontsize=10)
    axes[-1].set_xlabel("ms from the substep's start")
    fig.legend(handles=[Patch(color=colour[k], label=k) for k in kind_list], loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
