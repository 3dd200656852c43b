#!/usr/bin/python3
"""Kills `atssim run` N times at random moments (SIGKILL) and counts the files that a plain
h5py.File(path, "r") opens with every frame finite (docs/reliability.md).

    scripts/kill_loop.py build/release/atssim 40
"""
import os, random, signal, subprocess, sys, tempfile, time
import h5py, numpy as np
A = sys.argv[1]; n = int(sys.argv[2])
scene = os.path.join(os.path.dirname(A), "..", "..", "scenes", "hanging_cloth.yaml")
ok = bad = 0; frames = []
with tempfile.TemporaryDirectory() as d:
    for i in range(n):
        h5 = os.path.join(d, f"k{i}.h5")
        p = subprocess.Popen([A, "run", scene, "-o", h5, "--frames", "100000", "--quiet", "--devices", "cpu/2:0"])
        while not os.path.exists(h5[:-3] + ".xdmf"):
            time.sleep(0.01)
        time.sleep(random.uniform(0.0, 1.5))
        p.kill(); p.wait()
        try:
            with h5py.File(h5, "r") as f:
                x = f["frames/positions"][()]
                assert np.isfinite(x).all() and int(f.attrs["complete"]) == 0
            ok += 1; frames.append(len(x))
        except Exception as e:
            bad += 1; print("unreadable:", e)
        os.remove(h5)
print(f"{ok} of {n} killed files opened with plain h5py, all frames finite; frames held: {sorted(frames)}")
