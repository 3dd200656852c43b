#!/usr/bin/python3
"""Fault tests through the real binary: what a run leaves when it is killed,
interrupted, resumed, raced by a second writer, out of disk space, or robbed
of its output folder.

    test_faults.py sigkill|resume|disk_full|second_writer|keeps_earlier|sigint|vanished_folder|sigint_setup

Every atssim started here is killed and waited for in a finally block, so a
failing test leaves no process behind. Exit 77 = skipped (reason on stderr).
"""
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ATSSIM = os.environ.get("ATSSIM", "atssim")
SOURCE = os.environ.get("ATSSIM_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
SKIP = 77

SCENE = """simulation:
  fps: 60
  substeps: {substeps}
  iterations: 4
  frames: {frames}
objects:
  - name: cloth
    grid:
      size: [1.0, 1.0]
      resolution: [{res}, {res}]
    transform:
      translate: [0, 1.5, 0]
    material:
      density: 0.2
      stretch_stiffness: 1.0e4
      bend_stiffness: 1.0e-3
    pins:
      vertices: [0, {last}]
solver:
  method: {method}
"""


CHECKS = 0  # checks made: a test that made none ran nothing, and fails


def fail(message):
    print(f"FAILED: {message}", file=sys.stderr)
    sys.exit(1)


def check(condition, message):
    global CHECKS
    CHECKS += 1
    if not condition:
        fail(message)


def write_scene(folder, frames=100000, res=16, substeps=4, method="xpbd"):
    path = os.path.join(folder, "scene.yaml")
    with open(path, "w") as f:
        f.write(SCENE.format(frames=frames, res=res, last=res - 1, substeps=substeps, method=method))
    return path


def atssim(args, **kw):
    print("$", ATSSIM, " ".join(args), flush=True)
    return subprocess.Popen([ATSSIM] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)


def stop(proc):
    """Kills and reaps `proc` if it still runs (finally blocks)."""
    if proc is not None and proc.poll() is None:
        proc.kill()
    if proc is not None:
        proc.communicate()


def xdmf_frames(h5):
    path = h5[:-3] + ".xdmf"
    return open(path).read().count("<Time ") if os.path.exists(path) else 0


def wait_for_frames(proc, h5, frames, timeout=180):
    deadline = time.time() + timeout
    while time.time() < deadline:
        if proc.poll() is not None:
            out, err = proc.communicate()
            fail(f"atssim ended (exit {proc.returncode}) before writing {frames} frames: {err}")
        if xdmf_frames(h5) >= frames:
            return
        time.sleep(0.02)
    fail(f"no {frames} frames within {timeout} s")


def read_run(h5):
    """Plain h5py, as the docs show it: positions, complete flag, error."""
    with h5py.File(h5, "r") as f:
        return f["frames/positions"][()], int(f.attrs["complete"]), str(f.attrs["error"])


def one_line(err):
    lines = [l for l in err.splitlines() if l.strip()]
    check(len(lines) == 1, f"expected one line on stderr, got {len(lines)}: {err!r}")
    return lines[0]


def test_sigkill(tmp):
    scene = write_scene(tmp)
    h5 = os.path.join(tmp, "killed.h5")
    target = random.randint(3, 40)
    proc = None
    try:
        proc = atssim(["run", scene, "-o", h5, "--quiet"])
        wait_for_frames(proc, h5, target)
        proc.send_signal(signal.SIGKILL)
        proc.communicate()
    finally:
        stop(proc)
    positions, complete, _ = read_run(h5)
    print(f"killed after >= {target} frames: the file holds {len(positions)}, the sidecar lists {xdmf_frames(h5)}")
    check(len(positions) >= target, f"{len(positions)} frames, at least {target} were flushed")
    check(np.isfinite(positions).all(), "a flushed frame holds non-finite positions")
    check(complete == 0, "a killed run's file says complete")
    # The sidecar is appended after each flush: a kill between the two can
    # leave it one frame behind, never ahead.
    listed = xdmf_frames(h5)
    check(len(positions) - 1 <= listed <= len(positions),
          f"the sidecar lists {listed} frames, the file holds {len(positions)}")
    # /frames/flushed is written after each flush, the same way: as far as
    # the rows, or one frame behind.
    with h5py.File(h5, "r") as f:
        flushed = int(f["frames/flushed"][0])
    check(len(positions) - 1 <= flushed <= len(positions),
          f"/frames/flushed is {flushed}, the file holds {len(positions)} frames")
    r = subprocess.run([ATSSIM, "inspect", h5], capture_output=True, text=True)
    check(r.returncode == 0 and "incomplete" in r.stdout, f"atssim inspect: {r.stdout} {r.stderr}")


def test_resume(tmp):
    frames = 30
    scene = write_scene(tmp, frames=frames, res=32, substeps=16)
    args = ["--quiet", "--devices", "cpu"]
    full = os.path.join(tmp, "full.h5")
    r = subprocess.run([ATSSIM, "run", scene, "-o", full] + args, capture_output=True, text=True)
    check(r.returncode == 0, f"uninterrupted run: {r.stderr}")
    reference, complete, _ = read_run(full)
    check(complete == 1 and len(reference) == frames + 1, "the uninterrupted run is incomplete")

    h5 = os.path.join(tmp, "resumed.h5")
    # The run is killed as soon as it has flushed `target` frames; one that
    # got to its end before the kill is tried again with a fresh file, and
    # three such runs fail the test (it never passes without resuming).
    for attempt in range(3):
        target = random.randint(2, frames // 2)
        proc = None
        try:
            proc = atssim(["run", scene, "-o", h5] + args)
            wait_for_frames(proc, h5, target)
            proc.send_signal(signal.SIGKILL)
            proc.communicate()
        finally:
            stop(proc)
        killed, _, _ = read_run(h5)
        if len(killed) < frames + 1:
            break
        print(f"attempt {attempt + 1}: the run finished before the kill; again")
        for name in os.listdir(tmp):
            if name.startswith("resumed."):
                os.remove(os.path.join(tmp, name))
    check(len(killed) < frames + 1, "three runs finished before they could be killed")
    r = subprocess.run([ATSSIM, "run", scene, "-o", h5, "--resume"] + args, capture_output=True, text=True)
    check(r.returncode == 0, f"--resume: exit {r.returncode}: {r.stderr}")
    resumed, complete, _ = read_run(h5)
    print(f"killed with {len(killed)} frames, resumed to {len(resumed)}")
    check(complete == 1, "the resumed run is not complete")
    check(resumed.shape == reference.shape, f"resumed {resumed.shape}, uninterrupted {reference.shape}")
    differ = np.argwhere(np.any(resumed != reference, axis=(1, 2))).ravel()
    check(len(differ) == 0, f"frames {differ[:10]} differ from the uninterrupted run "
                            f"(max |d| {np.abs(resumed - reference).max():g})")
    with h5py.File(h5, "r") as f:
        check(len(f["frames/time"]) == frames + 1 and len(f["timing/frame_ms"]) == frames + 1,
              "the time series do not match the frames")
        check(list(f["schedule/makespan/frame"][()]) == list(range(1, frames + 1)),
              f"/schedule/makespan/frame is {list(f['schedule/makespan/frame'][()])}")
        check(int(f["frames/flushed"][0]) == frames + 1, f"/frames/flushed is {f['frames/flushed'][0]}")
    check(xdmf_frames(h5) == frames + 1, f"the sidecar lists {xdmf_frames(h5)} frames")
    r = subprocess.run([ATSSIM, "run", scene, "-o", h5, "--resume"] + args, capture_output=True, text=True)
    check(r.returncode == 2 and "complete run" in r.stderr, f"resuming a complete run: {r.returncode} {r.stderr}")


def test_disk_full(tmp):
    if os.geteuid() != 0:
        print("SKIPPED: mounting a small tmpfs needs root", file=sys.stderr)
        sys.exit(SKIP)
    mnt = os.path.join(tmp, "small")
    os.makedirs(mnt)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=3m", "tmpfs", mnt], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"SKIPPED: cannot mount a tmpfs here: {r.stderr.strip()}", file=sys.stderr)
        sys.exit(SKIP)
    proc = None
    try:
        scene = write_scene(tmp, res=32)
        h5 = os.path.join(mnt, "full.h5")
        proc = atssim(["run", scene, "-o", h5, "--quiet"])
        _, err = proc.communicate(timeout=300)
        line = one_line(err)
        print(line)
        check(proc.returncode == 1, f"exit {proc.returncode}, expected 1")
        check("full" in line and "frames kept in" in line, f"the message does not say the disk is full: {line}")
        positions, complete, error = read_run(h5)
        check(len(positions) >= 2 and np.isfinite(positions).all(), f"{len(positions)} readable frames")
        check(complete == 0 and "full" in error, f"complete={complete}, error={error!r}")
        kept = int(re.search(r"\((\d+) frames kept", line).group(1))
        check(kept == len(positions), f"the message says {kept} frames, the file holds {len(positions)}")
        print(f"disk full after {len(positions)} frames; all readable")
    finally:
        stop(proc)
        subprocess.run(["umount", "-l", mnt])


def test_second_writer(tmp):
    scene = write_scene(tmp)
    h5 = os.path.join(tmp, "shared.h5")
    first = None
    try:
        first = atssim(["run", scene, "-o", h5, "--quiet"])
        wait_for_frames(first, h5, 3)
        r = subprocess.run([ATSSIM, "run", scene, "-o", h5, "--quiet"], capture_output=True, text=True, timeout=120)
        line = one_line(r.stderr)
        print(line)
        check(r.returncode == 2, f"the second writer exited {r.returncode}, expected 2")
        check("another atssim run is writing" in line, f"unexpected message: {line}")
        check(first.poll() is None, "the first run stopped")
        first.send_signal(signal.SIGINT)
        first.communicate(timeout=60)
    finally:
        stop(first)
    positions, complete, error = read_run(h5)
    check(np.isfinite(positions).all() and len(positions) >= 3, "the first run's frames are damaged")
    check(complete == 0 and "interrupted" in error, f"complete={complete} error={error!r}")


def test_keeps_earlier(tmp):
    scene = write_scene(tmp, frames=5)
    h5 = os.path.join(tmp, "result.h5")
    r = subprocess.run([ATSSIM, "run", scene, "-o", h5, "--quiet"], capture_output=True, text=True)
    check(r.returncode == 0, f"first run: {r.stderr}")
    good, complete, _ = read_run(h5)
    check(complete == 1, "the first run is incomplete")
    # A second run at the same path fails part-way (Ctrl-C) ...
    proc = None
    try:
        proc = atssim(["run", scene, "-o", h5, "--frames", "100000", "--quiet"])
        wait_for_frames(proc, os.path.join(tmp, "result.partial.h5"), 3)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
        line = one_line(err)
        print(line)
        check(proc.returncode == 1, f"the interrupted run exited {proc.returncode}")
        check("result.partial.h5" in line and "left as it was" in line, f"message: {line}")
    finally:
        stop(proc)
    # ... and the earlier result is untouched; the failed run is beside it.
    after, complete, _ = read_run(h5)
    check(complete == 1 and np.array_equal(after, good), "the earlier result was changed")
    partial, pcomplete, error = read_run(os.path.join(tmp, "result.partial.h5"))
    check(pcomplete == 0 and "interrupted" in error and len(partial) >= 3, "the partial file is wrong")
    # A third run that completes replaces both.
    r = subprocess.run([ATSSIM, "run", scene, "-o", h5, "--frames", "3", "--quiet"], capture_output=True, text=True)
    check(r.returncode == 0, r.stderr)
    third, complete, _ = read_run(h5)
    check(complete == 1 and len(third) == 4, "the completed run did not take the path")
    check(not os.path.exists(os.path.join(tmp, "result.partial.xdmf")), "a partial sidecar was left")
    with open(h5[:-3] + ".xdmf") as f:
        check("result.h5:" in f.read(), "the sidecar does not point at result.h5")


def test_sigint(tmp):
    # Frames of many substeps: the first Ctrl-C must stop inside one.
    scene = write_scene(tmp, res=32, substeps=400)
    h5 = os.path.join(tmp, "int.h5")
    proc = None
    try:
        proc = atssim(["run", scene, "-o", h5, "--quiet"])
        wait_for_frames(proc, h5, 2)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=120)
        line = one_line(err)
        print(line)
        check(proc.returncode == 1, f"exit {proc.returncode}")
        m = re.search(r"interrupted in frame (\d+) \(substep (\d+) of 400\)", line)
        check(m is not None and int(m.group(2)) < 400, f"did not stop inside a frame: {line}")
        # Twice: the second Ctrl-C ends the process at once. The first comes
        # while the run is still setting up (profiling the devices), when it
        # is only noted; the second, a moment later, must end the process.
        h5 = os.path.join(tmp, "twice.h5")
        proc = atssim(["run", scene, "-o", h5, "--quiet"])
        time.sleep(0.3)
        proc.send_signal(signal.SIGINT)
        time.sleep(0.2)
        running = proc.poll() is None
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=120)
        print(err.strip())
        if running:
            check(proc.returncode == 130 and "interrupted again" in err, f"exit {proc.returncode}: {err}")
        else:
            print("the run had already stopped after the first Ctrl-C")
    finally:
        stop(proc)


