#!/usr/bin/python3
"""Seed 001's comparison on our sizes (issue #13): explicit integration of
mass-spring bodies, frame time side by side in one run.

For the mass-spring cloth (scenes/spring_cloth.yaml, grid N x N) and the
tetrahedral mass-spring box (scenes/spring_box.yaml, N^3 cells) at several
sizes, and each integrator (semi_euler, midpoint, rk4), times
  - the native host loop (bench/bench_native --method explicit: the explicit
    host reference, -O3 -march=native) on 1 thread and on 2 TBB threads;
  - atssim on one 1-CU sub-device (cpu/2:0), the whole device (cpu) and the
    two sub-devices with the split schedule (cpu/2);
each at the substeps per frame the stability limit asks for at that size
(found by asking atssim: a refused run names them). Prints a Markdown table
of median frame times (ms) and the ratios to the native 1-thread row.

With --trade it instead prints the speed/accuracy trade on one mass-spring
scene (the cloth at --trade-size): every method at several substep counts,
its error (RMS distance of the particles after --trade-frames frames from a
reference run: RK4 at 16x the smallest substep count used), against its
time per frame.

usage: scripts/bench_explicit.py [--cloth 32,64,128] [--solid 6,10,14] [--frames 5]
       scripts/bench_explicit.py --trade [--trade-size 32] [--trade-frames 30]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "release", "atssim")
NATIVE = os.path.join(ROOT, "build", "release", "bench", "bench_native")
SCENES = {"cloth": os.path.join(ROOT, "scenes", "spring_cloth.yaml"),
          "solid": os.path.join(ROOT, "scenes", "spring_box.yaml")}
DEVICE_VARIANTS = [("1 sub-device", "cpu/2:0", "single"), ("whole device", "cpu", "single"),
                   ("2 sub-devices (split)", "cpu/2", "split")]
INTEGRATORS = ["semi_euler", "midpoint", "rk4"]


def size_set(shape, n):
    return f"objects.0.grid.resolution=[{n},{n}]" if shape == "cloth" else f"objects.0.box.resolution=[{n},{n},{n}]"


def atssim(shape, sets, out, frames, devices="cpu", schedule="single", check=True):
    cmd = [BIN, "run", SCENES[shape], "-o", out, "--frames", str(frames), "--devices", devices, "--schedule",
           schedule, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    return subprocess.run(cmd, capture_output=True, text=True, check=check)


def stable_substeps(shape, n, integrator, tmp):
    """The scene's substeps, or those the stability limit asks for (with 10 % to spare)."""
    sets = [size_set(shape, n), "solver.method=explicit", f"solver.integrator={integrator}"]
    r = atssim(shape, sets, os.path.join(tmp, "probe.h5"), 1, check=False)
    if r.returncode == 0:
        with open(SCENES[shape]) as f:
            return int(re.search(r"substeps:\s*(\d+)", f.read()).group(1))
    m = re.search(r"substeps ≥ (\d+)", r.stderr)
    if not m:
        raise RuntimeError(r.stderr)
    return int(int(m.group(1)) * 1.1) + 1


def frame_ms(out, skip=2):
    with h5py.File(out, "r") as f:
        return float(np.median(f["timing/frame_ms"][1 + skip:]))


