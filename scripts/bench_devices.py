#!/usr/bin/python3
"""Devices against the native loop: frame time of the hanging cloth, side by side in one run.

For each method (XPBD, VBD; JPGD, which has no native loop, on the devices
only) and cloth size (64x64, 128x128, 256x256 vertices),
times
  - the native host loop a user would write instead (bench/bench_native: the
    project's host reference on one thread, and with tbb::parallel_for per
    color block on two threads, both compiled -O3 -march=native), and for
    XPBD the sceptic's baseline beside it (bench_native --loop plain:
    bench/plain_xpbd.hpp, the same per-color parallel_for written apart from
    the reference; the batches ordering with float8 lanes on 1 thread,
    bench/plain_xpbd_batches.hpp; and the color_batches ordering, the color
    blocks cut into groups of 8 float8 lanes, on 1 thread and with a
    parallel_for per block on 2, bench/plain_xpbd_color_batches.hpp); for VBD
    the reference's color_batches loop beside it (each color's vertices in
    batches of 8 whose gather runs as 8-float vectors, on 1 and 2 threads);
  - atssim with each executor asked for (--executor events,fused) on one
    1-CU sub-device (cpu/2:0), the whole 2-CU device (cpu), and the two
    sub-devices with the split and heft schedules (cpu/2); again with each
    other solver.ordering asked for (color_batches: XPBD and VBD;
    vertex_batches: JPGD, whose one-vertex ordering runs in the colors'
    columns) (--orderings colors,color_batches: the columns repeated with the
    ordering's name after them);
and prints one Markdown table of median frame times (ms; the prediction error
|measured - predicted| / measured substep makespan, median over frames, in
parentheses), a second with each cell's spread over the rounds (min / median
/ max), then the issue's targets checked against those numbers. Variants are
interleaved round by round so that drift hits them alike; the fastest round
counts in the first table.

usage: scripts/bench_devices.py [--executor events,fused|none] [--methods xpbd,vbd]
                                [--orderings colors,color_batches] [--sizes 64,128,256] [--rounds 2] [--frames 10]
Build first (scripts/test.sh or scripts/quickstart.sh).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "release", "atssim")
NATIVE = os.path.join(ROOT, "build", "release", "bench", "bench_native")
ROOFLINE = os.path.join(ROOT, "build", "release", "bench", "bench_roofline")
SCENE = os.path.join(ROOT, "scenes", "hanging_cloth.yaml")

DEVICE_VARIANTS = [  # label, devices, schedule
    ("1 sub-device", "cpu/2:0", "single"),
    ("whole device", "cpu", "single"),
    ("split", "cpu/2", "split"),
    ("heft", "cpu/2", "heft"),
]


def bench_arguments(sizes: str) -> argparse.ArgumentParser:
    """The options every device benchmark takes (the caller's docstring describes it)."""
    ap = argparse.ArgumentParser(description=sys.modules["__main__"].__doc__.splitlines()[0])
    ap.add_argument("--methods", default="xpbd,vbd")
    ap.add_argument("--sizes", default=sizes)
    ap.add_argument("--rounds", type=int, default=2, help="runs per variant; the fastest median counts")
    ap.add_argument("--frames", type=int, default=10, help="timed frames at 64x64 (fewer for bigger cloths)")
    return ap


def binaries_ready() -> bool:
    """Whether atssim and the native reference are built; sets the pocl kernel cache."""
    for path in (BIN, NATIVE):
        if not os.path.exists(path):
            print(f"{path} is missing: build first (scripts/test.sh)", file=sys.stderr)
            return False
    os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
    return True


def frames_for(size: int, frames: int) -> int:
    """Fewer frames for the big cloths (each frame of 256x256 VBD takes seconds)."""
    return max(3, frames * 64 // size) if size > 64 else frames


def run_native(method: str, size: int, threads: int, frames: int, loop: str = "reference",
               ordering: str = "colors") -> float:
    """Median frame ms of bench_native (loop: the project's host reference, or plain: bench/plain_xpbd*.hpp)."""
    command = [NATIVE, "--scene", SCENE, "--method", method, "--resolution", str(size), "--threads", str(threads),
               "--frames", str(frames), "--warmup", "1"]
    if loop != "reference":
        command += ["--loop", loop]
    if ordering != "colors":
        command += ["--ordering", ordering]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    run = json.loads(out)
    COUNTS[(method, size)] = run
    return run["median_ms"]


COUNTS = {}  # (method, size) -> bench_native's last JSON (the sizes the roofline counts with)

# The roofline's work per visit, counted by hand from the kernels' operations
# (bytes: every load and store of the visit, cache hits not discounted;
# flops: each add, multiply, divide and square root as one):
#   stretch, undamped (common/xpbd_distance.h): the 20-byte record, lambda
#     read and written (8), two float4 particles read and written (64);
#     36 flops;
#   isometric bending (common/xpbd_bending.h): the 48-byte record, 3 lambdas
#     read and written (24), four particles read and written (128); 92 flops;
#   per particle and substep, predict and the velocity update
#     (common/particle_steps.cl): x, v read, x_prev, v, x written (80), x,
#     x_prev read, v written (48); 18 flops.
XPBD_VISIT = {"stretch": (92, 36), "bend": (200, 92), "particle": (128, 18)}


def xpbd_frame_work(counts: dict):
    """Bytes and flops of one XPBD frame (cloth: stretch and bending, no tets)."""
    per_iteration = [counts[k] * XPBD_VISIT[k][i] for k in ("stretch", "bend") for i in (0, 1)]
    bytes_ = counts["substeps"] * (counts["iterations"] * (per_iteration[0] + per_iteration[2]) +
                                   counts["vertices"] * XPBD_VISIT["particle"][0])
    flops = counts["substeps"] * (counts["iterations"] * (per_iteration[1] + per_iteration[3]) +
                                  counts["vertices"] * XPBD_VISIT["particle"][1])
    return bytes_, flops


def run_atssim_frames(method: str, size: int, executor: str, devices: str, schedule: str, frames: int, out: str,
                     memory: str = "shared", ordering: str = "colors"):
    """Median frame ms, median prediction error and median bytes copied between memories per frame."""
    command = [BIN, "run", SCENE, "-o", out, "--frames", str(frames + 2), "--devices", devices, "--schedule", schedule,
               "--executor", executor, "--memory", memory, "--set", f"solver.method={method}", "--set",
               f"objects.0.grid.resolution=[{size},{size}]", "--quiet"]
    if method in ("xpbd", "vbd"):  # solver.ordering is set, colors too (XPBD's default depends on the size)
        command += ["--set", f"solver.ordering={ordering}"]
    if method == "jpgd":  # its one-vertex ordering stands in the colors' columns
        command += ["--set", f"solver.ordering={'vertices' if ordering == 'colors' else ordering}"]
    subprocess.run(command, check=True)
    with h5py.File(out, "r") as f:
        frame_ms = f["timing/frame_ms"][3:]  # skip the initial state and two warm-up frames
        pred = f["schedule/makespan/predicted_ms"][2:]
        meas = f["schedule/makespan/measured_ms"][2:]
        moved = f["schedule/makespan/bytes_moved"][2:]
        err = np.abs(meas - pred) / np.maximum(meas, 1e-9)
        return float(np.median(frame_ms)), float(np.median(err)), float(np.median(moved))


def run_atssim(method: str, size: int, executor: str, devices: str, schedule: str, frames: int, out: str,
               ordering: str = "colors"):
    return run_atssim_frames(method, size, executor, devices, schedule, frames, out, ordering=ordering)[:2]


NATIVE_VARIANTS = [  # label, loop, threads, ordering, methods
    ("native 1 thread", "reference", 1, "colors", ("xpbd", "vbd")),
    ("native TBB 2 threads", "reference", 2, "colors", ("xpbd", "vbd")),
    ("plain 1 thread", "plain", 1, "colors", ("xpbd",)),
    ("plain TBB 2 threads", "plain", 2, "colors", ("xpbd",)),
    ("plain batches float8 1 thread", "plain", 1, "batches", ("xpbd",)),
    ("plain color batches float8 1 thread", "plain", 1, "color_batches", ("xpbd",)),
    ("plain color batches float8 TBB 2 threads", "plain", 2, "color_batches", ("xpbd",)),
    ("native color batches float8 1 thread", "reference", 1, "color_batches", ("vbd",)),
    ("native color batches float8 TBB 2 threads", "reference", 2, "color_batches", ("vbd",)),
]


ORDERING_METHODS = {  # solver.ordering -> the methods that take it (JPGD's vertices run in the colors' columns)
    "colors": ("xpbd", "vbd", "jpgd"), "color_batches": ("xpbd", "vbd"), "batches": ("xpbd",),
    "vertex_batches": ("jpgd",)}


def device_columns(executors, orderings):
    """(column, executor, devices, schedule, ordering, methods) of each atssim run: every executor on every
    DEVICE_VARIANTS row, for colors as before and for each other ordering under its name (ORDERING_METHODS)."""
    return [(f"{e} {label}" + ("" if o == "colors" else f" {o}"), e, devices, schedule, o, ORDERING_METHODS[o])
            for o in orderings for e in executors for label, devices, schedule in DEVICE_VARIANTS]


def cell_text(cell) -> str:
    """ms, then in parentheses what else the cell holds: (ms, prediction error or None[, bytes moved])."""
    ms, err, *rest = cell
    extra = [] if err is None else [f"{100 * err:.0f} %"]
    if rest and rest[0]:
        extra.append(f"{rest[0] / 2**20:.2f} MiB")
    return f"{ms:.1f}" + (f" ({', '.join(extra)})" if extra else "")


def print_cells(results: dict, columns) -> None:
    """One Markdown row per (method, size): each column's cell, '–' where it was not measured."""
    print("| method | cloth | " + " | ".join(columns) + " |")
    print("|---|---|" + "---|" * len(columns))
    for (method, size), cells in results.items():
        row = [cell_text(cells[c]) if c in cells else "–" for c in columns]
        print(f"| {method.upper()} | {size}×{size} | " + " | ".join(row) + " |")


def spread(values) -> str:
    """min / median / max of a cell's rounds."""
    return f"{min(values):.1f} / {statistics.median(values):.1f} / {max(values):.1f}"


def print_roofline(machine: dict, results: dict, device, native) -> None:
    """% of limit: the time the machine's limits allow for a frame's bytes and flops over the measured time."""
    print()
    print(f"machine (bench/bench_roofline, 2 threads): stream triad {machine['triad_memory_gbs_n']:.1f} GB/s from "
          f"memory, {machine['triad_cache_gbs_n']:.1f} GB/s inside the last-level cache, FMA peak "
          f"{machine['fma_gflops_n']:.1f} GFLOP/s (1 thread: {machine['triad_memory_gbs_1']:.1f}, "
          f"{machine['triad_cache_gbs_1']:.1f} GB/s, {machine['fma_gflops_1']:.1f} GFLOP/s)")
    print()
    two_core = [n[0] for n in native if n[2] == 2] + [d[0] for d in device if d[2] != "cpu/2:0"]
    print("| method | cloth | MB / frame | MFLOP / frame | memory limit ms | cache limit ms | flop limit ms | "
          + " | ".join(f"{c}: % of memory limit / % of cache limit" for c in two_core) + " |")
    print("|---|---|---|---|---|---|---|" + "---|" * len(two_core))
    for (method, size), cells in results.items():
        if method != "xpbd" or (method, size) not in COUNTS:
            continue
        bytes_, flops = xpbd_frame_work(COUNTS[(method, size)])
        memory_ms = bytes_ / (machine["triad_memory_gbs_n"] * 1e9) * 1e3
        cache_ms = bytes_ / (machine["triad_cache_gbs_n"] * 1e9) * 1e3
        flop_ms = flops / (machine["fma_gflops_n"] * 1e9) * 1e3
        row = [f"{100 * max(memory_ms, flop_ms) / cells[c][0]:.0f} / {100 * max(cache_ms, flop_ms) / cells[c][0]:.0f}"
               if c in cells else "–" for c in two_core]
        print(f"| XPBD | {size}×{size} | {bytes_ / 1e6:.0f} | {flops / 1e6:.0f} | {memory_ms:.1f} | {cache_ms:.1f} | "
              f"{flop_ms:.1f} | " + " | ".join(row) + " |")
    print()
    print("% of limit = max(bytes / bandwidth, flops / peak) / measured frame ms, with the 2-thread limits; the "
          "bytes count every load and store of a visit (scripts/bench_devices.py XPBD_VISIT)")


def main() -> int:
    ap = bench_arguments("64,128,256")
    ap.add_argument("--executor", default="events,fused",
                    help="comma separated: events, fused; none: the native loops alone")
    ap.add_argument("--orderings", default="colors",
                    help="comma separated solver.ordering values for the atssim runs (colors, color_batches: XPBD, VBD; "
                    "batches: XPBD; vertex_batches: JPGD, whose vertices run as colors); "
                    "each but colors repeats the device columns with its name after them")
    ap.add_argument("--roofline", action="store_true", help="XPBD: also run bench/bench_roofline and print the "
                    "fraction of the machine's limits each loop reaches")
    args = ap.parse_args()
    unknown = [o for o in args.orderings.split(",") if o not in ORDERING_METHODS]
    if unknown:
        ap.error(f"--orderings: unknown {', '.join(unknown)}; use {', '.join(ORDERING_METHODS)}")
    if not binaries_ready():
        return 2
    machine = None
    if args.roofline:
        machine = json.loads(subprocess.run([ROOFLINE, "--threads", "2"], check=True, capture_output=True,
                                            text=True).stdout)
    executors = [] if args.executor == "none" else args.executor.split(",")
    methods = args.methods.split(",")
    sizes = [int(s) for s in args.sizes.split(",")]
    native = [v for v in NATIVE_VARIANTS if any(m in v[4] for m in methods)]
    device = [d for d in device_columns(executors, args.orderings.split(",")) if any(m in d[5] for m in methods)]
    columns = [v[0] for v in native] + [d[0] for d in device]
    rounds = {}  # (method, size) -> column -> [(ms, error or None) per round]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.h5")
        for method in methods:
            for size in sizes:
                frames = frames_for(size, args.frames)
                cells = {}
                for _ in range(args.rounds):
                    measured = {}
                    for label, loop, threads, ordering, for_methods in native:
                        if method in for_methods:
                            measured[label] = (run_native(method, size, threads, frames, loop, ordering), None)
                    for column, e, devices, schedule, ordering, for_methods in device:
                        if method in for_methods:
                            measured[column] = run_atssim(method, size, e, devices, schedule, frames, out, ordering)
                    for c, v in measured.items():
                        cells.setdefault(c, []).append(v)
                rounds[(method, size)] = cells
                print(f"measured {method} {size}x{size}", file=sys.stderr, flush=True)
    # The fastest round of each cell (its prediction error with it).
    results = {key: {c: min(v, key=lambda r: r[0]) for c, v in cells.items()} for key, cells in rounds.items()}

    print_cells(results, columns)
    print()
    print(f"ms per frame (16 substeps x 8 iterations), median of the timed frames, fastest of {args.rounds} "
          f"interleaved rounds; in parentheses the scheduler's prediction error")
    print()
    print("| method | cloth | " + " | ".join(columns) + " |")
    print("|---|---|" + "---|" * len(columns))
    for (method, size), cells in rounds.items():
        row = [spread([v[0] for v in cells[c]]) if c in cells else "–" for c in columns]
        print(f"| {method.upper()} | {size}×{size} | " + " | ".join(row) + " |")
    print()
    print(f"the spread: min / median / max over the {args.rounds} rounds of each cell's median frame ms")
    if "plain 1 thread" in columns:
        print()
        print("| method | cloth | native 1 thread / plain 1 thread (<= 1.1) | native TBB 2 / plain TBB 2 (<= 1.1) |")
        print("|---|---|---|---|")
        for (method, size), cells in results.items():
            if "plain 1 thread" not in cells:
                continue
            r1 = cells["native 1 thread"][0] / cells["plain 1 thread"][0]
            r2 = cells["native TBB 2 threads"][0] / cells["plain TBB 2 threads"][0]
            print(f"| {method.upper()} | {size}×{size} | {r1:.2f}{' ✓' if r1 <= 1.1 else ' ✗'} | "
                  f"{r2:.2f}{' ✓' if r2 <= 1.1 else ' ✗'} |")
    if machine is not None:
        print_roofline(machine, results, device, native)
    if "fused" not in executors or "colors" not in args.orderings.split(",") or not native:
        return 0  # (JPGD alone: no native loop to hold the targets against)
    print()
    print("| method | cloth | ordering | fused 1 sub vs events 1 sub (>= 2x at 64) | fused 1 sub / native 1 thread "
          "(<= 1.2 at 64, 256) | best two-sub fused vs fused 1 sub (>= 1.6x at 64, 1.8x above) | vs fused whole "
          "device, same ordering (>= 1; rounds that hold) | vs fused whole device, colors (>= 1) | vs fastest "
          "native loop on 2 cores (>= 1.1) | worst prediction error (<= 10 %) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for (method, size), cells in results.items():
        for ordering in args.orderings.split(","):
            suffix = "" if ordering == "colors" else f" {ordering}"
            if f"fused 1 sub-device{suffix}" not in cells or "native 1 thread" not in cells:
                continue  # JPGD has no native loop: its cells are in the tables above
            fused_one = cells[f"fused 1 sub-device{suffix}"][0]
            two = min(cells[f"fused split{suffix}"][0], cells[f"fused heft{suffix}"][0])
            whole = cells[f"fused whole device{suffix}"][0]
            events_one = cells["events 1 sub-device" + suffix][0] if "events" in executors else float("nan")
            worst = max(v[1] for c, v in cells.items()
                        if v[1] is not None and c.endswith(suffix) and (suffix or not c.endswith("batches")))
            per_round = rounds[(method, size)]
            held = sum(w[0] >= min(sp[0], h[0]) for w, sp, h in zip(per_round[f"fused whole device{suffix}"],
                                                                     per_round[f"fused split{suffix}"],
                                                                     per_round[f"fused heft{suffix}"]))
            fastest_native = min(cells[n[0]][0] for n in native if n[0] in cells)  # any native loop, 1 or 2 threads

            def mark(value, ok):
                return f"{value:.2f}{' ✓' if ok else ' ✗'}"
            need_two = 1.6 if size <= 64 else 1.8
            r1 = events_one / fused_one
            print(f"| {method.upper()} | {size}×{size} | {ordering} | " + " | ".join([
                mark(r1, r1 >= 2.0 or size != 64) if "events" in executors else "–",
                mark(fused_one / cells["native 1 thread"][0], fused_one / cells["native 1 thread"][0] <= 1.2 or
                     size not in (64, 256)),
                mark(fused_one / two, fused_one / two >= need_two),
                mark(whole / two, whole / two >= 1.0) + f" ({held}/{len(per_round[f'fused split{suffix}'])})",
                mark(cells["fused whole device"][0] / two, cells["fused whole device"][0] / two >= 1.0),
                mark(fastest_native / two, fastest_native / two >= 1.1),
                f"{100 * worst:.0f} %{' ✓' if worst <= 0.10 else ' ✗'}"]) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
