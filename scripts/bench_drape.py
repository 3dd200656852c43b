#!/usr/bin/python3
"""Two-device speedup of scenes/drape_sphere.yaml (48x48) with contact in the graph:
median frame ms of frames 6..20, one 1-CU sub-device vs two (heft, split), XPBD and VBD,
collider contact only and with self-contact on. Prints one Markdown table.

usage: scripts/bench_drape.py   (build first: cmake --build --preset release)
"""
import os
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
A = os.path.join(ROOT, "build", "release", "atssim")
S = os.path.join(ROOT, "scenes", "drape_sphere.yaml")
os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
print("| method | contact | 1 sub-device ms | 2 sub-devices heft ms | 2 sub-devices split ms | best speedup |")
print("|---|---|---|---|---|---|")
with tempfile.TemporaryDirectory() as d:
    for method in ("xpbd", "vbd"):
        for self_on in (False, True):
            row = []
            for devices, schedule in (("cpu/2:0", "single"), ("cpu/2", "heft"), ("cpu/2", "split")):
                out = os.path.join(d, "o.h5")
                cmd = [A, "run", S, "-o", out, "--frames", "20", "--devices", devices, "--schedule", schedule,
                       "--method", method, "--quiet"]
                if self_on:
                    cmd += ["--set", "contact.self=true", "--set", "contact.thickness=0.004"]
                subprocess.run(cmd, check=True)
                with h5py.File(out) as f:
                    row.append(float(np.median(f["timing/frame_ms"][6:])))
            best = row[0] / min(row[1:])
            print(f"| {method} | {'colliders + self' if self_on else 'colliders'} | {row[0]:.1f} | {row[1]:.1f} | {row[2]:.1f} | {best:.2f}x |", flush=True)
