#!/usr/bin/python3
"""Shared against separate memory on the two sub-devices, side by side in one run.

For each method (XPBD, VBD) and cloth size (64x64, 256x256 vertices), times
  - the native host loop on one thread (bench/bench_native, -O3 -march=native);
  - atssim on one 1-CU sub-device (cpu/2:0, events executor);
  - the two sub-devices (cpu/2) with the split and heft schedules, with the
    devices sharing SVM (--memory shared) and with every device its own
    memory (--memory separate: copies through the host between them), both
    with the events executor (the fused one needs a shared memory), and
    shared with the fused executor for reference;
and prints one Markdown table: median frame ms, the scheduler's prediction
error (|measured - predicted| / measured substep makespan, median) and, for
separate memories, the bytes copied per frame. Variants are interleaved round
by round; the fastest round counts.

usage: scripts/bench_memory.py [--methods xpbd,vbd] [--sizes 64,256] [--rounds 2] [--frames 10]
Build first (scripts/test.sh or scripts/quickstart.sh).
"""
import os
import sys
import tempfile

from bench_devices import bench_arguments, binaries_ready, frames_for, run_atssim_frames, run_native

VARIANTS = [  # label, devices, schedule, executor, memory
    ("events 1 sub-device", "cpu/2:0", "single", "events", "shared"),
    ("split shared", "cpu/2", "split", "events", "shared"),
    ("split separate", "cpu/2", "split", "events", "separate"),
    ("heft shared", "cpu/2", "heft", "events", "shared"),
    ("heft separate", "cpu/2", "heft", "events", "separate"),
    ("fused heft shared", "cpu/2", "heft", "fused", "shared"),
]


def mib(b: float) -> str:
    return f"{b / 2**20:.2f} MiB"


def main() -> int:
    args = bench_arguments("64,256").parse_args()
    if not binaries_ready():
        return 2
    methods = args.methods.split(",")
    sizes = [int(s) for s in args.sizes.split(",")]
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.h5")
        for method in methods:
            for size in sizes:
                frames = frames_for(size, args.frames)
                cells = {}
                for _ in range(args.rounds):
                    measured = {"native 1 thread": (run_native(method, size, 1, frames), None, None)}
                    for label, devices, schedule, executor, memory in VARIANTS:
                        measured[label] = run_atssim_frames(method, size, executor, devices, schedule, frames, out,
                                                            memory)
                    for c, v in measured.items():
                        if c not in cells or v[0] < cells[c][0]:
                            cells[c] = v
                results[(method, size)] = cells
                print(f"measured {method} {size}x{size}", file=sys.stderr, flush=True)

    columns = ["native 1 thread"] + [v[0] for v in VARIANTS]
    print("| method | cloth | " + " | ".join(columns) + " |")
    print("|---|---|" + "---|" * len(columns))
    for (method, size), cells in results.items():
        row = []
        for c in columns:
            ms, err, moved = cells[c]
            text = f"{ms:.1f}"
            if err is not None:
                text += f" ({100 * err:.0f} %"
                text += f", {mib(moved)})" if "separate" in c else ")"
            row.append(text)
        print(f"| {method.upper()} | {size}×{size} | " + " | ".join(row) + " |")
    print()
    print(f"ms per frame (16 substeps x 8 iterations), median of the timed frames, fastest of {args.rounds} "
          "interleaved rounds; in parentheses the prediction error and, for separate memories, the bytes copied "
          "between the memories per frame")
    print()
    print("| method | cloth | split separate / shared | heft separate / shared | heft separate vs 1 sub-device |")
    print("|---|---|---|---|---|")
    for (method, size), cells in results.items():
        print(f"| {method.upper()} | {size}×{size} | {cells['split separate'][0] / cells['split shared'][0]:.2f} | "
              f"{cells['heft separate'][0] / cells['heft shared'][0]:.2f} | "
              f"{cells['events 1 sub-device'][0] / cells['heft separate'][0]:.2f}× |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
