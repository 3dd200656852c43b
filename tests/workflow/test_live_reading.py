#!/usr/bin/python3
"""A notebook watching a run: python/atssim's follow_frames reads every 0.1 s
while the default scene (scenes/hanging_cloth.yaml, its first 40 frames, to
keep the test short) runs at full speed, in 5 runs. Each run: no read error
reaches the reader, every frame 0 … 40 is read exactly once and in order, and
each frame read equals the finished file's frame bit for bit (no
half-written row was taken for a frame). The reads that were retried inside
read_frames are counted and printed."""
import os
import subprocess
import sys

import h5py
import numpy as np

from workflow_common import ATSSIM, SOURCE_DIR, check, scene, temp_dir

sys.path.insert(0, os.path.join(SOURCE_DIR, "python"))
import atssim  # noqa: E402

RUNS = 5
FRAMES = 40

with temp_dir() as d:
    total_reads = total_retries = 0
    for run in range(RUNS):
        h5 = os.path.join(d, f"live{run}.h5")
        proc = subprocess.Popen([ATSSIM, "run", scene("hanging_cloth"), "-o", h5, "--frames", str(FRAMES), "--quiet"],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        times, positions, reads, retries = [], [], 0, 0
        try:
            for frames in atssim.follow_frames(h5, interval=0.1, timeout=30.0, idle_timeout=120.0):
                check(frames.first == len(times), f"run {run}: read from frame {frames.first}, "
                                                  f"expected {len(times)}")
                times.extend(frames.time)
                positions.extend(frames.positions)
                reads += 1
                retries += frames.retries
        finally:
            out, err = proc.communicate(timeout=600)
        check(proc.returncode == 0, f"run {run}: atssim exited {proc.returncode}: {err}")
        with h5py.File(h5, "r") as f:
            final_time = f["frames/time"][:]
            final = f["frames/positions"][:]
            check(int(f.attrs["complete"]) == 1, f"run {run}: the file is not complete")
        check(len(final_time) == FRAMES + 1, f"run {run}: {len(final_time)} frames in the file, expected {FRAMES + 1}")
        check(len(times) == len(final_time), f"run {run}: read {len(times)} frames of {len(final_time)}")
        check(np.array_equal(np.array(times), final_time), f"run {run}: the times read differ from the file's")
        check(np.array_equal(np.stack(positions), final), f"run {run}: a frame read differs from the file's")
        print(f"run {run}: {len(times)} frames in {reads} reads while the run wrote, {retries} reads retried")
        check(reads >= 3, f"run {run}: only {reads} reads saw new frames: the reader did not watch the run")
        total_reads += reads
        total_retries += retries
    print(f"{RUNS} runs: every frame read, {total_reads} reads, {total_retries} retried inside read_frames")
