#!/usr/bin/python3
"""How often a sheet dropped on its edge folds onto itself, per method.

The scene is the fold test's (tests/app/test_self_contact.cpp, kFold on a
floor with friction 0.8): a 0.4 m sheet of 10 x 10 vertices, bending 1e-5,
self-contact thickness 0.01 m. Which way it buckles is chaotic, so one run
says little; this runs it over a grid of substeps x iterations and counts
the runs that end folded: some vertex within 2 thicknesses of a triangle it
started 0.1 m or more away from, at the last frame (the test's criterion,
brute force in double here).

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

SCENE = """simulation: {fps: 60, substeps: 8, iterations: 6, frames: 60}
objects:
  - {name: sheet, grid: {size: [0.4, 0.4], resolution: [10, 10]}, transform: {rotate: [84, 0, 0], translate: [0, 0.22, 0]},
     material: {density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.00001}}
colliders:
  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], thickness: 0.005, friction: 0.8}
contact: {self: true, thickness: 0.01}
"""
THICKNESS = 0.01


def point_triangle(p, a, b, c):
    """Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = ab @ ap, ac @ ap
    if d1 <= 0 and d2 <= 0:
        return np.linalg.norm(p - a)
    bp = p - b
    d3, d4 = ab @ bp, ac @ bp
    if d3 >= 0 and d4 <= d3:
        return np.linalg.norm(p - b)
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return np.linalg.norm(p - (a + d1 / (d1 - d3) * ab))
    cp = p - c
    d5, d6 = ab @ cp, ac @ cp
    if d6 >= 0 and d5 <= d6:
        return np.linalg.norm(p - c)
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return np.linalg.norm(p - (a + d2 / (d2 - d6) * ac))
    va = d3 * d6 - d5 * d4
    if va <= 0 and d4 - d3 >= 0 and d5 - d6 >= 0:
        return np.linalg.norm(p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b)))
    denom = 1 / (va + vb + vc)
    return np.linalg.norm(p - (a + ab * vb * denom + ac * vc * denom))


def closest_far_pair(path):
    with h5py.File(path, "r") as f:
        x = f["frames/positions"][:].astype(np.float64)
        tris = f["mesh/sheet/triangles"][:]
    x0, xn = x[0], x[-1]
    return min(point_triangle(xn[v], *xn[t]) for t in tris for v in range(len(x0))
               if point_triangle(x0[v], *x0[t]) >= 0.1)


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
