#!/usr/bin/python3
"""Reads an atssim XDMF sidecar with meshio and checks it against h5py.

    scripts/check_meshio.py OUT.xdmf

meshio's TimeSeriesReader (Debian's python3-meshio 7.0) is a second reader,
independent of ParaView: every frame's "positions" must equal
/frames/positions[k] of the HDF5 file bit for bit, its times /frames/time,
and its cells each object's triangles and tetrahedra. Prints one JSON line;
exit 1 on any difference, 77 when meshio is not installed
(scripts/setup.sh installs it).
"""
import argparse
import json
import pathlib
import sys

import h5py
import numpy as np

try:
    import meshio
except ImportError:
    print("check_meshio: python3-meshio is not installed (bash scripts/setup.sh)", file=sys.stderr)
    sys.exit(77)


def expected_cells(f):
    tris, tets = [], []
    for name in f["mesh"]:
        g = f["mesh"][name]
        off = int(g.attrs["vertex_offset"])
        tris.append(g["triangles"][:].reshape(-1, 3) + off)
        tets.append(g["tetrahedra"][:].reshape(-1, 4) + off)
    return np.concatenate(tris), np.concatenate(tets)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("xdmf")
    a = p.parse_args()
    xdmf = pathlib.Path(a.xdmf)
    problems = []
    with meshio.xdmf.TimeSeriesReader(str(xdmf)) as reader, h5py.File(xdmf.with_suffix(".h5"), "r") as f:
        points, cells = reader.read_points_cells()
        x = f["frames/positions"]
        times = f["frames/time"][:]
        if reader.num_steps != x.shape[0]:
            problems.append(f"meshio sees {reader.num_steps} frames, the HDF5 file has {x.shape[0]}")
        if not np.array_equal(points, x[0]):
            problems.append("the mesh's points differ from frame 0")
        tris = np.concatenate([c.data for c in cells if c.type == "triangle"] or [np.zeros((0, 3), int)])
        tets = np.concatenate([c.data for c in cells if c.type == "tetra"] or [np.zeros((0, 4), int)])
        want_tris, want_tets = expected_cells(f)
        if not (np.array_equal(tris, want_tris) and np.array_equal(tets, want_tets)):
            problems.append("the cells differ from /mesh/*/triangles and tetrahedra")
        max_diff = 0.0
        for k in range(min(reader.num_steps, x.shape[0])):
            t, point_data, _ = reader.read_data(k)
            frame = point_data.get("positions")
            if frame is None:
                problems.append(f"frame {k} has no positions")
                continue
            if t != float(f"{times[k]:.9g}"):
                problems.append(f"frame {k}: time {t} != {times[k]}")
            if not np.array_equal(frame, x[k]):
                max_diff = max(max_diff, float(np.abs(frame - x[k]).max()))
                problems.append(f"frame {k}: positions differ (max {max_diff:g})")
    report = {"xdmf": str(xdmf), "frames": reader.num_steps, "points": len(points), "triangles": len(tris),
              "tetrahedra": len(tets), "equal_to_h5py": not problems}
    print(json.dumps(report))
    for problem in problems[:10]:
        print("check_meshio:", problem, file=sys.stderr)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
