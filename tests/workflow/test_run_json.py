#!/usr/bin/python3
"""`atssim run --json` prints one object that validates against
docs/run-summary.schema.json, for a complete run, a run that blows up and a
bad scene, and whose numbers agree with the HDF5 file the run wrote."""
import json
import os
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

from workflow_common import ATSSIM, SOURCE_DIR, check, run, scene, skip, temp_dir

sys.path.insert(0, os.path.join(SOURCE_DIR, "python"))
from atssim.frames import TRANSIENT  # noqa: E402  what a read inside a writer's flush raises

try:
    import jsonschema
except ImportError:
    skip("python3-jsonschema is not installed (bash scripts/setup.sh)")

with open(os.path.join(SOURCE_DIR, "docs", "run-summary.schema.json")) as f:
    SCHEMA = json.load(f)
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA, format_checker=jsonschema.FormatChecker())


def run_json(args, code):
    r = run([ATSSIM, "run", *args, "--json"])
    check(r.returncode == code, f"exit code {r.returncode}, expected {code}: {r.stderr}")
    summary = json.loads(r.stdout)  # the whole of stdout is one JSON object
    errors = [e.message for e in VALIDATOR.iter_errors(summary)]
    check(not errors, f"the summary does not validate: {errors}\n{r.stdout}")
    return summary, r


def nearest_rank(values, q):
    values = sorted(values)
    rank = int(np.ceil(q * len(values)))
    return values[max(rank, 1) - 1]


