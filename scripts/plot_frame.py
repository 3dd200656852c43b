#!/usr/bin/python3
"""Draw one frame of an atssim result as a shaded triangle mesh (PNG).

usage: scripts/plot_frame.py OUT.h5 [--frame K] [-o frame.png] [--no-colliders]
                             [--elev DEG] [--azim DEG]
The scene's colliders (from /scene/resolved) are drawn in grey where they
are at the frame's time: planes as a square patch, spheres, capsules, boxes
and meshes (the OBJ file the scene names) as wireframes.
Needs Debian's python3-h5py, python3-matplotlib, python3-numpy and
python3-yaml (scripts/setup.sh).
"""
import argparse
import math
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

try:
    import yaml
except ImportError:  # colliders are then not drawn
    yaml = None


def rotation_xyz_deg(deg):
    """About x, then y, then z (as the scene's rotate/rotation keys)."""
    rx, ry, rz = (math.radians(d) for d in deg)
    cx, sx, cy, sy, cz, sz = math.cos(rx), math.sin(rx), math.cos(ry), math.sin(ry), math.cos(rz), math.sin(rz)
    x = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    y = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    z = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return z @ y @ x


def axis_angle(w, angle):
    n = np.linalg.norm(w)
    if n == 0 or angle == 0:
        return np.eye(3)
    k = np.asarray(w, float) / n
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * kx + (1 - math.cos(angle)) * kx @ kx


def pivot_of(c):
    if c["type"] == "capsule":
        return 0.5 * (np.array(c["a"], float) + np.array(c["b"], float))
    if c["type"] == "plane":
        return np.array(c["point"], float)
    if c["type"] == "mesh":
        return np.array(c["position"], float)
    return np.array(c["center"], float)


def pose(c, t):
    """(rotation, pivot) at time t, as lib/model/collider_pose.cpp."""
    p0 = pivot_of(c)
    if "velocity" in c:
        w = np.array(c.get("angular_velocity", [0, 0, 0]), float)
        return axis_angle(w, np.linalg.norm(w) * t), p0 + t * np.array(c["velocity"], float)
    keys = c.get("keyframes")
    if keys:
        if t <= keys[0]["time"]:
            k = keys[0]
            return rotation_xyz_deg(k.get("rotation", [0, 0, 0])), np.array(k["position"], float)
        if t >= keys[-1]["time"]:
            k = keys[-1]
            return rotation_xyz_deg(k.get("rotation", [0, 0, 0])), np.array(k["position"], float)
        i = next(i for i, k in enumerate(keys) if k["time"] >= t)
        a, b = keys[i - 1], keys[i]
        s = (t - a["time"]) / (b["time"] - a["time"])
        # the drawing interpolates the rotation angles (the simulation slerps)
        deg = (1 - s) * np.array(a.get("rotation", [0, 0, 0]), float) + s * np.array(b.get("rotation", [0, 0, 0]), float)
        return rotation_xyz_deg(deg), (1 - s) * np.array(a["position"], float) + s * np.array(b["position"], float)
    return np.eye(3), p0


def read_obj(path):
    vs, fs = [], []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                vs.append([float(x) for x in w[1:4]])
            elif w[0] == "f":
                idx = [int(x.split("/")[0]) - 1 for x in w[1:]]
                for k in range(1, len(idx) - 1):
                    fs.append([idx[0], idx[k], idx[k + 1]])
    return np.array(vs), np.array(fs)


def draw(ax, pts, tris=None, **kw):
    """pts in atssim's y-up frame; matplotlib's 3-D axes are z-up."""
    if tris is None:
        ax.plot(pts[:, 0], pts[:, 2], pts[:, 1], **kw)
    else:
        ax.plot_trisurf(pts[:, 0], pts[:, 2], pts[:, 1], triangles=tris, color="0.6", alpha=0.25,
                        linewidth=0.2, edgecolor="0.35")


