#!/usr/bin/python3
"""XPBD's solver.ordering, colors against batches: frame time on one sub-device and the convergence effect.

For each cloth size (64x64, 128x128, 256x256 vertices of scenes/hanging_cloth.yaml),
times, side by side in one run with the variants interleaved round by round
(the fastest round counts):
  - the native host loop (bench/bench_native, XPBD, one thread) over the
    colour order and over the batches' order (--ordering batches);
  - atssim XPBD on one 1-CU pocl sub-device (cpu/2:0, schedule single) with
    each executor asked for (--executor events,fused) and each ordering, and
    fused colors on the whole 2-CU device (cpu), which batches cannot use;
then prints one Markdown table of median frame times (ms) with the ratio
colors / batches per executor, and the y_k table of `atssim converge` for
both orderings from one state (10 frames of VBD; the order changes the
Gauss-Seidel result).

usage: scripts/bench_ordering.py [--executor events,fused] [--sizes 64,128,256] [--rounds 3] [--frames 10]
                                 [--converge-size 32]
Build first (scripts/test.sh or scripts/quickstart.sh).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_devices import BIN, NATIVE, SCENE, binaries_ready, frames_for  # noqa: E402

ORDERINGS = ("colors", "batches")


def run_native(size: int, ordering: str, frames: int) -> float:
    out = subprocess.run([NATIVE, "--scene", SCENE, "--method", "xpbd", "--resolution", str(size), "--threads", "1",
                          "--frames", str(frames), "--warmup", "1", "--ordering", ordering],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["median_ms"]


def run_atssim_frames_with(size: int, ordering: str, executor: str, frames: int, out: str,
                           devices: str = "cpu/2:0") -> float:
    subprocess.run([BIN, "run", SCENE, "-o", out, "--frames", str(frames + 2), "--devices", devices, "--schedule",
                    "single", "--executor", executor, "--set", "solver.method=xpbd", "--set",
                    f"solver.ordering={ordering}", "--set", f"objects.0.grid.resolution=[{size},{size}]", "--quiet"],
                   check=True)
    with h5py.File(out, "r") as f:
        return float(np.median(f["timing/frame_ms"][3:]))  # skip the initial state and two warm-up frames


def converge_table(size: int, ordering: str, out: str) -> str:
    # The state is reached with the scene's solver.method: VBD, so that both
    # orderings start from the same state (XPBD would reach it in its own order).
    return subprocess.run([BIN, "converge", SCENE, "-o", out, "--method", "vbd", "--methods", "xpbd", "--devices",
                           "cpu/2:0", "--iterations", "64", "--frames-before", "10", "--set",
                           f"solver.ordering={ordering}", "--set",
                           f"objects.0.grid.resolution=[{size},{size}]"],
                          check=True, capture_output=True, text=True).stdout


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--executor", default="events,fused", help="comma separated: events, fused")
    ap.add_argument("--sizes", default="64,128,256")
    ap.add_argument("--rounds", type=int, default=3, help="runs per variant; the fastest median counts")
    ap.add_argument("--frames", type=int, default=10, help="timed frames at 64x64 (fewer for bigger cloths)")
    ap.add_argument("--converge-size", type=int, default=32, help="cloth size of the converge runs (0: none)")
    args = ap.parse_args()
    if not binaries_ready():
        return 2
    executors = args.executor.split(",")
    sizes = [int(s) for s in args.sizes.split(",")]
    columns = [f"native 1 thread {o}" for o in ORDERINGS] + [f"{e} {o}" for e in executors for o in ORDERINGS]
    if "fused" in executors:
        columns.append("fused colors whole device")
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.h5")
        for size in sizes:
            frames = frames_for(size, args.frames)
            cells = {}
            for _ in range(args.rounds):
                for o in ORDERINGS:
                    measured = {f"native 1 thread {o}": run_native(size, o, frames)}
                    for e in executors:
                        measured[f"{e} {o}"] = run_atssim_frames_with(size, o, e, frames, out)
                    if o == "colors" and "fused" in executors:  # colors can use both CUs; batches cannot
                        measured["fused colors whole device"] = run_atssim_frames_with(size, o, "fused", frames, out,
                                                                                        "cpu")
                    for c, v in measured.items():
                        cells[c] = min(v, cells.get(c, v))
            results[size] = cells
            print(f"measured {size}x{size}", file=sys.stderr, flush=True)
        tables = {o: converge_table(args.converge_size, o, out) for o in ORDERINGS} if args.converge_size else {}

    ratios = ["native"] + executors
    print("| cloth | " + " | ".join(columns) + " | " + " | ".join(f"{r} colors / batches" for r in ratios) + " |")
    print("|---|" + "---|" * (len(columns) + len(ratios)))
    for size, cells in results.items():
        row = [f"{cells[c]:.1f}" for c in columns]
        for r in ratios:
            key = "native 1 thread" if r == "native" else r
            row.append(f"{cells[key + ' colors'] / cells[key + ' batches']:.2f}")
        print(f"| {size}×{size} | " + " | ".join(row) + " |")
    print()
    print(f"XPBD ms per frame (16 substeps x 8 iterations), median of the timed frames, fastest of {args.rounds} "
          "interleaved rounds; devices: one 1-CU pocl sub-device (cpu/2:0), schedule single; \"whole device\": "
          "the 2-CU pocl device (cpu), which colors can use and batches cannot")
    for o, table in tables.items():
        print()
        print(f"atssim converge, {args.converge_size}x{args.converge_size}, state after 10 VBD frames, "
              f"solver.ordering={o}:")
        print("\n".join(line for line in table.rstrip().splitlines() if not line.startswith("wrote ")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
