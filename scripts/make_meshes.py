#!/usr/bin/python3
"""Writes the obstacle meshes of the example scenes as small OBJ files.

usage: scripts/make_meshes.py [OUT_DIR]      (default: scenes/meshes)

  sphere.obj  an icosphere of radius 1 (closed): scale it in the scene
  funnel.obj  an open funnel, axis +y: a cone from radius 0.5 at y = 0.5 down
              to a 0.12 spout at y = 0, and a 0.3 long spout below
  bowl.obj    a closed bowl: a hemispherical shell of outer radius 0.5 and
              0.04 wall, open at the top (y = 0), rim closed by a ring
Everything is computed here (no downloads); the files are committed.
"""
import math
import os
import sys


def write_obj(path, vertices, faces, comment):
    with open(path, "w", encoding="utf-8") as out:
        out.write(f"# {comment}\n# written by scripts/make_meshes.py\n")
        for v in vertices:
            out.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
        for f in faces:
            out.write("f {} {} {}\n".format(*(i + 1 for i in f)))
    print(f"wrote {path}: {len(vertices)} vertices, {len(faces)} triangles")


def icosphere(levels):
    t = (1 + math.sqrt(5)) / 2
    vs = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
          (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    fs = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
          (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
          (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]

    def unit(v):
        n = math.sqrt(sum(c * c for c in v))
        return tuple(c / n for c in v)

    vs = [unit(v) for v in vs]
    for _ in range(levels):
        mid = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                vs.append(unit(tuple(p + q for p, q in zip(vs[a], vs[b]))))
                mid[key] = len(vs) - 1
            return mid[key]

        nxt = []
        for a, b, c in fs:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            nxt += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        fs = nxt
    return vs, fs


def revolve(profile, segments, close=False):
    """Rings of (radius, y) about +y, consecutive rings joined by two
    triangles per segment (a radius of 0 is one vertex, a pole; two poles in
    a row are not joined). With `close`, the last ring joins the first. One
    winding along the whole profile, so the surface is consistently
    oriented."""
    vs, rings = [], []
    for r, y in profile:
        if r < 1e-9:
            rings.append([len(vs)] * segments)
            vs.append((0.0, y, 0.0))
            continue
        ring = []
        for k in range(segments):
            a = 2 * math.pi * k / segments
            ring.append(len(vs))
            vs.append((r * math.cos(a), y, r * math.sin(a)))
        rings.append(ring)
    if close:
        rings.append(rings[0])
    fs = []
    for top, bottom in zip(rings, rings[1:]):
        if top[0] == top[1] and bottom[0] == bottom[1]:
            continue
        for k in range(segments):
            a, b = top[k], top[(k + 1) % segments]
            c, d = bottom[k], bottom[(k + 1) % segments]
            for f in ((a, c, b), (b, c, d)):
                if len(set(f)) == 3:
                    fs.append(f)
    return vs, fs


def funnel():
    profile = [(0.5, 0.5), (0.38, 0.375), (0.26, 0.25), (0.14, 0.125), (0.12, 0.0), (0.12, -0.15), (0.12, -0.3)]
    return revolve(profile, 32)


def bowl():
    """The shell's surface as one closed profile: the inner side from the
    rim down to the bottom, the outer side from the bottom back up, and the
    rim ring between the outer and the inner top."""
    outer, wall, n = 0.5, 0.04, 10
    inner = [((outer - wall) * math.cos(math.pi / 2 * i / n), -(outer - wall) * math.sin(math.pi / 2 * i / n))
             for i in range(n + 1)]
    outside = [(outer * math.cos(math.pi / 2 * i / n), -outer * math.sin(math.pi / 2 * i / n))
               for i in range(n, -1, -1)]
    inner[-1] = (0.0, inner[-1][1])
    outside[0] = (0.0, outside[0][1])
    return revolve(inner + outside, 32, close=True)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "meshes"))
    os.makedirs(out, exist_ok=True)
    vs, fs = icosphere(3)
    write_obj(os.path.join(out, "sphere.obj"), vs, fs, "icosphere, radius 1, closed")
    vs, fs = funnel()
    write_obj(os.path.join(out, "funnel.obj"), vs, fs, "open funnel, axis +y, mouth radius 0.5 at y = 0.5")
    vs, fs = bowl()
    write_obj(os.path.join(out, "bowl.obj"), vs, fs, "closed bowl shell, outer radius 0.5, wall 0.04, rim at y = 0")
    return 0


if __name__ == "__main__":
    sys.exit(main())
