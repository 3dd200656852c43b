#!/usr/bin/python3
"""Cost of contact between simulated surfaces (scene `contact: {self: true}`):
a square cloth of N x N vertices lying on a sphere (contact thickness a fifth
of the edge), run with self-contact
on and off side by side. Per size: frame time on and off, their ratio, the
contact time per frame (on - off: detection, XPBD's projections, the
contact energy inside VBD's and JPGD's vertex solves, which is no task of
its own), and the share of the last recorded substep the contact tasks
took; then the log-log slope of the contact time over the sizes (each
round's own on - off, the median of those; with several rounds also the
range of each round's own slope), beside the slope of the self-off frame
time, that of the contact time from the fastest frames (the shortest
frame after the skip over every round, on less off: noise only slows a
frame, so these are the least disturbed) and that of the contact tasks'
own time, measured task by task (each frame's recorded substep times the
substeps, the median over frames and rounds; without the contact terms
inside VBD's and JPGD's vertex solve, which are no task). The last
substep is a frame's last, which often keeps the pair lists (detection
rebuilds them when the motion since they were made outgrows them; they are
kept across frames), so its breakdown by task shows a kept substep; a
frame's mean is in on - off.
Frame time is /timing/frame_ms (the substeps on the device); the host's own
work on each frame (/timing/host_ms: with self-contact mostly the per-frame
surface record, /contact/surface_*) comes after it and before the next
frame, so the last column, (frame + host) on over off, is what a frame of
wall time costs.

usage: scripts/bench_self_contact.py [--sizes 128,256] [--frames 4] [--skip 2] [--methods vbd,xpbd] [--rounds 1]
                                     [--query-radius K]   (contact.query_radius = K thicknesses; unset: 3)
                                     [--bin PATH]         (the atssim binary; default build/release/atssim)
Build first (cmake --build --preset release). Prints one Markdown table.
"""
import argparse
import collections
import json
import math
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "release", "atssim")
NATIVE = os.path.join(ROOT, "build", "release", "bench", "bench_native")

SCENE = """simulation: {{fps: 60, substeps: {substeps}, iterations: {iterations}, frames: {frames}}}
objects:
  - {{name: cloth, grid: {{size: [2, 2], resolution: [{n}, {n}]}}, transform: {{translate: [0, 0.505, 0]}},
     material: {{density: 0.2, stretch_stiffness: 1000, bend_stiffness: 0.0001}}}}
colliders:
  - {{type: sphere, center: [0, 0, 0], radius: 0.5, thickness: 0.004}}
contact: {{self: {self}, thickness: {thickness}{query}}}
"""

CONTACT_KINDS = {"detection"}


def thickness(n):
    """A fifth of the edge (2 m / (n - 1)): the same relative thickness at
    every size, so the pairs per vertex stay alike (at 128 x 128: 3.1 mm)."""
    return round(0.2 * 2.0 / (n - 1), 6)
def query(n, args):
    """contact.query_radius as --query-radius thicknesses, or nothing (the default, 3)."""
    return "" if args.query_radius is None else f", query_radius: {args.query_radius * thickness(n):.6f}"


CONTACT_NAMES = ("collision/bound", "collision/surface", "contact/first_guess")


Run = collections.namedtuple("Run", "frame_ms host_ms contact substep by_name fastest_ms tasks_ms")
Point = collections.namedtuple("Point", "vertices paired rounds off fastest tasks")


