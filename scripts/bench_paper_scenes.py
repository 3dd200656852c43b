#!/usr/bin/python3
"""The paper's five scenes (He et al. 2025, Table 1) on this machine's CPU.

For each scene of scenes/paper/ (the paper-size YAML, or with --small its
_small variant): vertices, cloth triangles, tetrahedra, substeps,
iterations, contacts per frame, and ms/frame (XPBD, the paper's Table 1
method, unless --method) in four set-ups:
  sub     one 1-CU pocl sub-device   (--devices cpu/2:0 --schedule single)
  whole   the whole 2-CU CPU device  (--devices cpu --schedule single)
  split   two 1-CU sub-devices       (--devices cpu/2 --schedule split)
  heft    two 1-CU sub-devices       (--devices cpu/2 --schedule heft)
and, where the machine has an OpenCL GPU, gpu (--devices gpu), gpu_split and
gpu_heft (--devices gpu,cpu: the GPU and the whole CPU device, events,
copies through the host), printed in a second table beside the paper's GPU
and hybrid columns.
"best 2-dev" is the faster of split and heft. ms/frame is the median over
the simulated frames (frame 0, the initial state, left out) of
/timing/frame_ms + /timing/host_ms: the frame's substeps and the host's own
work on it, mostly the per-frame surface record (files written before
host_ms existed: frame_ms alone).

Contacts per frame: the run's /contact/active (particle-collider pairs with
a gap below 1 % of the collider's thickness) plus the vertex-triangle pairs
between simulated surfaces closer than the contact thickness, counted here
from the frame positions (k-d tree over the vertices, exact point-triangle
distances, incident pairs left out; edge-edge pairs are not counted), the
mean over the simulated frames of the whole-device run. Unlike the
solvers and /contact/surface_pairs, this count keeps sheet neighbours
(docs/scene-format.md, contact): neighbours in a layer's own plane closer
than the thickness, which the paper scenes' regular meshes have only where
cloth is squeezed (at rest such neighbours are about 0.7 edge apart,
farther than the thickness).

Per-core comparison: the paper's CPU column (M3 Max, 16 cores) scaled to
this device's cores and this scene's vertex count, assuming linear
scaling in both: paper_ms x 16 / cores x (vertices / paper vertices);
"x paper/core" is whole-device ms over that.

Where the time goes: per task kind, the measured time of the one-sub-device
run's last recorded substep (/schedule rows of the last frame), times the
substeps, in ms per frame and as a share.

usage: scripts/bench_paper_scenes.py [--small] [--frames 3] [--scenes dress,funnel]
                                     [--setups sub,whole,split,heft] [--method xpbd] [--executor auto]
                                     [--keep DIR [--reuse]]
Build first (cmake --build --preset release). Paper-size meshes are written
by scripts/make_meshes.py --paper when missing. Prints Markdown tables.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml
from scipy.spatial import cKDTree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(ROOT, "build", "release", "atssim")
SCENES = ("dress", "jersey", "pillows", "funnel", "letters")

# He et al. 2025, Table 1 (Apple M3 Max, XPBD, 1/60 s frames): vertices,
# triangles, tetrahedra, substeps, iterations, collisions, CPU / GPU / hybrid ms.
PAPER = {
    "dress": (104e3, 207e3, 0, 32, 8, 96.9e3, 815.9, 268.6, 174.5),
    "jersey": (69e3, 138e3, 0, 32, 8, 78.6e3, 506.1, 173.1, 122.2),
    "pillows": (176e3, 90e3, 493e3, 64, 8, 17.7e3, 2180.0, 813.5, 463.8),
    "funnel": (132e3, 260e3, 2.7e3, 64, 12, 225.7e3, 2210.0, 935.6, 528.5),
    "letters": (190e3, 0, 635e3, 32, 8, 7.4e3, 1490.0, 368.9, 266.0),
}
PAPER_CORES = 16

SETUPS = {
    "sub": ("cpu/2:0", "single"),
    "whole": ("cpu", "single"),
    "split": ("cpu/2", "split"),
    "heft": ("cpu/2", "heft"),
    # a machine with an OpenCL GPU beside the CPU device (each its own platform and memory)
    "gpu": ("gpu", "single"),
    "gpu_split": ("gpu,cpu", "split"),
    "gpu_heft": ("gpu,cpu", "heft"),
}


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def run(scene, out, devices, schedule, args):
    cmd = [BIN, "run", scene, "-o", out, "--frames", str(args.frames), "--devices", devices, "--schedule", schedule,
           "--set", f"solver.method={args.method}", "--executor", args.executor,
           # a paper-size detection task on a loaded 1-CU sub-device can exceed the
           # fused executor's default 10 s watchdog
           "--set", "solver.wait_timeout=600", "--quiet"]
    subprocess.run(cmd, check=True)


def complete(out, frames):
    """Whether `out` holds a finished run of `frames` frames (for --reuse)."""
    try:
        with h5py.File(out, "r") as f:
            return f["timing/frame_ms"].shape[0] == frames + 1
    except (OSError, KeyError):
        return False


def frame_ms(out):
    with h5py.File(out, "r") as f:
        ms = f["timing/frame_ms"][1:]
        if "timing/host_ms" in f:
            ms = ms + f["timing/host_ms"][1:]
        return float(np.median(ms))


def sizes(out):
    """Vertices, cloth triangles (objects without tetrahedra, the paper's
    #Tri.), tetrahedra, substeps, iterations, contact thickness, and every
    surface triangle in global vertex numbers."""
    with h5py.File(out, "r") as f:
        verts = f["frames/positions"].shape[1]
        cloth_tris, tets, surface = 0, 0, []
        for name in f["mesh"]:
            g = f["mesh"][name]
            ntet = g["tetrahedra"].shape[0] if "tetrahedra" in g else 0
            tets += ntet
            tris = g["triangles"][:].astype(np.int64)
            if ntet == 0:
                cloth_tris += tris.shape[0]
            surface.append(tris + int(g.attrs["vertex_offset"]))
        resolved = yaml.safe_load(text(f["scene/resolved"][()]))
    sim = resolved["simulation"]
    contact = resolved.get("contact") or {}
    thickness = float(contact.get("thickness", 0.005)) if contact.get("self") else None
    return verts, cloth_tris, tets, sim["substeps"], sim["iterations"], thickness, np.concatenate(surface)


def point_triangle(p, a, b, c):
    """Distances of points p to triangles abc (rows), Ericson's closest-point
    regions, vectorised."""
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    denom = va + vb + vc
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.where(denom != 0, vb / denom, 0.0)
        w = np.where(denom != 0, vc / denom, 0.0)
    q = a + ab * v[:, None] + ac * w[:, None]          # interior
    def seg(x, y):
        t = np.clip(np.einsum("ij,ij->i", p - x, y - x) / np.maximum(np.einsum("ij,ij->i", y - x, y - x), 1e-30),
                    0, 1)
        return np.linalg.norm(p - (x + (y - x) * t[:, None]), axis=1)
    inside = (va >= 0) & (vb >= 0) & (vc >= 0) & (denom > 0)
    edge = np.minimum(np.minimum(seg(a, b), seg(b, c)), seg(c, a))
    return np.where(inside, np.minimum(np.linalg.norm(p - q, axis=1), edge), edge)


def surface_pairs(x, tris, thickness):
    """Vertex-triangle pairs closer than `thickness`, incident ones left out."""
    a, b, c = x[tris[:, 0]], x[tris[:, 1]], x[tris[:, 2]]
    centre = (a + b + c) / 3
    reach = np.max(np.stack([np.linalg.norm(a - centre, axis=1), np.linalg.norm(b - centre, axis=1),
                             np.linalg.norm(c - centre, axis=1)]), axis=0) + thickness
    tree = cKDTree(x)
    found = tree.query_ball_point(centre, reach)
    ti = np.repeat(np.arange(len(tris)), [len(l) for l in found])
    vi = np.fromiter((v for l in found for v in l), dtype=np.int64, count=len(ti))
    keep = (vi != tris[ti, 0]) & (vi != tris[ti, 1]) & (vi != tris[ti, 2])
    ti, vi = ti[keep], vi[keep]
    count = 0
    for s in range(0, len(ti), 1 << 20):
        t, v = ti[s:s + (1 << 20)], vi[s:s + (1 << 20)]
        count += int(np.sum(point_triangle(x[v], a[t], b[t], c[t]) < thickness))
    return count


def contacts_per_frame(out, tris, thickness):
    with h5py.File(out, "r") as f:
        active = f["contact/active"][1:] if "contact/active" in f else np.zeros(0)
        positions = f["frames/positions"]
        per = []
        for k in range(1, positions.shape[0]):
            x = positions[k].astype(np.float64)
            self_pairs = surface_pairs(x, tris, thickness) if thickness else 0
            per.append((int(active[k - 1]) if len(active) >= k else 0) + self_pairs)
    return float(np.mean(per)) if per else 0.0


def kinds(out, substeps):
    with h5py.File(out, "r") as f:
        kind = [text(k) for k in f["schedule/tasks/kind"][:]]
        s = f["schedule"]
        frames = s["frame"][:]
        last = frames == frames.max()
        by = {}
        for t, a, b in zip(s["task"][:][last], s["measured_start_ms"][:][last], s["measured_finish_ms"][:][last]):
            by[kind[t]] = by.get(kind[t], 0.0) + (b - a) * substeps
    return by


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--small", action="store_true", help="the _small variants (seconds, not hours)")
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--setups", default="sub,whole,split,heft", help=", ".join(SETUPS))
    ap.add_argument("--method", default="xpbd")
    ap.add_argument("--executor", default="auto", help="auto, fused or events (CLI --executor)")
    ap.add_argument("--cores", type=int, default=os.cpu_count(), help="cores of the whole CPU device")
    ap.add_argument("--keep", help="keep the result files in this folder")
    ap.add_argument("--reuse", action="store_true", help="with --keep: skip runs whose result file is complete")
    args = ap.parse_args()
    if not os.path.exists(BIN):
        print(f"{BIN} is missing: build first", file=sys.stderr)
        return 2
    os.environ.setdefault("POCL_CACHE_DIR", os.path.expanduser("~/.cache/atssim/pocl"))
    scenes = args.scenes.split(",")
    for s in scenes:
        if s not in SCENES:
            print(f"--scenes: unknown scene '{s}' (use {', '.join(SCENES)})", file=sys.stderr)
            return 2
    setups = args.setups.split(",")
    for setup in setups:
        if setup not in SETUPS:
            print(f"--setups: unknown set-up '{setup}' (use {', '.join(SETUPS)})", file=sys.stderr)
            return 2
    if not args.small and not os.path.exists(os.path.join(ROOT, "scenes", "paper", "meshes", "large", "jersey.obj")):
        subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_meshes.py"), "--paper"], check=True,
                       stdout=subprocess.DEVNULL)
    tmp = tempfile.TemporaryDirectory()
    where = args.keep or tmp.name
    os.makedirs(where, exist_ok=True)
    rows, breakdown = [], []
    for s in scenes:
        scene = os.path.join(ROOT, "scenes", "paper", f"{s}_small.yaml" if args.small else f"{s}.yaml")
        ms = {}
        for setup in setups:
            out = os.path.join(where, f"{s}_{setup}.h5")
            if not (args.reuse and complete(out, args.frames)):
                try:
                    run(scene, out, *SETUPS[setup], args)
                except subprocess.CalledProcessError as e:  # one set-up failing leaves the others' numbers
                    print(f"{s} {setup}: failed ({e})", file=sys.stderr, flush=True)
                    continue
            ms[setup] = frame_ms(out)
            print(f"{s} {setup}: {ms[setup]:.1f} ms/frame", file=sys.stderr, flush=True)
        if not ms:
            continue
        ref = os.path.join(where, f"{s}_{'whole' if 'whole' in ms else next(iter(ms))}.h5")
        verts, tris, tets, sub, it, thickness, surface = sizes(ref)
        contacts = contacts_per_frame(ref, surface, thickness)
        if "sub" in ms:
            breakdown.append((s, kinds(os.path.join(where, f"{s}_sub.h5"), sub)))
        rows.append((s, verts, tris, tets, sub, it, contacts, ms))
    fmt = lambda v: f"{v:.0f}" if v >= 100 else f"{v:.1f}"
    print("| scene | vertices | triangles | tets | substeps | iterations | contacts/frame | "
          "1 sub-device ms | whole CPU ms | best 2-dev ms (schedule) | 2-dev vs 1 sub | "
          "paper CPU ms | paper per-core equivalent ms | whole CPU x paper/core |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|")
    for s, verts, tris, tets, sub, it, contacts, ms in rows:
        p = PAPER[s]
        two = {k: v for k, v in ms.items() if k in ("split", "heft")}
        best = min(two, key=two.get) if two else None
        equivalent = p[6] * PAPER_CORES / args.cores * (verts / p[0])
        cells = [s, str(verts), str(tris), str(tets), str(sub), str(it), f"{contacts:.0f}",
                 fmt(ms["sub"]) if "sub" in ms else "–", fmt(ms["whole"]) if "whole" in ms else "–",
                 f"{fmt(two[best])} ({best})" if best else "–",
                 f"{ms['sub'] / two[best]:.2f}x" if best and "sub" in ms else "–",
                 fmt(p[6]), fmt(equivalent), f"{ms['whole'] / equivalent:.1f}" if "whole" in ms else "–"]
        print("| " + " | ".join(cells) + " |")
    if any(k.startswith("gpu") for r in rows for k in r[7]):
        print("\n| scene | whole CPU ms | GPU ms | best GPU+CPU ms (schedule) | GPU+CPU vs faster alone | "
              "paper CPU ms | paper GPU ms | paper hybrid ms |")
        print("|---|---:|---:|---|---:|---:|---:|---:|")
        for s, verts, tris, tets, sub, it, contacts, ms in rows:
            p = PAPER[s]
            both = {k: v for k, v in ms.items() if k in ("gpu_split", "gpu_heft")}
            best = min(both, key=both.get) if both else None
            alone = [ms[k] for k in ("whole", "gpu") if k in ms]
            cells = [s, fmt(ms["whole"]) if "whole" in ms else "–", fmt(ms["gpu"]) if "gpu" in ms else "–",
                     f"{fmt(both[best])} ({best[4:]})" if best else "–",
                     f"{min(alone) / both[best]:.2f}x" if best and alone else "–", fmt(p[6]), fmt(p[7]), fmt(p[8])]
            print("| " + " | ".join(cells) + " |")
    print("\nPaper (Table 1, M3 Max): " + "; ".join(
        f"{s} {p[0] / 1e3:.0f} K vertices, {p[1] / 1e3:.0f} K tris, {p[2] / 1e3:.1f} K tets, {p[3]} x {p[4]}, "
        f"{p[5] / 1e3:.1f} K collisions, CPU {p[6]:.0f} / GPU {p[7]:.0f} / hybrid {p[8]:.0f} ms"
        for s, p in PAPER.items() if s in scenes) + ".")
    if breakdown:
        print("\nWhere the time goes (one sub-device, ms per frame from the last substep x substeps):\n")
        print("| scene | task kinds, largest first |")
        print("|---|---|")
        for s, by in breakdown:
            total = sum(by.values())
            top = sorted(by.items(), key=lambda kv: -kv[1])
            print(f"| {s} | " + ", ".join(f"{k} {fmt(v)} ({100 * v / total:.0f} %)" for k, v in top if v > 0.005 * total)
                  + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
