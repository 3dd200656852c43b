#!/usr/bin/python3
"""Collects a sweep's summaries into one table and a time-vs-accuracy plot.

    scripts/sweep_merge.py OUTDIR [--reference N] [-o OUTDIR/sweep.csv] [--plot OUTDIR/sweep.png]

One CSV row per point of OUTDIR/points.tsv (made by scripts/sweep.sh), in
grid order: the point's --set values, its status, frames, ms/frame (median,
p95), the scheduler's prediction error, wall time, and its accuracy: the
distance of its final positions from those of a reference point, RMS and
max over the vertices (metres). The reference is the grid's last point
unless --reference says otherwise: list each axis's values from cheap to
accurate (substeps 4,8,16; iterations 2,4,8) and the last point is the most
converged one. Points with another vertex count or frame time than the
reference get no accuracy (empty cells). The plot draws accuracy against
ms/frame, one marker per point, labelled with its values.
"""
import argparse
import csv
import json
import math
import pathlib
import sys

import h5py
import numpy as np


def load_points(out):
    rows = []
    for i, line in enumerate((out / "points.tsv").read_text().splitlines()):
        settings = dict(s.split("=", 1) for s in line.split("\t"))
        name = f"p{i:03d}"
        summary = {}
        if (out / f"{name}.json").exists():
            try:
                summary = json.loads((out / f"{name}.json").read_text())
            except json.JSONDecodeError:
                summary = {"status": "unreadable"}
        rows.append({"index": i, "name": name, "settings": settings, "summary": summary})
    return rows


def final_state(path):
    """Time and positions of the last frame, or None when unreadable."""
    try:
        with h5py.File(path, "r") as f:
            return float(f["frames/time"][-1]), f["frames/positions"][-1].astype(np.float64)
    except (OSError, KeyError, IndexError, RuntimeError):  # h5py raises RuntimeError for a broken header
        return None


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("outdir")
    p.add_argument("--reference", type=int, default=-1, help="index of the reference point (default: the last)")
    p.add_argument("-o", "--csv", help="CSV to write (default OUTDIR/sweep.csv)")
    p.add_argument("--plot", help="PNG to write (default OUTDIR/sweep.png)")
    a = p.parse_args()
    out = pathlib.Path(a.outdir)
    if not (out / "points.tsv").exists():
        sys.exit(f"sweep_merge: {out} has no points.tsv (run scripts/sweep.sh first)")
    rows = load_points(out)
    ref = rows[a.reference]
    ref_state = final_state(out / f"{ref['name']}.h5") if ref["summary"].get("status") == "complete" else None
    if ref_state is None:
        print(f"sweep_merge: the reference {ref['name']} is not complete: no accuracy column", file=sys.stderr)

    keys = list(rows[0]["settings"])
    header = ["point", *keys, "status", "frames", "particles", "ms_per_frame_median", "ms_per_frame_p95",
              "prediction_error_median", "wall_s", "rms_error_m", "max_error_m", "reference", "output"]
    table = []
    for r in rows:
        s = r["summary"]
        ms = s.get("ms_per_frame", {})
        rms = mx = ""
        if s.get("status") == "complete" and ref_state is not None:
            state = final_state(out / f"{r['name']}.h5")
            if state is not None and state[1].shape == ref_state[1].shape and math.isclose(state[0], ref_state[0]):
                d = np.linalg.norm(state[1] - ref_state[1], axis=1)
                rms, mx = float(np.sqrt(np.mean(d * d))), float(d.max())
        table.append([r["name"], *[r["settings"].get(k, "") for k in keys], s.get("status", "missing"),
                      s.get("frames", {}).get("written", ""), s.get("particles", ""), ms.get("median", ""),
                      ms.get("p95", ""), s.get("prediction_error", {}).get("median", ""), s.get("wall_s", ""),
                      rms, mx, ref["name"], s.get("output", "")])
    csv_path = pathlib.Path(a.csv) if a.csv else out / "sweep.csv"
    with open(csv_path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows([["" if v is None else v for v in row] for row in table])
    complete = sum(1 for row in table if row[len(keys) + 1] == "complete")
    print(f"sweep_merge: {len(table)} rows ({complete} complete) -> {csv_path}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    i_ms, i_rms = header.index("ms_per_frame_median"), header.index("rms_error_m")
    floor = None
    errors = [row[i_rms] for row in table if isinstance(row[i_rms], float) and row[i_rms] > 0]
    if errors:
        floor = min(errors) / 3  # the reference itself (error 0) sits below the others
    for r, row in zip(rows, table):
        if not isinstance(row[i_ms], (int, float)) or not isinstance(row[i_rms], float):
            continue
        y = row[i_rms] if row[i_rms] > 0 else floor
        if y is None:
            continue
        ax.plot(row[i_ms], y, "o", color="C3" if r is ref else "C0")
        label = ", ".join(f"{k.split('.')[-1]}={v}" for k, v in r["settings"].items())
        ax.annotate(label + (" (reference)" if r is ref else ""), (row[i_ms], y), fontsize=7,
                    xytext=(4, 3), textcoords="offset points")
    ax.set_xlabel("ms per frame (median)")
    ax.set_ylabel(f"RMS distance of final positions from {ref['name']} (m)")
    ax.set_yscale("log")
    ax.set_title(f"{out.name}: time vs accuracy, {len(table)} points")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    plot_path = pathlib.Path(a.plot) if a.plot else out / "sweep.png"
    fig.savefig(plot_path, dpi=120)
    print(f"sweep_merge: plot -> {plot_path}")


if __name__ == "__main__":
    main()