def run(tmp, n, method, self_on, args):
    """One run's frame time (median and fastest after the skip), host time,
    and its contact tasks: their time in the last recorded substep (with that
    substep's length and their time by name) and their own time per frame."""
    scene = os.path.join(tmp, f"s{n}{method}{int(self_on)}.yaml")
    out = os.path.join(tmp, f"o{n}{method}{int(self_on)}.h5")
    with open(scene, "w") as f:
        f.write(SCENE.format(substeps=args.substeps, iterations=args.iterations, frames=args.frames, n=n,
                             self="true" if self_on else "false", thickness=thickness(n), query=query(n, args)))
    subprocess.run([args.bin, "run", scene, "-o", out, "--devices", args.devices, "--set", f"solver.method={method}",
                    "--quiet"], check=True)
    with h5py.File(out, "r") as f:
        frame_ms = float(np.median(f["timing/frame_ms"][args.skip:]))
        fastest_ms = float(np.min(f["timing/frame_ms"][args.skip:]))
        host_ms = float(np.median(f["timing/host_ms"][args.skip:]))
        names = [s.decode() if isinstance(s, bytes) else s for s in f["schedule/tasks/name"][:]]
        kinds = [s.decode() if isinstance(s, bytes) else s for s in f["schedule/tasks/kind"][:]]
        is_contact_task = np.array([kind in CONTACT_KINDS or any(k in name for k in CONTACT_NAMES)
                                    for name, kind in zip(names, kinds)], dtype=bool)
        s = f["schedule"]
        frames, task = s["frame"][:], s["task"][:]
        start, finish = s["measured_start_ms"][:], s["measured_finish_ms"][:]
    took = finish - start
    is_contact = is_contact_task[task]
    last = frames == frames.max()
    contact = float(np.sum(took[last & is_contact]))
    by_name = {}
    for t, ms in zip(task[last & is_contact], took[last & is_contact]):
        base = names[t].split("[")[0]
        by_name[base] = by_name.get(base, 0.0) + float(ms)
    substep = float(np.nanmax(finish[last]) - np.nanmin(start[last]))
    # The contact tasks' own time, measured task by task rather than as a
    # difference of two runs: each frame's recorded substep (its last) times
    # the substeps, the median over the frames after the skip. The contact
    # work inside the vertex solves is not in it.
    per_frame = [float(np.sum(took[(frames == fr) & is_contact])) * args.substeps
                 for fr in np.unique(frames) if fr > args.skip]
    tasks_ms = float(np.median(per_frame)) if per_frame else float("nan")
    return Run(frame_ms, host_ms, contact, substep, by_name, fastest_ms, tasks_ms)


def native_ms(tmp, n, method, args):
    """The native host loop (bench/bench_native: the host XPBD/VBD reference,
    2 threads) on the same cloth: it has no contact of any kind, so it is the
    reference for the elastic part only."""
    scene = os.path.join(tmp, f"native{n}.yaml")
    with open(scene, "w") as f:
        f.write(SCENE.format(substeps=args.substeps, iterations=args.iterations, frames=args.frames, n=n,
                             self="false", thickness=thickness(n), query="").replace("colliders:", "unused_colliders:").split("unused_colliders:")[0])
    # VBD's native loop in VBD's default ordering, color_batches (the same lanes on the host)
    ordering = ["--ordering", "color_batches"] if method == "vbd" else []
    out = subprocess.run([NATIVE, "--scene", scene, "--method", method, "--resolution", str(n), "--threads", "2",
                          "--frames", str(args.frames), "--warmup", "1"] + ordering,
                         check=True, capture_output=True, text=True)
    return json.loads(out.stdout)["median_ms"]


