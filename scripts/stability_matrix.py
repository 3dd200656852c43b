#!/usr/bin/env python3
"""The stability matrix (issue #13): every method x stretch stiffness x
substep x mass ratio x iterations x start state, sampled so that it runs in
minutes, each cell a small hanging cloth run by tests/stability/stability_cell.

A cell passes when every frame stays finite and the closed system's total
energy (kinetic + gravity + elastic, measured per frame) never rises above its
start by more than 1 % of its scale (stability_cell.cpp says which); a cell
whose scene the method refuses before running (one line, exit 2 from atssim)
counts as refused, not failed. Prints a table per sweep and writes every
cell's JSON.

The energy criterion measures under-convergence as much as instability
(docs/accuracy.md), and implicit cells fail it at 8 iterations as a matter
of course; those failures are reported, not fatal. The script exits 1 when
a cell breaks what docs/accuracy.md says every cell shows: a cell ended in
an error or a timeout, a frame went non-finite, an explicit integrator's
cell failed instead of passing or being refused, or an SOSD or JPGD cell
moved the cloth up (its centroid drop below zero; their safe defaults on
stiff scenes, solver/vertex/stiffness_ratio.hpp).

  scripts/stability_matrix.py --binary build/release/tests/stability/stability_cell [--output m.json]
"""
import argparse
import itertools
import json
import subprocess
import sys
import time

METHODS = ["xpbd", "vbd", "sosd", "jpgd", "explicit:semi_euler", "explicit:midpoint", "explicit:rk4"]
IMPLICIT = METHODS[:4]


def cells():
    """(sweep, method, options) of every sampled cell."""
    for m, k, h in itertools.product(METHODS, [1e0, 1e3, 1e6, 1e9, 1e12], [1e-3, 1e-2, 1e-1]):
        yield "stiffness x substep", m, {"stiffness": k, "substep": h}
    for m, r, k in itertools.product(METHODS, [1e3, 1e6], [1e3, 1e9]):
        yield "mass ratio", m, {"stiffness": k, "substep": 1e-2, "mass-ratio": r}
    for m, it in itertools.product(IMPLICIT, [1, 10, 100, 1000]):
        yield "iterations", m, {"stiffness": 1e6, "substep": 1e-2, "iterations": it}
    for m, state, k in itertools.product(METHODS, ["degenerate", "inverted"], [1e3, 1e9]):
        yield "start state", m, {"stiffness": k, "substep": 1e-2, "state": state}
    # The case of issue #13: SOSD, density 1e-6 kg/m², stiffness 1e12, 60 fps x 16 substeps, 10 frames.
    for m in METHODS:
        yield "light and stiff", m, {"stiffness": 1e12, "density": 1e-6, "substep": 1.0 / 960.0, "grid": 16,
                                     "substeps-per-frame": 16, "frames": 10}


def run_cell(binary, method, options, timeout):
    name, _, integrator = method.partition(":")
    cmd = [binary, "--method", name]
    if integrator:
        cmd += ["--integrator", integrator]
    for key, value in options.items():
        cmd += [f"--{key}", repr(value) if isinstance(value, float) else str(value)]
    start = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"outcome": "timeout", "seconds": timeout}
    result = {"outcome": "error", "stderr": p.stderr.strip()[-400:], "exit": p.returncode}
    for line in p.stdout.splitlines():
        if line.startswith("{"):
            result = json.loads(line)
    result["seconds"] = round(time.monotonic() - start, 2)
    return result


def label(options):
    return ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in options.items())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--binary", required=True, help="tests/stability/stability_cell")
    ap.add_argument("--output", help="write every cell's result here (JSON)")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per cell (a cell past it fails)")
    ap.add_argument("--only", help="run only the sweep of this name")
    args = ap.parse_args()
    results = []
    for sweep, method, options in cells():
        if args.only and sweep != args.only:
            continue
        r = run_cell(args.binary, method, options, args.timeout)
        r.update({"sweep": sweep, "method": method, "options": options})
        results.append(r)
        extra = ""
        if r["outcome"] in ("pass", "fail"):
            extra = (f"rise {r['rise']:.3g} J (tolerance {r['tolerance']:.3g}), finite {r['finite']}, "
                     f"drop {r['drop']:.3g} m (free fall {r['free_fall']:.3g}), "
                     f"h²λmax {r['stiffness_to_inertia']:.2g}")
        elif r["outcome"] == "refused":
            extra = r["message"][:160]
        else:
            extra = json.dumps({k: r[k] for k in r if k in ("stderr", "exit", "seconds")})
        print(f"{r['outcome']:8} {sweep:20} {method:20} {label(options):60} {extra}", flush=True)
    if args.output:
        with open(args.output, "w") as f:
            json.dump(results, f, indent=1)
    counts = {}
    for r in results:
        counts[r["outcome"]] = counts.get(r["outcome"], 0) + 1
    print("summary:", ", ".join(f"{v} {k}" for k, v in sorted(counts.items())))
    by_method = {}
    for r in results:
        by_method.setdefault(r["method"], {}).setdefault(r["outcome"], 0)
        by_method[r["method"]][r["outcome"]] += 1
    for m, c in by_method.items():
        print(f"  {m:20}", ", ".join(f"{v} {k}" for k, v in sorted(c.items())))
    broken = []
    for r in results:
        where = f"{r['sweep']}, {r['method']}, {label(r['options'])}"
        if r["outcome"] not in ("pass", "fail", "refused"):
            broken.append(f"{where}: {r['outcome']}")
        elif r["outcome"] == "refused":
            continue
        elif not r["finite"]:
            broken.append(f"{where}: non-finite")
        elif r["method"].startswith("explicit") and r["outcome"] != "pass":
            broken.append(f"{where}: an explicit cell that runs must pass (rise {r['rise']:.3g} J)")
        elif r["method"] in ("sosd", "jpgd") and r["drop"] < 0.0:
            broken.append(f"{where}: the cloth moved up ({-r['drop']:.3g} m)")
    for b in broken:
        print("BROKEN:", b)
    print(f"{len(broken)} cells break what the matrix claims")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