with temp_dir() as d:
    # A complete two-device run: every field is there and matches the file.
    h5 = os.path.join(d, "cloth.h5")
    s, _ = run_json([scene("hanging_cloth"), "-o", h5, "--frames", "6", "--devices", "cpu/2", "--schedule", "split",
                     "--set", "objects.0.grid.resolution=[24, 24]"], 0)
    print(json.dumps(s, indent=1))
    check(s["status"] == "complete" and s["output"] == h5 and s["xdmf"] == h5[:-3] + ".xdmf", "paths")
    check(s["schedule"] == "split" and len(s["devices"]) == 2, "two devices, split")
    check(s["particles"] == 576 and s["frames"] == {"requested": 6, "simulated": 6, "written": 7}, "counts")
    with h5py.File(h5, "r") as f:
        ms = f["timing/frame_ms"][1:]
        # /timing: a row per written frame, 0 for the initial state; the
        # three parts of a frame's time are disjoint stretches of the run,
        # so together they fit in its wall time.
        timing = [f[f"timing/{k}"][:] for k in ("frame_ms", "schedule_ms", "host_ms")]
        check(all(len(t) == 7 and t[0] == 0 for t in timing), "a /timing row per frame, 0 first")
        check(all(np.all(np.isfinite(t)) and np.all(t >= 0) for t in timing), "finite, not negative")
        check(np.all(timing[2][1:] > 0), f"the host's work on each frame is recorded: {timing[2]}")
        check(sum(t.sum() for t in timing) <= 1000 * s["wall_s"], f"/timing sums to more than the run's wall time")
        predicted = f["schedule/makespan/predicted_ms"][:]
        measured = f["schedule/makespan/measured_ms"][:]
        executor = f["schedule"].attrs["executor"]
        check(s["executor"] == (executor.decode() if isinstance(executor, bytes) else executor), "executor")
    check(abs(s["ms_per_frame"]["median"] - nearest_rank(ms, 0.5)) < 1e-3 * nearest_rank(ms, 0.5), "median ms")
    check(abs(s["ms_per_frame"]["p95"] - nearest_rank(ms, 0.95)) < 1e-3 * nearest_rank(ms, 0.95), "p95 ms")
    host = timing[2][1:]
    check(abs(s["host_ms_per_frame"]["median"] - nearest_rank(host, 0.5)) <= 1e-3 * nearest_rank(host, 0.5),
          "median host ms")
    error = np.abs(measured - predicted) / measured
    check(s["prediction_error"]["frames"] == len(error), "prediction error over every recorded frame")
    check(abs(s["prediction_error"]["median"] - nearest_rank(error, 0.5)) < 1e-4, "prediction error median")

    # A run that blows up: exit 1, status failed, the frames it kept.
    # (block-Jacobi descent, stiffness 1e30, full steps, heavy momentum: float32 overflows)
    s, r = run_json([scene("hanging_cloth"), "-o", os.path.join(d, "wild.h5"), "--frames", "3", "--method", "jpgd",
                     "--set", "simulation.fps=0.1", "--set", "simulation.substeps=1", "--set",
                     "simulation.gravity=[0, -1000000, 0]", "--set", "objects.0.material.stretch_stiffness=1e30",
                     "--set", "objects.0.material.bend_stiffness=1e20", "--set", "solver.jacobi_step=1",
                     "--set", "solver.momentum=0.999"], 1)
    check(s["status"] == "failed" and "blew up" in s["error"] and s["frames"]["written"] == 1, "failed run")
    check(r.stderr.count("\n") == 1, "the error line is still on stderr")

    # A bad scene: exit 2, status input_error, nothing written.
    s, _ = run_json([scene("hanging_cloth"), "-o", os.path.join(d, "bad.h5"), "--set", "simulation.substeps=0"], 2)
    check(s["status"] == "input_error" and s["output"] is None and "substeps" in s["error"], "input error")
    refused = s

    # --tolerance: `accuracy` lists the choices, as /decisions holds them.
    h5 = os.path.join(d, "tuned.h5")
    s, _ = run_json([scene("hanging_cloth"), "-o", h5, "--frames", "5", "--devices", "cpu", "--tolerance", "1e-2",
                     "--recheck", "4", "--set", "objects.0.grid.resolution=[10, 10]"], 0)
    a = s["accuracy"]
    check(a is not None and a["tolerance"] == 0.01 and a["budget_ms"] is None and a["recheck"] == 4, f"accuracy: {a}")
    rows = a["decisions"]
    with h5py.File(h5, "r") as f:
        g = f["decisions"]
        check(len(rows) == g["frame"].shape[0] and len(rows) >= 2, f"{len(rows)} decisions in the summary")
        for i, row in enumerate(rows):
            check(row["frame"] == int(g["frame"][i]) and row["iterations"] == int(g["iterations"][i]), f"row {i}")
            check(row["method"] == g["method"][i].decode().rstrip("\0"), f"row {i}: method")
            check(row["changed"] == bool(g["changed"][i]), f"row {i}: changed")
            y = float(g["y"][i])
            check((row["y"] is None and np.isnan(y)) or abs(row["y"] - y) <= 1e-5 * abs(y), f"row {i}: y")
    check(rows[0]["frame"] == 0 and rows[0]["changed"], "the probe is the first row")
    check(s["method"] == rows[-1]["method"], "the run ends with the last choice's method")
    check(refused["accuracy"] is None, "no accuracy object without --tolerance / --budget")

    # A budget no choice fits: exit 2, nothing written, the goal and no decisions.
    s, _ = run_json([scene("hanging_cloth"), "-o", os.path.join(d, "none.h5"), "--devices", "cpu", "--budget",
                     "1e-9"], 2)
    check(s["status"] == "input_error" and "no choice fits" in s["error"], f"refused budget: {s['error']}")
    check(s["accuracy"] == {"tolerance": None, "budget_ms": 1e-9, "recheck": 30, "decisions": []}, f"{s['accuracy']}")
    check(not os.path.exists(os.path.join(d, "none.h5")), "a refused budget writes nothing")

    # SIGTERM (a cluster's time limit, a sweep being stopped): the run stops
    # after the current frame, keeps its frames and says it was interrupted.
    out = os.path.join(d, "long.h5")
    args = [ATSSIM, "run", scene("hanging_cloth"), "-o", out, "--frames", "100000", "--devices", "cpu/2:0", "--json"]
    proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.time() + 60
        while time.time() < deadline:
            time.sleep(0.1)
            try:
                with h5py.File(out, "r", swmr=True) as f:
                    if f["frames/time"].shape[0] >= 3:
                        break
            except TRANSIENT:  # the writer was inside a flush: HDF5 says so as OSError or RuntimeError
                pass
        proc.send_signal(signal.SIGTERM)
        stdout, stderr = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:  # a failed check above: never leave the run writing into the folder
            proc.kill()
            proc.communicate()
    s = json.loads(stdout)
    check(proc.returncode == 1 and VALIDATOR.is_valid(s), f"interrupted run: exit {proc.returncode}, {stdout}")
    check(s["status"] == "interrupted" and s["frames"]["written"] >= 3, f"interrupted run: {s['status']}, {s['frames']}")

    # The schema can fail: a summary without its status, or a complete run
    # that names no output, does not validate.
    broken = dict(refused)
    del broken["status"]
    check(not VALIDATOR.is_valid(broken), "a summary without a status validates")
    broken = dict(refused, status="complete", exit_code=0, error="")
    check(not VALIDATOR.is_valid(broken), "a complete summary without an output validates")
print("passed")