def native(shape, n, integrator, threads, substeps, frames):
    out = subprocess.run([NATIVE, "--scene", SCENES[shape], "--method", "explicit", "--integrator", integrator,
                          "--shape", shape, "--resolution", str(n), "--threads", str(threads), "--substeps",
                          str(substeps), "--frames", str(frames), "--warmup", "1"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["median_ms"]


def seed001(args):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.h5")
        for shape, sizes in (("cloth", args.cloth), ("solid", args.solid)):
            for n in [int(s) for s in sizes.split(",") if s]:
                for integrator in INTEGRATORS:
                    substeps = stable_substeps(shape, n, integrator, tmp)
                    sets = [size_set(shape, n), "solver.method=explicit", f"solver.integrator={integrator}",
                            f"simulation.substeps={substeps}"]
                    cells = {"native 1 thread": native(shape, n, integrator, 1, substeps, args.frames),
                             "native TBB 2 threads": native(shape, n, integrator, 2, substeps, args.frames)}
                    for label, devices, schedule in DEVICE_VARIANTS:
                        atssim(shape, sets, out, args.frames + 2, devices, schedule)
                        cells[label] = frame_ms(out)
                    rows.append((shape, n, integrator, substeps, cells))
                    print(f"measured {shape} {n} {integrator}", file=sys.stderr, flush=True)
    columns = ["native 1 thread", "native TBB 2 threads"] + [v[0] for v in DEVICE_VARIANTS]
    print("| body | size | integrator | substeps | " + " | ".join(columns) + " |")
    print("|---|---|---|---|" + "---|" * len(columns))
    for shape, n, integrator, substeps, cells in rows:
        size = f"{n}×{n}" if shape == "cloth" else f"{n}³ cells"
        base = cells["native 1 thread"]
        vals = [f"{cells['native 1 thread']:.1f}"] + [f"{cells[c]:.1f} ({base / cells[c]:.2f}×)" for c in columns[1:]]
        print(f"| {shape} | {size} | {integrator} | {substeps} | " + " | ".join(vals) + " |")
    print()
    print(f"ms per frame, median of {args.frames} timed frames (native: after 1 warm-up frame; atssim: after 2); "
          "in parentheses the speed-up over the native 1-thread loop")


def trade(args):
    n = args.trade_size
    with tempfile.TemporaryDirectory() as tmp:
        base = stable_substeps("cloth", n, "semi_euler", tmp)
        variants = []
        for integrator in INTEGRATORS:
            s0 = stable_substeps("cloth", n, integrator, tmp)
            for s in (s0, 2 * s0, 4 * s0):
                variants.append((f"explicit {integrator}", s, ["solver.method=explicit",
                                                               f"solver.integrator={integrator}"]))
        for method in ("xpbd", "vbd", "sosd", "jpgd"):
            for s in (max(1, base // 16), max(1, base // 4), base):
                variants.append((f"{method} (8 iterations)", s, [f"solver.method={method}"]))
        finest = max(s for _, s, _ in variants)
        ref = os.path.join(tmp, "ref.h5")
        atssim("cloth", [size_set("cloth", n), "solver.method=explicit", "solver.integrator=rk4",
                         f"simulation.substeps={16 * finest}"], ref, args.trade_frames)
        with h5py.File(ref, "r") as f:
            x_ref = f["frames/positions"][args.trade_frames].astype(np.float64)
        print(f"| variant | substeps per frame | ms per frame | RMS error after {args.trade_frames} frames (m) |")
        print("|---|---|---|---|")
        out = os.path.join(tmp, "out.h5")
        for name, s, sets in variants:
            r = atssim("cloth", [size_set("cloth", n), f"simulation.substeps={s}"] + sets, out, args.trade_frames,
                       check=False)
            if r.returncode != 0:
                print(f"| {name} | {s} | refused or failed: {r.stderr.strip()[:120]} | |")
                continue
            with h5py.File(out, "r") as f:
                x = f["frames/positions"][args.trade_frames].astype(np.float64)
                ms = float(np.median(f["timing/frame_ms"][3:]))
            err = float(np.sqrt(np.mean(np.sum((x - x_ref) ** 2, axis=1))))
            print(f"| {name} | {s} | {ms:.2f} | {err:.3g} |", flush=True)
        print()
        print(f"cloth {n}×{n} (scenes/spring_cloth.yaml), reference: explicit RK4 at {16 * finest} substeps per "
              f"frame (16× the finest variant's {finest}); one whole CPU device")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cloth", default="32,64,128")
    ap.add_argument("--solid", default="6,10,14")
    ap.add_argument("--frames", type=int, default=5)
    ap.add_argument("--trade", action="store_true")
    ap.add_argument("--trade-size", type=int, default=32)
    ap.add_argument("--trade-frames", type=int, default=30)
    args = ap.parse_args()
    for path in (BIN, NATIVE):
        if not os.path.exists(path):
            print(f"{path} is missing: build first (scripts/test.sh)", file=sys.stderr)
            return 2
    os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
    trade(args) if args.trade else seed001(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
