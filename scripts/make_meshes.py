#!/usr/bin/python3
"""Writes the obstacle meshes of the example scenes as small OBJ files.

usage: scripts/make_meshes.py [OUT_DIR]      (default: scenes/meshes)
       scripts/make_meshes.py --paper [ROOT]  (default: scenes/paper/meshes)

  sphere.obj  an icosphere of radius 1 (closed): scale it in the scene
  funnel.obj  an open funnel, axis +y: a cone from radius 0.5 at y = 0.5 down
              to a 0.12 spout at y = 0, and a 0.3 long spout below
  bowl.obj    a closed bowl: a hemispherical shell of outer radius 0.5 and
              0.04 wall, open at the top (y = 0), rim closed by a ring

With --paper it also writes the meshes of the paper's five scenes
(scenes/paper/*.yaml, He et al. 2025 Table 1): the small variants' meshes
into scenes/paper/meshes/ (committed) and the paper-size ones into
scenes/paper/meshes/large/ (tens of MB, not committed: run
`scripts/make_meshes.py --paper` before a paper-size run; the benchmark
does it):

  dress_layerK.obj   three concentric flared skirt layers (open cones,
                     waist radius 0.20 at y = 1.0, hem 0.40 at y = 0.2, the
                     next layer 12 mm out (small) or 4 mm (paper size))
  jersey.obj         a tube shirt of elliptical section with a shoulder
                     yoke closing to a neck hole (one open mesh)
  ball.node/.ele     a voxel ball of radius 0.09, each cell cut into six
                     tetrahedra (Kuhn), TetGen format
  letters/X.node/.ele  block letters: 5 x 7 bitmap glyphs, each pixel a
                     square of 2 cm extruded 2 cm deep (one cell; paper size: 5 x 5 cells of
                     4 mm per pixel, 6 cells = 2.4 cm deep), cut into cells and
                     six tetrahedra per cell
Everything is computed here (no downloads); the default meshes are committed.
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
    unknown = [a for a in sys.argv[1:] if a.startswith("-") and a != "--paper"]
    if unknown:
        if unknown[0] in ("-h", "--help"):
            print(__doc__)
            return 0
        print(f"make_meshes.py: unknown option '{unknown[0]}' (use --paper [ROOT] or an output folder)", file=sys.stderr)
        return 2
    if "--paper" in sys.argv[1:]:
        roots = [a for a in sys.argv[1:] if not a.startswith("--")]
        return paper_meshes(roots[0] if roots else None)
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "meshes"))
    os.makedirs(out, exist_ok=True)
    vs, fs = icosphere(3)
    write_obj(os.path.join(out, "sphere.obj"), vs, fs, "icosphere, radius 1, closed")
    vs, fs = funnel()
    write_obj(os.path.join(out, "funnel.obj"), vs, fs, "open funnel, axis +y, mouth radius 0.5 at y = 0.5")
    vs, fs = bowl()
    write_obj(os.path.join(out, "bowl.obj"), vs, fs, "closed bowl shell, outer radius 0.5, wall 0.04, rim at y = 0")
    return 0


# ---------------------------------------------------------------- paper scenes

def write_tetgen(stem, vertices, tets, comment):
    """TetGen .node/.ele, points numbered from 0; every tetrahedron turned
    to positive volume."""
    def vol(a, b, c, d):
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        w = [d[i] - a[i] for i in range(3)]
        return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
                + u[2] * (v[0] * w[1] - v[1] * w[0]))
    with open(stem + ".node", "w", encoding="utf-8") as out:
        out.write(f"# {comment}\n# written by scripts/make_meshes.py\n{len(vertices)} 3 0 0\n")
        for i, v in enumerate(vertices):
            out.write("{} {:.6f} {:.6f} {:.6f}\n".format(i, *v))
    with open(stem + ".ele", "w", encoding="utf-8") as out:
        out.write(f"# {comment}\n{len(tets)} 4 0\n")
        for i, t in enumerate(tets):
            a, b, c, d = t
            if vol(vertices[a], vertices[b], vertices[c], vertices[d]) < 0:
                a, b = b, a
            out.write(f"{i} {a} {b} {c} {d}\n")
    print(f"wrote {stem}.node/.ele: {len(vertices)} vertices, {len(tets)} tetrahedra")


KUHN = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]


def voxel_tets(cells, size):
    """Cells (integer (i, j, k) triples) of edge `size`, each cut into the six
    Kuhn tetrahedra along its main diagonal (the same cut in every cell, so
    neighbouring cells share their faces' triangles); the shared corners are
    one vertex. Returns vertices, tetrahedra."""
    index, vertices, tets = {}, [], []

    def corner(c):
        if c not in index:
            index[c] = len(vertices)
            vertices.append(tuple(size * x for x in c))
        return index[c]
    for cell in sorted(cells):
        for perm in KUHN:
            p = list(cell)
            ids = [corner(tuple(p))]
            for axis in perm:
                p[axis] += 1
                ids.append(corner(tuple(p)))
            tets.append(tuple(ids))
    return vertices, tets


def voxel_ball(radius, cells_across):
    """A ball of `radius` about the origin made of cubes whose centres lie
    within it (a staircase surface)."""
    h = 2 * radius / cells_across
    n = cells_across // 2 + 1
    cells = [(i, j, k) for i in range(-n, n) for j in range(-n, n) for k in range(-n, n)
             if ((i + 0.5) ** 2 + (j + 0.5) ** 2 + (k + 0.5) ** 2) * h * h <= radius * radius]
    vs, ts = voxel_tets(cells, h)
    return [tuple(c for c in v) for v in vs], ts


# 5 x 7 block glyphs, rows from the top ('#' = filled).
GLYPHS = {
    "A": [".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"],
    "C": [".####", "#....", "#....", "#....", "#....", "#....", ".####"],
    "D": ["####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."],
    "E": ["#####", "#....", "#....", "####.", "#....", "#....", "#####"],
    "F": ["#####", "#....", "#....", "####.", "#....", "#....", "#...."],
    "G": [".####", "#....", "#....", "#.###", "#...#", "#...#", ".###."],
    "H": ["#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"],
    "I": ["#####", "..#..", "..#..", "..#..", "..#..", "..#..", "#####"],
    "K": ["#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"],
    "L": ["#....", "#....", "#....", "#....", "#....", "#....", "#####"],
    "M": ["#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"],
    "N": ["#...#", "##..#", "#.#.#", "#.#.#", "#..##", "#...#", "#...#"],
    "O": [".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."],
    "R": ["####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"],
    "S": [".####", "#....", "#....", ".###.", "....#", "....#", "####."],
    "T": ["#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."],
    "U": ["#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."],
    "W": ["#...#", "#...#", "#...#", "#.#.#", "#.#.#", "##.##", "#...#"],
}
# The 45 letters that fall into the bowl, in the order of the scene's objects.
LETTERS = "AUTOMATEDTASKSCHEDULINGFORCLOTHSIMULATIONSWEN"


def glyph_cells(rows, sub, depth):
    """Cells of a glyph: each filled pixel `sub` x `sub` cells in x (columns)
    and y (rows, upwards), `depth` cells deep in z."""
    cells = []
    for r, row in enumerate(rows):
        for c, ch in enumerate(row):
            if ch != "#":
                continue
            for a in range(sub):
                for b in range(sub):
                    for k in range(depth):
                        cells.append((c * sub + a, (len(rows) - 1 - r) * sub + b, k))
    return cells


def letter(ch, pixel, sub, depth_cells):
    """Glyph `ch` centred on the origin: pixel edge `pixel`, glyph plane xy,
    extruded along z by depth_cells cells of edge pixel / sub."""
    h = pixel / sub
    vs, ts = voxel_tets(glyph_cells(GLYPHS[ch], sub, depth_cells), h)
    cx, cy, cz = 5 * pixel / 2, 7 * pixel / 2, depth_cells * h / 2
    return [(x - cx, y - cy, z - cz) for x, y, z in vs], ts


def ring_surface(rings, close=False):
    """Consecutive rings of equally many points joined by two triangles per
    segment (an open tube when `close` is false)."""
    vs, ids = [], []
    for ring in rings:
        ids.append(list(range(len(vs), len(vs) + len(ring))))
        vs.extend(ring)
    fs = []
    for top, bottom in zip(ids, ids[1:]):
        n = len(top)
        for k in range(n):
            a, b, c, d = top[k], top[(k + 1) % n], bottom[k], bottom[(k + 1) % n]
            fs += [(a, c, b), (b, c, d)]
    return vs, fs


def skirt(waist, hem, top, bottom, segments, rings):
    """A flared skirt layer: an open cone from radius `waist` at y = top to
    `hem` at y = bottom, `rings` rings of `segments` points."""
    out = []
    for j in range(rings):
        t = j / (rings - 1)
        r, y = waist + (hem - waist) * t, top + (bottom - top) * t
        out.append([(r * math.cos(2 * math.pi * k / segments), y, r * math.sin(2 * math.pi * k / segments))
                    for k in range(segments)])
    return ring_surface(out)


def shirt(segments, body_rings, yoke_rings):
    """A tube shirt: an elliptical tube (semi-axes 0.28 along x, 0.19 along
    z) from the hem at y = 0.95 up to the shoulders at y = 1.485, then a flat
    yoke closing to a neck hole of 0.6 times that size."""
    a, b, hem, shoulder, neck = 0.28, 0.19, 0.95, 1.485, 0.6
    rings = []
    for j in range(yoke_rings):          # neck hole outwards to the shoulder line
        s = neck + (1 - neck) * j / yoke_rings
        rings.append([(s * a * math.cos(2 * math.pi * k / segments), shoulder,
                       s * b * math.sin(2 * math.pi * k / segments)) for k in range(segments)])
    for j in range(body_rings + 1):      # shoulders down to the hem
        y = shoulder + (hem - shoulder) * j / body_rings
        rings.append([(a * math.cos(2 * math.pi * k / segments), y, b * math.sin(2 * math.pi * k / segments))
                      for k in range(segments)])
    return ring_surface(rings)


def paper_meshes(root=None):
    """Into ROOT (a test's copy of scenes/paper/meshes) when given."""
    root = root or os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes",
                                                 "paper", "meshes"))
    sizes = {  # small variant (committed), paper size (generated)
        "small": dict(out=root, skirt=(32, 17), gap=0.012, shirt=(32, 20, 8), ball=6, sub=1, depth=1),
        "large": dict(out=os.path.join(root, "large"), skirt=(256, 136), gap=0.004, shirt=(320, 180, 36), ball=9, sub=5,
                      depth=6),
    }
    which = [w for w in ("small", "large") if "--small-only" not in sys.argv or w == "small"]
    for name in which:
        z = sizes[name]
        out = z["out"]
        os.makedirs(os.path.join(out, "letters"), exist_ok=True)
        for k in range(3):  # parallel cones, z["gap"] apart: the layers touch from the start
            waist, hem = 0.20 + k * z["gap"], 0.40 + k * z["gap"]
            vs, fs = skirt(waist, hem, 1.0, 0.2, *z["skirt"])
            write_obj(os.path.join(out, f"dress_layer{k}.obj"), vs, fs,
                      f"dress layer {k}: open cone, waist radius {waist} at y = 1, hem radius {hem} at y = 0.2")
        vs, fs = shirt(*z["shirt"])
        write_obj(os.path.join(out, "jersey.obj"), vs, fs, "tube shirt, shoulders at y = 1.485, hem at y = 0.95")
        vs, ts = voxel_ball(0.09, z["ball"])
        write_tetgen(os.path.join(out, "ball"), vs, ts, "voxel ball, radius 0.09, Kuhn tetrahedra")
        for ch in sorted(set(LETTERS)):
            vs, ts = letter(ch, 0.02, z["sub"], z["depth"])
            write_tetgen(os.path.join(out, "letters", ch), vs, ts,
                         f"block letter {ch}: 5 x 7 pixels of 2 cm, {z['depth'] * 0.02 / z['sub']:.3g} m deep, Kuhn tetrahedra")
    return 0


if __name__ == "__main__":
    sys.exit(main())
