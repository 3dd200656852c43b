#!/usr/bin/python3
"""ParaView (pvpython under Xvfb) renders a frame of hanging_cloth, pillows and
mesh_cloth from their XDMF, reporting every object's points, triangles and
tetrahedra, and loads the file of a run killed mid-way; meshio reads every
frame with the positions h5py reads.

    test_readers.py paraview|meshio
"""
import json
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

from workflow_common import SCRIPTS, ATSSIM, check, fail, require_tool, run, scene, skip, temp_dir

SCENES = ["hanging_cloth", "pillows", "mesh_cloth"]
FRAMES = 6


def simulate(dir, name):
    h5 = os.path.join(dir, name + ".h5")
    r = run([ATSSIM, "run", scene(name), "-o", h5, "--frames", str(FRAMES), "--quiet"])
    check(r.returncode == 0, f"atssim run {name}: {r.stderr}")
    with h5py.File(h5, "r") as f:
        tris = sum(len(f["mesh"][o]["triangles"]) for o in f["mesh"])
        tets = sum(len(f["mesh"][o]["tetrahedra"]) for o in f["mesh"])
        return h5, f["frames/positions"].shape, tris, tets


def paraview(dir):
    require_tool("pvpython", "bash scripts/setup.sh paraview")
    require_tool("Xvfb", "bash scripts/setup.sh paraview")
    from matplotlib.image import imread
    for name in SCENES:
        h5, (frames, particles, _), tris, tets = simulate(dir, name)
        png = os.path.join(dir, name + ".png")
        # From another folder, by a relative path, as a user would type it.
        r = run(["bash", os.path.join(SCRIPTS, "with_xvfb.sh"), "pvpython", os.path.join(SCRIPTS, "paraview_render.py"),
                 os.path.relpath(h5[:-3] + ".xdmf", "/"), "--frame", "3", "-o", png], cwd="/")
        check(r.returncode == 0, f"pvpython on {name}: {r.stdout}\n{r.stderr}")
        report = json.loads(r.stdout.strip().splitlines()[-1])
        print(name, report)
        check(report["time_steps"] == frames, f"{name}: ParaView sees {report['time_steps']} steps, not {frames}")
        check(report["points"] == particles, f"{name}: ParaView sees {report['points']} points, not {particles}")
        check(report["triangles"] == tris and report["tetrahedra"] == tets,
              f"{name}: ParaView sees {report['triangles']} triangles and {report['tetrahedra']} tets, "
              f"the file has {tris} and {tets}")
        check(abs(report["time"] - 3 / 60) < 1e-6, f"{name}: frame 3 shown at t = {report['time']}")
        image = imread(png)[..., :3]
        background = image[0, 0]
        covered = np.mean(np.any(np.abs(image - background) > 0.02, axis=-1))
        print(f"{name}: {covered:.1%} of the picture is not background")
        check(covered > 0.02, f"{name}: the rendered frame is (nearly) empty ({covered:.2%} covered)")
    paraview_killed_run(dir)


def paraview_killed_run(dir):
    """A run killed mid-way: its sidecar (hyperslab geometry: no views yet)
    loads in ParaView as it is, listing every flushed frame (no h5clear)."""
    h5 = os.path.join(dir, "killed.h5")
    proc = subprocess.Popen([ATSSIM, "run", scene("hanging_cloth"), "-o", h5, "--frames", "100000", "--quiet",
                             "--devices", "cpu/2:0"])
    deadline = time.time() + 120
    while time.time() < deadline and proc.poll() is None:
        time.sleep(0.05)
        if os.path.exists(h5[:-3] + ".xdmf") and open(h5[:-3] + ".xdmf").read().count("<Time ") >= 8:
            break
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    with h5py.File(h5, "r") as f:  # the plain open, as ParaView does it
        flushed = f["frames/positions"].shape[0]
    png = os.path.join(dir, "killed.png")
    r = run(["bash", os.path.join(SCRIPTS, "with_xvfb.sh"), "pvpython", os.path.join(SCRIPTS, "paraview_render.py"),
             h5[:-3] + ".xdmf", "-o", png])
    check(r.returncode == 0, f"pvpython on a killed run: {r.stdout}\n{r.stderr}")
    report = json.loads(r.stdout.strip().splitlines()[-1])
    print("killed run", report)
    check(report["time_steps"] >= 8 and report["points"] == 4096 and report["triangles"] == 7938,
          f"ParaView on a killed run's file: {report}")
    # The sidecar is appended after each flush: a kill between the two leaves it one frame behind.
    check(flushed - 1 <= report["time_steps"] <= flushed,
          f"ParaView sees {report['time_steps']} steps, the file holds {flushed} frames")


def meshio(dir):
    try:
        import meshio  # noqa: F401
    except ImportError:
        skip("python3-meshio is not installed (bash scripts/setup.sh)")
    for name in SCENES + ["soft_box"]:
        h5, (frames, particles, _), tris, tets = simulate(dir, name)
        r = run([sys.executable, os.path.join(SCRIPTS, "check_meshio.py"), h5[:-3] + ".xdmf"])
        check(r.returncode == 0, f"meshio on {name}: {r.stdout}\n{r.stderr}")
        report = json.loads(r.stdout.strip().splitlines()[-1])
        print(name, report)
        check(report["frames"] == frames and report["points"] == particles, f"{name}: {report}")
        check(report["triangles"] == tris and report["tetrahedra"] == tets, f"{name}: {report}")


if __name__ == "__main__":
    which = sys.argv[1] if len(sys.argv) > 1 else fail("usage: test_readers.py paraview|meshio")
    with temp_dir() as d:
        {"paraview": paraview, "meshio": meshio}[which](d)
    print("passed")
