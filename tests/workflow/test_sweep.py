#!/usr/bin/python3
"""A 3×3 sweep (substeps × iterations) under GNU parallel with 2 jobs, or as
a Slurm job array: killed halfway (SIGKILL to the whole process group),
run again, it finishes the rest without re-running finished points, and the
merged table has 9 rows.

    test_sweep.py parallel     # GNU parallel, killed halfway and resumed
    test_sweep.py slurm        # a Slurm array on the running one-node cluster
                               # (scripts/slurm_cluster.sh start)
"""
import csv
import glob
import os
import signal
import subprocess
import sys
import time

from workflow_common import ATSSIM, SCRIPTS, check, fail, require_tool, run, scene, temp_dir

GRID = ["--set", "simulation.substeps=2,4,8", "--set", "simulation.iterations=2,4,8"]
# One compute unit a point: two points at once share this machine's 2 cores.
RUN_ARGS = ["--", "--frames", "200", "--devices", "cpu/2:0", "--set", "objects.0.grid.resolution=[32, 32]"]


def sweep_command(out, backend):
    return ["bash", os.path.join(SCRIPTS, "sweep.sh"), scene("hanging_cloth"), out, *GRID, "--backend", backend,
            "--jobs", "2", *RUN_ARGS]


def complete_points(out):
    done = []
    for path in sorted(glob.glob(os.path.join(out, "p*.json"))):
        with open(path) as f:
            if '"status": "complete"' in f.read():
                done.append(os.path.basename(path)[:-5])
    return done


def session_processes(session):
    """The live (not yet zombie) processes of a session."""
    found = []
    for stat in glob.glob("/proc/[0-9]*/stat"):
        try:
            with open(stat) as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        # fields after "(comm)": state, ppid, pgrp, session
        if int(fields[3]) == session and fields[0] != "Z":
            found.append(int(stat.split("/")[2]))
    return found


def signal_session(session, sig, settled):
    """Send `sig` to every process of a session until `settled(pid)` holds for
    each live one. One pass is not enough: a process forked while /proc is
    being read (GNU parallel starting the next point, a point script starting
    its `mv`) escapes it."""
    deadline = time.time() + 30
    while time.time() < deadline:
        pending = [pid for pid in session_processes(session) if not settled(pid)]
        if not pending:
            return
        for pid in pending:
            try:
                os.kill(pid, sig)
            except ProcessLookupError:
                pass
        time.sleep(0.01)
    fail(f"processes of session {session} do not take signal {sig}: {session_processes(session)}")


def process_state(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0]
    except OSError:
        return "X"


def freeze_session(session):
    """SIGSTOP the whole session, so that no point can finish while the test
    decides whether to kill it now."""
    signal_session(session, signal.SIGSTOP, lambda pid: process_state(pid) in "TtXZ")


def thaw_session(session):
    for pid in session_processes(session):
        try:
            os.kill(pid, signal.SIGCONT)
        except ProcessLookupError:
            pass


def kill_session(session):
    """SIGKILL every process of a session: GNU parallel puts each job in a
    process group of its own, so killing the sweep's group would leave the
    running atssim processes behind; kill until none is left, so that no
    process forked meanwhile finishes a point after the test has counted the
    complete ones."""
    signal_session(session, signal.SIGKILL, lambda pid: False)


def check_merged(out):
    r = run([sys.executable, os.path.join(SCRIPTS, "sweep_merge.py"), out])
    check(r.returncode == 0, f"sweep_merge: {r.stderr}")
    with open(os.path.join(out, "sweep.csv")) as f:
        rows = list(csv.DictReader(f))
    print(open(os.path.join(out, "sweep.csv")).read())
    check(len(rows) == 9, f"the merged table has {len(rows)} rows, not 9")
    check(all(row["status"] == "complete" for row in rows), "every row is complete")
    check({(r["simulation.substeps"], r["simulation.iterations"]) for r in rows} ==
          {(s, i) for s in "248" for i in "248"}, "the rows are the 3×3 grid")
    check(float(rows[-1]["rms_error_m"]) == 0.0, "the reference point is at distance 0 from itself")
    check(float(rows[0]["rms_error_m"]) > float(rows[-2]["rms_error_m"]),
          "2 substeps × 2 iterations are further from the reference than 8 × 4")
    check(os.path.getsize(os.path.join(out, "sweep.png")) > 10000, "the time-vs-accuracy plot")
    for i in range(9):
        for ext in ("h5", "xdmf", "json"):
            check(os.path.exists(os.path.join(out, f"p{i:03d}.{ext}")), f"p{i:03d}.{ext} exists")
        r = run([ATSSIM, "inspect", os.path.join(out, f"p{i:03d}.h5")])
        check("status:    complete" in r.stdout, f"p{i:03d}.h5 is complete")


