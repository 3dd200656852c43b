#!/usr/bin/python3
"""A GPU and a CPU together: frame time of the hanging cloth, side by side in one run.

For a machine with an OpenCL GPU and an OpenCL CPU device (pocl), each on
its own platform (so each has its own memory: the events executor, copies
through the host), for each method and cloth size, times
  - the native host loop (bench/bench_native, 1 thread and a tbb::parallel_for
    per colour on every core; for XPBD also the plain loop of bench/plain_xpbd.hpp);
  - atssim on the whole CPU device (`--devices cpu`), on the GPU alone
    (`--devices gpu`), and on both (`--devices gpu,cpu`) with the split and
    heft schedules;
and prints one Markdown table of median frame times (ms; the scheduler's
prediction error and the bytes copied between the memories per frame in
parentheses), the spread over the rounds, and the ratios that matter: both
devices against the faster device alone and against the fastest native loop.
Variants are interleaved round by round; the fastest round counts.

usage: scripts/bench_hybrid.py [--methods xpbd,vbd] [--sizes 64,256,512] [--rounds 2] [--frames 10]
                               [--threads N (native loop; default: every core)]
On a machine without a GPU it says so and exits 2. Build first.
"""
import os
import signal
import subprocess
import sys
import tempfile

from bench_devices import (BIN, bench_arguments, binaries_ready, frames_for, print_cells, run_atssim_frames,
                           run_native, spread)

VARIANTS = [  # label, devices, schedule
    ("CPU device", "cpu", "single"),
    ("GPU", "gpu", "single"),
    ("GPU+CPU split", "gpu,cpu", "split"),
    ("GPU+CPU heft", "gpu,cpu", "heft"),
]


def devices_listing() -> str:
    return subprocess.run([BIN, "devices"], check=True, capture_output=True, text=True).stdout


def measure(methods, sizes, native, args, rounds) -> None:
    """Fills rounds[(method, size)][column] with (ms, error, bytes moved) per round, cell by cell."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.h5")
        for method in methods:
            for size in sizes:
                frames = frames_for(size, args.frames)
                cells = rounds.setdefault((method, size), {})
                for _ in range(args.rounds):
                    for label, loop, threads, for_methods in native:
                        if method in for_methods:
                            cells.setdefault(label, []).append(
                                (run_native(method, size, threads, frames, loop), None, None))
                    for label, devices, schedule in VARIANTS:
                        try:
                            cells.setdefault(label, []).append(
                                run_atssim_frames(method, size, "events", devices, schedule, frames, out))
                        except subprocess.CalledProcessError as e:
                            print(f"{method} {size} {label}: failed ({e})", file=sys.stderr, flush=True)
                print(f"measured {method} {size}x{size}", file=sys.stderr, flush=True)


def main() -> int:
    ap = bench_arguments("64,256,512")
    ap.add_argument("--threads", type=int, default=os.cpu_count(), help="threads of the native TBB loop")
    args = ap.parse_args()
    if not binaries_ready():
        return 2
    listing = devices_listing()
    if "— gpu," not in listing:
        print("bench_hybrid: no OpenCL GPU here (`atssim devices`):\n" + listing, file=sys.stderr)
        return 2
    methods = args.methods.split(",")
    sizes = [int(s) for s in args.sizes.split(",")]
    native = [("native 1 thread", "reference", 1, ("xpbd", "vbd")),
              (f"native TBB {args.threads} threads", "reference", args.threads, ("xpbd", "vbd")),
              (f"plain TBB {args.threads} threads", "plain", args.threads, ("xpbd",))]
    columns = [n[0] for n in native] + [v[0] for v in VARIANTS]
    rounds = {}

    def stop(*_):  # `timeout` or a batch system's TERM: print what was measured so far
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    try:
        measure(methods, sizes, native, args, rounds)
    except KeyboardInterrupt:
        print("bench_hybrid: interrupted; the tables hold the cells measured before", file=sys.stderr)
    results = {key: {c: min(v, key=lambda r: r[0]) for c, v in cells.items() if v} for key, cells in rounds.items()}

    print_cells(results, columns)
    print()
    print(f"ms per frame (16 substeps x 8 iterations), median of the timed frames, fastest of {args.rounds} "
          "interleaved rounds; in parentheses the scheduler's prediction error and the bytes copied between the "
          "GPU's and the CPU's memories per frame; events executor throughout")
    print()
    print("| method | cloth | " + " | ".join(columns) + " |")
    print("|---|---|" + "---|" * len(columns))
    for (method, size), cells in rounds.items():
        print(f"| {method.upper()} | {size}×{size} | " +
              " | ".join(spread([v[0] for v in cells[c]]) if cells.get(c) else "–" for c in columns) + " |")
    print()
    print(f"the spread: min / median / max over the {args.rounds} rounds of each cell's median frame ms")
    print()
    print("| method | cloth | GPU vs CPU device | best of both vs faster alone | best of both vs fastest native |")
    print("|---|---|---|---|---|")
    for (method, size), cells in results.items():
        ms = {c: v[0] for c, v in cells.items()}
        if not all(v[0] in ms for v in VARIANTS):
            print(f"| {method.upper()} | {size}×{size} | – | – | – |")
            continue
        both = min(ms["GPU+CPU split"], ms["GPU+CPU heft"])
        alone = min(ms["GPU"], ms["CPU device"])
        fastest_native = min(ms[n[0]] for n in native if n[0] in ms)
        print(f"| {method.upper()} | {size}×{size} | {ms['CPU device'] / ms['GPU']:.2f}× | {alone / both:.2f}× | "
              f"{fastest_native / both:.2f}× |")
    print()
    print("ratios > 1: the second is faster (time of the first over time of the second, e.g. CPU ms / GPU ms)")
    print()
    print("devices (`atssim devices`):\n```\n" + listing.rstrip() + "\n```")
    return 0


if __name__ == "__main__":
    sys.exit(main())
