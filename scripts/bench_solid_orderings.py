#!/usr/bin/python3
"""XPBD's StVK tets in each solver.ordering, side by side in one run.

The solid is scenes/soft_box.yaml as XPBD simulates it (material.model stvk,
solver.method xpbd: a copy with those two keys changed, written to a
temporary directory), its box cut into N x N x N cells of 6 tets. For each N
it times
  - the native host loops (bench/bench_native --shape solid): the project's
    host XPBD reference (scalar tets), and the sceptic's loop over the
    color_batches order (--loop plain --ordering color_batches: each color
    block cut into groups of 8 tets solved as 8 float lanes with GCC vector
    extensions, bench/float8_lanes.hpp tet_group8), each on one thread and
    with tbb::parallel_for per color block on two, and
  - atssim with solver.ordering colors (a work-item per tet) and
    color_batches (a work-item per batch of 8 tets of a color block, solved
    as float8 lanes: kernels/xpbd/xpbd.cl, xpbd_tet_lanes) on the whole 2-CU
    CPU device and on the two 1-CU sub-devices (cpu/2, split and heft),
    fused executor,
interleaved round by round, and prints one Markdown table: the median frame
time of each cell's fastest round, its spread over the rounds (min / median
/ max of the rounds' medians), and each cell against colors on the whole
device and against the native 2-thread loop.

usage: scripts/bench_solid_orderings.py [--sizes 12,24] [--rounds 3] [--frames 6]
Build first (scripts/test.sh or scripts/quickstart.sh).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "release", "atssim")
NATIVE = os.path.join(ROOT, "build", "release", "bench", "bench_native")
SOURCE_SCENE = os.path.join(ROOT, "scenes", "soft_box.yaml")

ORDERINGS = ["colors", "color_batches"]
DEVICES = [("whole device", "cpu", "single"), ("split", "cpu/2", "split"), ("heft", "cpu/2", "heft")]


def xpbd_scene(directory: str) -> str:
    """soft_box.yaml with the StVK model and the XPBD method."""
    with open(SOURCE_SCENE) as f:
        text = f.read()
    for old, new in (("model: neo_hookean", "model: stvk"), ("method: vbd", "method: xpbd")):
        if old not in text:
            sys.exit(f"bench_solid_orderings: {SOURCE_SCENE} no longer holds '{old}'; update this script")
        text = text.replace(old, new)
    path = os.path.join(directory, "soft_box_xpbd.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def run_native(scene: str, size: int, threads: int, frames: int, lanes: bool) -> float:
    command = [NATIVE, "--scene", scene, "--method", "xpbd", "--shape", "solid", "--resolution", str(size),
               "--threads", str(threads), "--frames", str(frames), "--warmup", "1"]
    if lanes:
        command += ["--loop", "plain", "--ordering", "color_batches"]
    return json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)["median_ms"]


def run_atssim(scene: str, size: int, ordering: str, devices: str, schedule: str, frames: int, out: str) -> float:
    command = [BIN, "run", scene, "-o", out, "--frames", str(frames + 1), "--devices", devices, "--schedule",
               schedule, "--executor", "fused", "--json", "-q", "--set", f"objects.0.box.resolution=[{size},{size},{size}]",
               "--set", f"solver.ordering={ordering}"]
    result = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
    return result["ms_per_frame"]["median"]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="12,24")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--frames", type=int, default=6)
    args = ap.parse_args()
    for binary in (BIN, NATIVE):
        if not os.access(binary, os.X_OK):
            sys.exit(f"bench_solid_orderings: {binary} is missing; build first (bash scripts/quickstart.sh)")
    sizes = [int(s) for s in args.sizes.split(",")]
    native = [("native 1 thread", (1, False)), ("native 2 threads", (2, False)),
              ("native lanes 1 thread", (1, True)), ("native lanes 2 threads", (2, True))]
    columns = [(label, None) for label, _ in native]
    columns += [(f"{label}, {ordering}", (ordering, devices, schedule)) for ordering in ORDERINGS
                for label, devices, schedule in DEVICES]
    runs = {}  # (size, column) -> [ms per round]
    with tempfile.TemporaryDirectory() as tmp:
        scene = xpbd_scene(tmp)
        out = os.path.join(tmp, "out.h5")
        for r in range(args.rounds):
            for size in sizes:
                for label, variant in columns:
                    if variant is None:
                        threads, lanes = dict(native)[label]
                        ms = run_native(scene, size, threads, args.frames, lanes)
                    else:
                        ms = run_atssim(scene, size, *variant, args.frames, out)
                    runs.setdefault((size, label), []).append(ms)
                    print(f"round {r + 1}: {size}^3 cells, {label}: {ms:.1f} ms", file=sys.stderr)
    print("| cells | tets | " + " | ".join(label for label, _ in columns) + " |")
    print("|---|---:|" + "---:|" * len(columns))
    for size in sizes:
        best = {label: min(runs[(size, label)]) for label, _ in columns}
        print(f"| {size}³ | {6 * size ** 3} | " + " | ".join(f"{best[label]:.1f}" for label, _ in columns) + " |")
    print()
    print("Spread over the rounds (min / median / max ms):")
    print()
    print("| cells | " + " | ".join(label for label, _ in columns) + " |")
    print("|---|" + "---|" * len(columns))
    for size in sizes:
        cells = []
        for label, _ in columns:
            v = runs[(size, label)]
            cells.append(f"{min(v):.1f} / {statistics.median(v):.1f} / {max(v):.1f}")
        print(f"| {size}³ | " + " | ".join(cells) + " |")
    print()
    print("Ratios (fastest rounds): time of colors on the whole device, and of the fastest native 2-thread "
          "loop, over the cell's time (above 1: the cell is faster):")
    print()
    device_columns = [label for label, variant in columns if variant is not None]
    print("| cells | " + " | ".join(device_columns) + " |")
    print("|---|" + "---|" * len(device_columns))
    for size in sizes:
        reference = min(runs[(size, "whole device, colors")])
        fastest = min(min(runs[(size, "native 2 threads")]), min(runs[(size, "native lanes 2 threads")]))
        cells = [f"{reference / min(runs[(size, label)]):.2f} / {fastest / min(runs[(size, label)]):.2f}"
                 for label in device_columns]
        print(f"| {size}³ | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