def parallel(out):
    require_tool("parallel", "bash scripts/setup.sh")
    # Start the sweep in its own session and kill all of it (GNU parallel and
    # the atssim runs) once some points are complete and others are not.
    print("$", " ".join(sweep_command(out, "parallel")), flush=True)
    proc = subprocess.Popen(sweep_command(out, "parallel"), start_new_session=True, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    def halfway():
        done = complete_points(out)
        running = [p for p in glob.glob(os.path.join(out, "p*.h5")) if os.path.basename(p)[:-3] not in done]
        return len(done) >= 3 and running

    # A point can finish between a look at the files and the kill: freeze the
    # sweep, look again, and kill only while the look still holds.
    deadline = time.time() + 300
    while proc.poll() is None and time.time() < deadline:
        if halfway():
            freeze_session(proc.pid)
            if halfway():
                break
            thaw_session(proc.pid)
        time.sleep(0.02)
    kill_session(proc.pid)
    proc.wait()
    time.sleep(0.5)  # let the killed runs' files settle
    print(proc.stdout.read())
    before = complete_points(out)
    in_flight = [os.path.basename(p)[:-3] for p in glob.glob(os.path.join(out, "p*.h5"))
                 if os.path.basename(p)[:-3] not in before]
    print("complete when killed:", before, "killed mid-run:", in_flight)
    check(3 <= len(before) < 9, f"the kill came too late to show a resume ({len(before)} of 9 complete)")
    check(in_flight, "no point was running when the sweep was killed")
    stamps = {p: os.stat(os.path.join(out, p + ".h5")).st_mtime_ns for p in before}

    r = run(sweep_command(out, "parallel"))
    print(r.stdout, r.stderr)
    check(r.returncode == 0, "the resumed sweep succeeds")
    check(f"{len(before)} complete already, {9 - len(before)} to run" in r.stderr, "it runs only the rest")
    for p in before:
        check(os.stat(os.path.join(out, p + ".h5")).st_mtime_ns == stamps[p], f"{p} was not run again")
    check_merged(out)


def slurm(out):
    require_tool("sbatch", "bash scripts/setup.sh slurm")
    r = run(["sinfo", "-h", "-o", "%T"])
    if r.returncode != 0 or "idle" not in r.stdout and "mix" not in r.stdout:
        fail(f"no Slurm cluster answers (start one with scripts/slurm_cluster.sh start): {r.stdout}{r.stderr}")
    r = run(sweep_command(out, "slurm"))
    print(r.stdout, r.stderr)
    check(r.returncode == 0, "the Slurm sweep succeeds")
    check("Slurm job array" in r.stderr, "it ran as a job array")
    logs = glob.glob(os.path.join(out, "slurm-*_*.out"))
    check(len(logs) == 9, f"{len(logs)} array task logs, not 9")
    check_merged(out)
    # Run again: every point is complete, nothing is submitted.
    r = run(sweep_command(out, "slurm"))
    check(r.returncode == 0 and "9 complete already, 0 to run" in r.stderr, "a second run submits nothing")


if __name__ == "__main__":
    which = sys.argv[1] if len(sys.argv) > 1 else fail("usage: test_sweep.py parallel|slurm")
    with temp_dir() as d:
        {"parallel": parallel, "slurm": slurm}[which](os.path.join(d, "sweep"))
    print("passed")
