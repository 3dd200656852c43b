#!/usr/bin/python3
"""How often a sheet dropped on its edge folds onto itself, per method.

The scene is the fold test's (tests/app/test_self_contact.cpp, kFold on a
floor with friction 0.8): a 0.4 m sheet of 10 x 10 vertices, bending 1e-5,
self-contact thickness 0.01 m. Which way it buckles is chaotic, so one run
says little; this runs it over a grid of substeps x iterations and counts
the runs that end folded: some vertex within 2 thicknesses of a triangle it
started 0.1 m or more away from, at the last frame (the test's criterion,
brute force in double here, with bench_paper_scenes.py's point_triangle).

usage: scripts/fold_rate.py [--atssim build/release/atssim] [--methods xpbd,sosd,vbd,jpgd]
                            [--substeps 8,12,16,24,32] [--iterations 6,10,20]
Prints one line per run and a Markdown table of the counts."""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_paper_scenes import point_triangle  # noqa: E402  (Ericson's regions, vectorised)

SCENE = """simulation: {fps: 60, substeps: 8, iterations: 6, frames: 60}
objects:
  - {name: sheet, grid: {size: [0.4, 0.4], resolution: [10, 10]}, transform: {rotate: [84, 0, 0], translate: [0, 0.22, 0]},
     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.00001}}
colliders:
  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], thickness: 0.005, friction: 0.8}
contact: {self: true, thickness: 0.01}
"""
THICKNESS = 0.01


def closest_far_pair(path):
    with h5py.File(path, "r") as f:
        x = f["frames/positions"][:].astype(np.float64)
        tris = f["mesh/sheet/triangles"][:].astype(np.int64)
    x0, xn = x[0], x[-1]
    v = np.repeat(np.arange(len(x0)), len(tris))  # every vertex against every triangle
    t = np.tile(np.arange(len(tris)), len(x0))
    far = point_triangle(x0[v], *(x0[tris[t, k]] for k in range(3))) >= 0.1
    v, t = v[far], t[far]
    return float(point_triangle(xn[v], *(xn[tris[t, k]] for k in range(3))).min())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--atssim", default="build/release/atssim")
    ap.add_argument("--methods", default="xpbd,sosd,vbd,jpgd")
    ap.add_argument("--substeps", default="8,12,16,24,32")
    ap.add_argument("--iterations", default="6,10,20")
    a = ap.parse_args()
    methods = a.methods.split(",")
    grid = [(int(s), int(i)) for s in a.substeps.split(",") for i in a.iterations.split(",")]
    folded = {m: 0 for m in methods}
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "fold.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        for m in methods:
            for s, i in grid:
                out = os.path.join(tmp, "out.h5")
                subprocess.run([a.atssim, "run", scene, "-o", out, "--quiet", "--method", m,
                                "--set", f"simulation.substeps={s}", "--set", f"simulation.iterations={i}"],
                               check=True)
                d = closest_far_pair(out)
                folded[m] += d < 2 * THICKNESS
                print(f"{m} substeps {s} iterations {i}: closest far pair {d:.4f} m"
                      f" ({'folded' if d < 2 * THICKNESS else 'not folded'})", flush=True)
    print()
    print("| method | runs that end folded |")
    print("|---|---|")
    for m in methods:
        print(f"| {m} | {folded[m]} of {len(grid)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
