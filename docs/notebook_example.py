#!/usr/bin/python3
"""atssim results in a notebook: h5py + matplotlib, nothing else.

Each "# %%" block is a notebook cell (VS Code and Jupytext open the file as a
notebook; pasting the blocks into Jupyter works too). As a script it makes
its own small results in a temporary folder and draws one figure:

    /usr/bin/python3 docs/notebook_example.py [-o docs/notebook-example.png]

The cells: (1) a run with its `--json` summary; (2) positions of a frame from
/frames/positions; (3) the schedule map of the last recorded substep,
predicted vs measured; (4) convergence curves from `atssim converge`;
(5) reading a file while atssim is still writing it (python/atssim.follow_frames).
"""
# %% Setup: where atssim is, a folder for the results.
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

root = pathlib.Path(__file__).resolve().parent.parent
ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("-o", "--output", default=str(root / "docs" / "notebook-example.png"))
ap.add_argument("--atssim", default=os.environ.get("ATSSIM", str(root / "build" / "release" / "atssim")))
args, _ = ap.parse_known_args()
atssim_binary = args.atssim
work = pathlib.Path(tempfile.mkdtemp(prefix="atssim-notebook-"))
scene = str(root / "scenes" / "hanging_cloth.yaml")
small = ["--set", "objects.0.grid.resolution=[32, 32]"]

# %% (1) A run on two sub-devices; its summary is one JSON object on stdout.
run = subprocess.run([atssim_binary, "run", scene, "-o", str(work / "cloth.h5"), "--frames", "40", "--devices", "cpu/2",
                      "--schedule", "split", *small, "--json"], capture_output=True, text=True, check=True)
summary = json.loads(run.stdout)
print(f"{summary['status']}: {summary['frames']['written']} frames, "
      f"{summary['ms_per_frame']['median']:.2f} ms/frame (p95 {summary['ms_per_frame']['p95']:.2f}), "
      f"prediction error {100 * summary['prediction_error']['median']:.1f} %")

# %% (2) Positions: /frames/positions is [frames, vertices, 3]; objects are row ranges.
fig, axes = plt.subplots(2, 2, figsize=(11, 8))
with h5py.File(work / "cloth.h5", "r") as f:
    x = f["frames/positions"]
    t = f["frames/time"][:]
    cloth = f["mesh/cloth"]
    first, count = cloth.attrs["vertex_offset"], cloth.attrs["vertex_count"]
    tris = cloth["triangles"][:]
    ax = axes[0, 0]
    for k in (0, len(t) // 2, len(t) - 1):
        p = x[k, first:first + count]
        ax.triplot(p[:, 0], p[:, 1], tris, lw=0.3, label=f"t = {t[k]:.2f} s")
    ax.set_title("positions (side view, x–y)")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.legend(fontsize=8)

# %% (3) The schedule map: where each task of the last recorded substep ran, predicted and measured.
    frames = f["schedule/frame"][:]
    rows = frames == frames.max()
    device = f["schedule/device"][:][rows]
    kind = np.array([k.decode() for k in f["schedule/tasks/kind"][:]])[f["schedule/task"][:][rows]]
    ax = axes[0, 1]
    colours = {k: f"C{i}" for i, k in enumerate(dict.fromkeys(kind))}
    for lane, (start, finish) in enumerate([("predicted_start_ms", "predicted_finish_ms"),
                                            ("measured_start_ms", "measured_finish_ms")]):
        s, e = f["schedule/" + start][:][rows], f["schedule/" + finish][:][rows]
        for d, a, b, k in zip(device, s, e, kind):
            ax.barh(2 * d + lane, b - a, left=a, color=colours[k], height=0.8)
    ax.set_yticks(range(2 * (device.max() + 1)),
                  [f"dev {d} {w}" for d in range(device.max() + 1) for w in ("predicted", "measured")])
    ax.set_xlabel("ms from the substep's start")
    mode = f["schedule"].attrs["mode"]
    ax.set_title(f"schedule map, frame {frames.max()} ({mode.decode() if isinstance(mode, bytes) else mode})")
    ax.legend(handles=[plt.Rectangle((0, 0), 1, 1, color=c) for c in colours.values()], labels=list(colours),
              fontsize=7, loc="lower right")

# %% (4) Convergence: relative energy error y_k against iterations, per method.
subprocess.run([atssim_binary, "converge", scene, "-o", str(work / "convergence.h5"), "--methods", "xpbd,vbd",
                "--iterations", "16", "--frames-before", "5", *small], capture_output=True, text=True, check=True)
with h5py.File(work / "convergence.h5", "r") as f:
    ax = axes[1, 0]
    for name in (v.decode() for v in f["convergence/variants"][:]):
        g = f["convergence/" + name.replace("/", ":")]
        ax.loglog(g["iterations"][:], g["relative_error"][:], "o-", label=name)
    ax.set_xlabel("iterations")
    ax.set_ylabel("(E_k − E*) / (E_0 − E*)")
    ax.set_title("convergence against the Newton reference")
    ax.legend(fontsize=8)

# %% (5) A file that is still being written: python/atssim reads the frames the run has flushed in
# full, retrying a read that lands inside a flush (docs/output-format.md), every 0.1 s.
sys.path.insert(0, str(root / "python"))
import atssim  # noqa: E402

proc = subprocess.Popen([atssim_binary, "run", scene, "-o", str(work / "live.h5"), "--frames", "400", "--devices",
                         "cpu/2:0", *small, "--quiet"])
seen, retried, complete = [], 0, False
for new in atssim.follow_frames(work / "live.h5", interval=0.1):
    last = new.first + len(new.time)
    seen.append((last, float(new.positions[-1, :, 1].min())))  # frames so far, lowest point of the newest
    retried += new.retries
proc.wait()
# follow_frames ends once the run has ended and every frame was yielded; the
# read that sees the end may bring no new frame, so ask the file itself.
complete = atssim.read_frames(work / "live.h5", seen[-1][0] if seen else 0).complete
print(f"{retried} reads caught the writer mid-flush and were retried inside read_frames")
print(f"read {len(seen)} growing states while the run wrote; complete afterwards: {complete}")
ax = axes[1, 1]
ax.plot([n for n, _ in seen], [y for _, y in seen], ".")
ax.set_xlabel("frames in the file when read")
ax.set_ylabel("lowest y of the newest frame (m)")
ax.set_title(f"reading while atssim writes ({len(seen)} reads)")

fig.tight_layout()
fig.savefig(args.output, dpi=100)
print(f"wrote {args.output}")
assert summary["status"] == "complete" and len(seen) >= 3 and complete == 1
