#!/usr/bin/python3
"""Task merging at run time (solver.task_merging, paper §4.1.1): its gain, side by side in one run.

For scenes whose colour blocks are small (the hanging cloth at 32x32 and
64x64, the mesh tablecloth), each executor (events: a hop between the
sub-devices costs an event, 10-37 us here; fused: an SVM handshake,
~0.05 us), runs `--schedule heft` on the two 1-CU sub-devices (cpu/2) with
solver.task_merging auto and off, interleaved round by round, and prints
  - the median frame ms of each (frames after the first two), auto / off;
  - the median measured substep makespan of each (/schedule/makespan);
  - in how many recorded frames the schedule merged blocks, and HEFT's
    predicted makespan with the merge against without it (the gain the run
    expected when it chose).
Results never differ (the merges change only where and in what order the
tasks run); the test suite checks that.

usage: scripts/bench_merging.py [--cases cloth32,cloth64,mesh] [--executors events,fused] [--rounds 3]
                                [--frames 20]
Build first (cmake --build --preset release).
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
CASES = {
    "cloth32": ("scenes/hanging_cloth.yaml", ["objects.0.grid.resolution=[32,32]"]),
    "cloth64": ("scenes/hanging_cloth.yaml", []),
    "mesh": ("scenes/mesh_cloth.yaml", []),
}


def run(case: str, executor: str, merging: str, frames: int, out: str) -> dict:
    scene, sets = CASES[case]
    cmd = [BIN, "run", os.path.join(ROOT, scene), "-o", out, "--frames", str(frames), "--devices", "cpu/2",
           "--schedule", "heft", "--executor", executor, "--set", f"solver.task_merging={merging}", "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True)
    with h5py.File(out, "r") as f:
        frame_ms = f["timing/frame_ms"][3:]
        s = f["schedule"]
        row_frame, group = s["frame"][:], s["merge_group"][:]
        merged_frames = sorted({int(k) for k in row_frame[group >= 0]})
        mk = s["makespan"]
        mk_frame = mk["frame"][:]
        chosen = np.isin(mk_frame, merged_frames)
        return {
            "frame_ms": float(np.median(frame_ms)),
            "makespan_ms": float(np.median(mk["measured_ms"][2:])),
            "merged": len(merged_frames),
            "recorded": len(mk_frame),
            "predicted": mk["predicted_ms"][:][chosen],
            "unmerged": mk["unmerged_predicted_ms"][:][chosen],
        }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--executors", default="events,fused")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--frames", type=int, default=20)
    args = ap.parse_args()
    if not os.path.exists(BIN):
        print(f"{BIN} is missing: build first", file=sys.stderr)
        return 2
    os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
    cases = args.cases.split(",")
    for c in cases:
        if c not in CASES:
            print(f"--cases: unknown case '{c}' (use {', '.join(CASES)})", file=sys.stderr)
            return 2
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.h5")
        for case in cases:
            for executor in args.executors.split(","):
                cell = results.setdefault((case, executor), {"auto": [], "off": []})
                for _ in range(args.rounds):
                    for merging in ("off", "auto"):
                        cell[merging].append(run(case, executor, merging, args.frames, out))
                print(f"measured {case} {executor}", file=sys.stderr, flush=True)
    print("| scene | executor | off: frame ms | auto: frame ms | auto / off | off: substep ms | auto: substep ms | "
          "auto / off | frames that merged (auto) | predicted substep, merged / unmerged |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---|---|")
    for (case, executor), cell in results.items():
        med = {m: {k: statistics.median(r[k] for r in cell[m]) for k in ("frame_ms", "makespan_ms")} for m in cell}
        merged = sum(r["merged"] for r in cell["auto"])
        recorded = sum(r["recorded"] for r in cell["auto"])
        pred = np.concatenate([r["predicted"] for r in cell["auto"]])
        unmerged = np.concatenate([r["unmerged"] for r in cell["auto"]])
        expected = (f"{np.median(pred):.3f} / {np.median(unmerged):.3f} ms ({np.median(pred / unmerged):.2f})"
                    if len(pred) else "–")
        print(f"| {case} | {executor} | {med['off']['frame_ms']:.1f} | {med['auto']['frame_ms']:.1f} | "
              f"{med['auto']['frame_ms'] / med['off']['frame_ms']:.2f} | {med['off']['makespan_ms']:.3f} | "
              f"{med['auto']['makespan_ms']:.3f} | {med['auto']['makespan_ms'] / med['off']['makespan_ms']:.2f} | "
              f"{merged} of {recorded} | {expected} |")
    print()
    print(f"medians over {args.rounds} interleaved rounds of each run's median ({args.frames} frames, the first two "
          "left out); substep ms: the measured makespan of each frame's recorded substep")
    return 0


if __name__ == "__main__":
    sys.exit(main())