def test_vanished_folder(tmp):
    scene = write_scene(tmp)
    folder = os.path.join(tmp, "out")
    os.makedirs(folder)
    h5 = os.path.join(folder, "gone.h5")
    proc = None
    try:
        proc = atssim(["run", scene, "-o", h5, "--quiet"])
        wait_for_frames(proc, h5, 3)
        shutil.rmtree(folder)
        _, err = proc.communicate(timeout=60)
        line = one_line(err)
        print(line)
        check(proc.returncode == 1, f"exit {proc.returncode}")
        check("removed" in line, f"message: {line}")
    finally:
        stop(proc)


def test_sigint_setup(tmp):
    """Ctrl-C (SIGINT to the whole process group, as a terminal sends it) while
    the kernels are being built: an empty POCL_CACHE_DIR makes pocl compile
    them, and the signal comes once it has started (its cache folder is no
    longer empty). One line, from atssim, exit 1, nothing written."""
    scene = write_scene(tmp, frames=2)
    cache = os.path.join(tmp, "pocl-cache")
    os.makedirs(cache)
    h5 = os.path.join(tmp, "setup.h5")
    env = dict(os.environ, POCL_CACHE_DIR=cache)
    proc = None
    try:
        proc = subprocess.Popen([ATSSIM, "run", scene, "-o", h5, "--quiet"], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, env=env, start_new_session=True)
        deadline = time.monotonic() + 60
        while not os.listdir(cache) and proc.poll() is None and time.monotonic() < deadline:
            time.sleep(0.01)
        check(proc.poll() is None, "the run ended before it began building kernels")
        time.sleep(random.uniform(0.0, 0.3))
        os.killpg(proc.pid, signal.SIGINT)
        out, err = proc.communicate(timeout=120)
        print(err)
        lines = [l for l in err.splitlines() if l.strip()]
        check(len(lines) == 1, f"{len(lines)} lines on stderr, expected one: {err!r}")
        check(lines[0].startswith("atssim: interrupted during device set-up"), f"the line: {lines[0]!r}")
        check(proc.returncode == 1, f"exit {proc.returncode}, expected 1")
        check(out == "", f"stdout: {out!r}")
        left = [f for f in os.listdir(tmp) if f.startswith("setup")]
        check(not left, f"it wrote {left}")
    finally:
        stop(proc)


def main():
    test = {"sigkill": test_sigkill, "resume": test_resume, "disk_full": test_disk_full,
            "second_writer": test_second_writer, "keeps_earlier": test_keeps_earlier, "sigint": test_sigint,
            "vanished_folder": test_vanished_folder, "sigint_setup": test_sigint_setup}[sys.argv[1]]
    seed = int(os.environ.get("ATSSIM_FAULT_SEED", random.randrange(1 << 30)))
    random.seed(seed)
    print(f"seed {seed} (ATSSIM_FAULT_SEED to repeat)")
    with tempfile.TemporaryDirectory(prefix="atssim-faults-") as tmp:
        test(tmp)
    if CHECKS == 0:
        fail(f"{sys.argv[1]} made no check: it ran nothing")
    print(f"passed ({CHECKS} checks)")


if __name__ == "__main__":
    main()