def draw_collider(ax, c, t, extent):
    r, pivot = pose(c, t)
    p0 = pivot_of(c)
    place = lambda x: (r @ (np.asarray(x, float) - p0).T).T + pivot  # noqa: E731
    kind = c["type"]
    u = np.linspace(0, 2 * math.pi, 25)
    if kind == "sphere":
        centre, rad = place(np.array(c["center"], float)[None])[0], c["radius"]
        v = np.linspace(0, math.pi, 13)
        x = centre[0] + rad * np.outer(np.cos(u), np.sin(v))
        y = centre[1] + rad * np.outer(np.ones_like(u), np.cos(v))
        z = centre[2] + rad * np.outer(np.sin(u), np.sin(v))
        ax.plot_wireframe(x, z, y, color="0.5", linewidth=0.4)
    elif kind == "capsule":
        a, b = place(np.array([c["a"], c["b"]], float))
        draw(ax, np.array([a, b]), color="0.4", linewidth=3)
    elif kind == "box":
        half = 0.5 * np.array(c["size"], float)
        rot = rotation_xyz_deg(c.get("rotate", [0, 0, 0]))
        corners = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]) * half
        pts = place((rot @ corners.T).T + np.array(c["center"], float))
        for i in range(8):
            for j in range(i + 1, 8):
                if bin(i ^ j).count("1") == 1:
                    draw(ax, pts[[i, j]], color="0.4", linewidth=0.8)
    elif kind == "plane":
        n = r @ (np.array(c.get("normal", [0, 1, 0]), float))
        n /= np.linalg.norm(n)
        e1 = np.cross(n, [0, 0, 1] if abs(n[2]) < 0.9 else [1, 0, 0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
        p = pivot
        quad = np.array([p + extent * (sa * e1 + sb * e2) for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1), (-1, -1))])
        draw(ax, quad, color="0.5", linewidth=0.8)
    elif kind == "mesh":
        path = c["file"]
        if not os.path.exists(path):
            print(f"collider {c.get('name')}: {path} not found, not drawn", file=sys.stderr)
            return
        vs, fs = read_obj(path)
        local = vs * np.array(c.get("scale", [1, 1, 1]), float)
        world = (rotation_xyz_deg(c.get("rotation", [0, 0, 0])) @ local.T).T + np.array(c["position"], float)
        draw(ax, place(world), fs)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("--frame", type=int, default=-1, help="frame index (default: last)")
    ap.add_argument("-o", "--output", default="frame.png")
    ap.add_argument("--no-colliders", action="store_true", help="draw the simulated objects only")
    ap.add_argument("--elev", type=float, default=None, help="camera elevation in degrees")
    ap.add_argument("--azim", type=float, default=None, help="camera azimuth in degrees")
    args = ap.parse_args()
    try:
        f = h5py.File(args.result, "r", swmr=True)
    except OSError as e:
        print(f"{args.result}: cannot open ({e})", file=sys.stderr)
        return 2
    with f:
        fmt = f.attrs.get("format", b"")
        if (fmt.decode() if isinstance(fmt, bytes) else fmt) != "atssim":
            print(f"{args.result}: not an atssim result file", file=sys.stderr)
            return 2
        positions = f["frames/positions"]
        frames = positions.shape[0]
        k = args.frame if args.frame >= 0 else frames + args.frame
        if not 0 <= k < frames:
            print(f"{args.result}: frame {args.frame} does not exist ({frames} frames)", file=sys.stderr)
            return 2
        x = positions[k]
        t = f["frames/time"][k]
        fig = plt.figure(figsize=(6, 6))
        ax = fig.add_subplot(projection="3d")
        for name, group in f["mesh"].items():
            off = int(group.attrs["vertex_offset"])
            n = int(group.attrs["vertex_count"])
            p = x[off:off + n]
            tris = group["triangles"][:] if "triangles" in group else None
            if tris is None or len(tris) == 0:
                ax.scatter(p[:, 0], p[:, 2], p[:, 1], s=2)
                continue
            # atssim is y-up; matplotlib's 3-D axes are z-up.
            ax.plot_trisurf(p[:, 0], p[:, 2], p[:, 1], triangles=tris, cmap="viridis",
                            linewidth=0.1, edgecolor="k", alpha=0.9)
        if not args.no_colliders and yaml is not None and "scene/resolved" in f:
            text = f["scene/resolved"][()]
            scene = yaml.safe_load(text.decode() if isinstance(text, bytes) else text)
            extent = 0.5 * float(np.max(np.ptp(x, axis=0))) + 0.2
            for c in scene.get("colliders", []) or []:
                draw_collider(ax, c, float(t), extent)
        lo, hi = x.min(axis=0), x.max(axis=0)
        mid, half = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo)) + 0.15
        ax.set_xlim(mid[0] - half, mid[0] + half)
        ax.set_ylim(mid[2] - half, mid[2] + half)
        ax.set_zlim(mid[1] - half, mid[1] + half)
        if args.elev is not None or args.azim is not None:
            ax.view_init(elev=args.elev, azim=args.azim)
        ax.set_xlabel("x")
        ax.set_ylabel("z")
        ax.set_zlabel("y")
        ax.set_title(f"{os.path.basename(args.result)}: frame {k}, t = {t:.3f} s")
        fig.savefig(args.output, dpi=100)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