def slope_line(method, points):
    """The log-log slope of the contact time between the first and last
    size: of the medians, with the range of each round's own (round r's on -
    off at both sizes), and beside it the slope of the self-off frame time,
    the solve's own growth with size on this machine (cache effects included),
    against which the contact time's can be read."""
    (v0, c0, r0, off0, f0, t0), (v1, c1, r1, off1, f1, t1) = points[0], points[-1]  # Point
    slope = lambda a, b: math.log(b / a) / math.log(v1 / v0)
    off = f"; of the self-off frame time: {slope(off0, off1):.2f}"
    fast = ", ".join(f"{p.fastest:.1f}" for p in points)
    off += (f"; of the fastest frames' contact time ({fast} ms): "
            + (f"{slope(f0, f1):.2f}" if f0 > 0 and f1 > 0 else "none (not positive)"))
    tasks = ", ".join(f"{p.tasks:.1f}" for p in points)
    off += (f"; of the contact tasks' own time ({tasks} ms a frame, each frame's recorded substep times the "
            f"substeps): " + (f"{slope(t0, t1):.2f}" if t0 > 0 and t1 > 0 else "none"))
    if not (c0 > 0 and c1 > 0):
        return (f"| {method} | no slope: a contact time (on - off) is not positive, the noise is larger "
                f"than it; use more --rounds{off} | | | | | |")
    per_round = [slope(a, b) for a, b in zip(r0, r1) if a > 0 and b > 0]
    if len(r0) < 2:
        spread = ""
    elif per_round:
        spread = (f" (rounds {min(per_round):.2f}–{max(per_round):.2f}, {len(per_round)} of {len(r0)} with both "
                  f"contact times positive)")
    else:
        spread = f" (no round of {len(r0)} has both contact times positive)"
    return (f"| {method} | log-log slope of the contact time, {v0} → {v1} vertices: {slope(c0, c1):.2f}"
            f"{spread}{off} | | | | | |")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="128,256", help="vertices per side, comma separated")
    ap.add_argument("--frames", type=int, default=4)
    ap.add_argument("--skip", type=int, default=2, help="frames left out before the median (warm-up, settling)")
    ap.add_argument("--substeps", type=int, default=4)
    ap.add_argument("--iterations", type=int, default=4)
    ap.add_argument("--methods", default="vbd,xpbd")
    ap.add_argument("--devices", default="cpu")
    ap.add_argument("--rounds", type=int, default=1,
                    help="off/on pairs per size, alternated; the median ratio is printed with its range")
    ap.add_argument("--query-radius", type=float, default=None,
                    help="contact.query_radius in thicknesses (unset: the scene default, 3)")
    ap.add_argument("--bin", default=BIN,
                    help="the atssim binary to measure (default: this checkout's release build); an older "
                         "commit's build, run right after, gives a before/after in one sitting")
    args = ap.parse_args()
    if not os.path.exists(args.bin):
        print(f"{args.bin} is missing: build first", file=sys.stderr)
        return 2
    os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
    sizes = [int(s) for s in args.sizes.split(",")]
    print("| method | vertices | frame ms, self off | frame ms, self on | on/off | contact ms/frame (on - off) | "
          "contact tasks' share of the last substep | host ms, self off | host ms, self on | "
          "on/off, frame + host |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    breakdown = []
    with tempfile.TemporaryDirectory() as tmp:
        for method in args.methods.split(","):
            points = []
            for n in sizes:
                # Off and on alternated, round by round, in turn first; each
                # round's ratio from its own pair, their median printed with
                # their range (a noisy VM moves single runs by 30 %).
                rounds = []
                for r in range(args.rounds):
                    pair = {}
                    for self_on in ((False, True) if r % 2 == 0 else (True, False)):
                        pair[self_on] = run(tmp, n, method, self_on, args)
                    rounds.append(pair)
                med = lambda xs: float(np.median(xs))
                off = med([p[False].frame_ms for p in rounds])
                host_off = med([p[False].host_ms for p in rounds])
                on = med([p[True].frame_ms for p in rounds])
                host_on = med([p[True].host_ms for p in rounds])
                ratios = [p[True].frame_ms / p[False].frame_ms for p in rounds]
                ratios_host = [(p[True].frame_ms + p[True].host_ms) / (p[False].frame_ms + p[False].host_ms)
                               for p in rounds]
                last = rounds[-1][True]
                contact, substep = last.contact, last.substep
                breakdown.append((method, n * n, last.by_name))
                # The contact time from each round's own pair (on - off),
                # then the median: a sitting's drift cancels within a pair.
                own = [p[True].frame_ms - p[False].frame_ms for p in rounds]
                # And from the fastest frames: the shortest frame after the
                # skip over every round, on less off. A VM's noise only ever
                # slows a frame, so the fastest frames are the least
                # disturbed (the "fastest of N" of scripts/bench_devices.py).
                fastest = min(p[True].fastest_ms for p in rounds) - min(p[False].fastest_ms for p in rounds)
                paired = med(own)
                points.append(Point(n * n, paired, own, off, fastest, med([p[True].tasks_ms for p in rounds])))
                spread = lambda xs: f" ({min(xs):.2f}–{max(xs):.2f})" if len(xs) > 1 else ""
                print(f"| {method} | {n * n} | {off:.1f} | {on:.1f} | {med(ratios):.2f}{spread(ratios)} | "
                      f"{paired:.2f} | {100 * contact / substep:.0f} % | {host_off:.1f} | {host_on:.1f} | "
                      f"{med(ratios_host):.2f}{spread(ratios_host)} |", flush=True)
                if method in ("xpbd", "vbd") and os.path.exists(NATIVE):
                    print(f"| native {method} (host reference{', color_batches' if method == 'vbd' else ''}, 2 threads, no contact) | {n * n} | "
                          f"{native_ms(tmp, n, method, args):.1f} | – | – | – | – | – | – | – |", flush=True)
            if len(points) >= 2:
                print(slope_line(method, points), flush=True)
    print("\nThe last substep's four largest contact tasks by name (ms, times the substeps):\n")
    print("| method | vertices | tasks |")
    print("|---|---|---|")
    for method, v, by_name in breakdown:
        top = sorted(by_name.items(), key=lambda kv: -kv[1])[:4]
        print(f"| {method} | {v} | " + ", ".join(f"{k} {ms * args.substeps:.2f}" for k, ms in top) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
