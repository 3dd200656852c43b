#!/usr/bin/python3
"""Two devices against one: frame time of the hanging cloth per schedule.

For cloths of about 4k, 16k and 64k vertices, runs atssim on sub-device A
alone, sub-device B alone (the pocl CPU device split into two 1-CU
sub-devices), the whole 2-CU device, and the two sub-devices with the
`split`, `heft` and `async` schedules (async: asynchronous Gauss-Seidel,
depth 2, average displacements — not the same iteration, so compare its
accuracy in docs/accuracy.md too); prints one Markdown table with the median
frame time, the speedup of the best two-device schedule over the best single
sub-device and over the whole device, and the scheduler's prediction error
|measured - predicted| / measured substep makespan (median over frames).

usage: scripts/bench_devices.py [--frames N] [--sizes 64,128,256] [--rounds R]
Build first (scripts/test.sh or scripts/quickstart.sh).
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "release", "atssim")
SCENE = os.path.join(ROOT, "scenes", "hanging_cloth.yaml")

VARIANTS = [  # label, devices, schedule
    ("A alone", "cpu/2:0", "single"),
    ("B alone", "cpu/2:1", "single"),
    ("whole device", "cpu", "single"),
    ("split", "cpu/2", "split"),
    ("heft", "cpu/2", "heft"),
    ("async", "cpu/2", "async"),
]


def run(res: int, devices: str, schedule: str, frames: int, out: str):
    cmd = [BIN, "run", SCENE, "-o", out, "--frames", str(frames), "--devices", devices, "--schedule", schedule,
           "--set", f"objects.0.grid.resolution=[{res},{res}]", "--quiet"]
    subprocess.run(cmd, check=True)
    with h5py.File(out, "r") as f:
        frame_ms = f["timing/frame_ms"][2:]  # skip the initial state and the first (warm-up) frame
        pred = f["schedule/makespan/predicted_ms"][1:]
        meas = f["schedule/makespan/measured_ms"][1:]
        err = np.abs(meas - pred) / np.maximum(meas, 1e-9)
        return float(np.median(frame_ms)), float(np.median(err))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=12)
    ap.add_argument("--sizes", default="64,128,256")
    ap.add_argument("--rounds", type=int, default=2, help="runs per variant; the fastest median counts")
    args = ap.parse_args()
    if not os.path.exists(BIN):
        print(f"{BIN} is missing: build first (scripts/test.sh)", file=sys.stderr)
        return 2
    os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
    sizes = [int(s) for s in args.sizes.split(",")]
    header = "| vertices | " + " | ".join(f"{v[0]} ms" for v in VARIANTS) + \
             " | best 2-device vs best sub-device | vs whole device | prediction error split / heft / async |"
    print(header)
    print("|" + "---|" * (len(VARIANTS) + 4))
    with tempfile.TemporaryDirectory() as tmp:
        for res in sizes:
            ms, err = {}, {}
            for r in range(args.rounds):
                for label, devices, schedule in VARIANTS:  # interleaved, so drift hits all alike
                    t, e = run(res, devices, schedule, args.frames, os.path.join(tmp, "out.h5"))
                    if label not in ms or t < ms[label]:
                        ms[label], err[label] = t, e
            best_two = min(ms["split"], ms["heft"], ms["async"])
            best_one = min(ms["A alone"], ms["B alone"])
            row = f"| {res * res} ({res}×{res}) | " + " | ".join(f"{ms[v[0]]:.1f}" for v in VARIANTS)
            row += f" | {best_one / best_two:.2f}× | {ms['whole device'] / best_two:.2f}× |"
            row += f" {100 * err['split']:.0f} % / {100 * err['heft']:.0f} % / {100 * err['async']:.0f} % |"
            print(row, flush=True)
    print()
    print(f"frames={args.frames} rounds={args.rounds} scene=scenes/hanging_cloth.yaml "
          "(16 substeps, 8 iterations, stretch + bending); median frame time without the first frame")
    return 0


if __name__ == "__main__":
    sys.exit(main())
