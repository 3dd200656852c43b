#!/usr/bin/python3
"""Per solver method, like Table 2 of He et al. 2025: frame time on one
sub-device, on the whole device and with the best two-device schedule, and
the relative energy error each method reaches in a fixed wall-time budget
per substep (the speed/accuracy trade).

usage: scripts/bench_methods.py [--resolution 64] [--frames 8] [--budget-ms 10]
       scripts/bench_methods.py --scene scenes/pillows.yaml --set objects.1.material.model=stvk ...
Build first (scripts/test.sh). Prints one Markdown table.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "release", "atssim")
SCENE = os.path.join(ROOT, "scenes", "hanging_cloth.yaml")


def registry():
    """The methods atssim knows (its method registry, `atssim methods --json`)."""
    out = subprocess.run([BIN, "methods", "--json"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def frame_ms(scene, sets, method, devices, schedule, frames, out):
    subprocess.run([BIN, "run", scene, "-o", out, "--frames", str(frames), "--devices", devices, "--schedule",
                    schedule, "--set", f"solver.method={method}", *sets, "--quiet"], check=True)
    with h5py.File(out, "r") as f:
        return float(np.median(f["timing/frame_ms"][2:]))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--resolution", type=int, default=64)
    ap.add_argument("--frames", type=int, default=8)
    ap.add_argument("--budget-ms", type=float, default=10.0, help="wall time per substep for the accuracy column")
    ap.add_argument("--iterations", type=int, default=128, help="largest k tried for the accuracy column")
    ap.add_argument("--frames-before", type=int, default=10, help="frames simulated before the accuracy substep")
    ap.add_argument("--scene", default=SCENE, help="scene file (default: the hanging cloth, resized)")
    ap.add_argument("--methods", default="", help="comma separated (default: every method of `atssim methods`)")
    ap.add_argument("--set", action="append", default=[], help="scene override KEY=VALUE for every run (repeatable)")
    args = ap.parse_args()
    if not os.path.exists(BIN):
        print(f"{BIN} is missing: build first (scripts/test.sh)", file=sys.stderr)
        return 2
    known = registry()
    gauss_seidel = {m["name"] for m in known if m["iterations"] == "gauss_seidel"}  # async relaxes these only
    methods = args.methods.split(",") if args.methods else [m["name"] for m in known]
    # --resolution resizes the default scene's grid; other scenes run as written.
    sets = ["--set", f"objects.0.grid.resolution=[{args.resolution},{args.resolution}]"] if args.scene == SCENE else []
    for kv in args.set:
        sets += ["--set", kv]
    os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
    print(f"| method | one sub-device ms | whole device ms | best two-device ms (schedule) | vs sub-device | "
          f"vs whole | y within {args.budget_ms:g} ms/substep (k) |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.h5")
        conv = os.path.join(tmp, "conv.h5")
        subprocess.run([BIN, "converge", args.scene, "-o", conv, "--devices", "cpu/2", "--methods", ",".join(methods),
                        "--schedules", "single,heft", "--iterations", str(args.iterations), "--frames-before", str(args.frames_before),
                        *sets], check=True, stdout=subprocess.DEVNULL)
        with h5py.File(conv, "r") as f:
            c = f["convergence"]
            best = {}
            for m in methods:
                choice = None
                for sched in ["single", "heft"]:
                    g = c[f"{m}:{sched}"]
                    for k, y, t in zip(g["iterations"][:], g["relative_error"][:], g["time_ms"][:]):
                        if t <= args.budget_ms and (choice is None or y < choice[0]):
                            choice = (y, int(k), sched)
                best[m] = choice
        for m in methods:
            one = frame_ms(args.scene, sets, m, "cpu/2:0", "single", args.frames, out)
            whole = frame_ms(args.scene, sets, m, "cpu", "single", args.frames, out)
            schedules = ["split", "heft"] + (["async"] if m in gauss_seidel else [])
            two = {s: frame_ms(args.scene, sets, m, "cpu/2", s, args.frames, out) for s in schedules}
            s_best = min(two, key=two.get)
            acc = best[m]
            acc_text = f"{acc[0]:.3g} (k={acc[1]}, {acc[2]})" if acc else "– (no k fits)"
            print(f"| {m} | {one:.1f} | {whole:.1f} | {two[s_best]:.1f} ({s_best}) | {one / two[s_best]:.2f}× | "
                  f"{whole / two[s_best]:.2f}× | {acc_text} |", flush=True)
    print()
    what = f"hanging cloth {args.resolution}×{args.resolution}" if args.scene == SCENE else os.path.basename(args.scene)
    print(f"{what}, the scene's substeps and iterations for the frame times; "
          f"accuracy from `atssim converge` (single and heft on cpu/2, k = 1, 2, 4, …, {args.iterations})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
