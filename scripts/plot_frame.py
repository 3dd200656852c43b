#!/usr/bin/python3
"""Draw one frame of an atssim result as a shaded triangle mesh (PNG).

usage: scripts/plot_frame.py OUT.h5 [--frame K] [-o frame.png]
Needs Debian's python3-h5py and python3-matplotlib (scripts/setup.sh).
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("result")
    ap.add_argument("--frame", type=int, default=-1, help="frame index (default: last)")
    ap.add_argument("-o", "--output", default="frame.png")
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
            # atssim is y-up; matplotlib's 3-D axes are z-up.
            ax.plot_trisurf(p[:, 0], p[:, 2], p[:, 1], triangles=group["triangles"][:], cmap="viridis",
                            linewidth=0.1, edgecolor="k", alpha=0.9)
        ax.set_xlabel("x")
        ax.set_ylabel("z")
        ax.set_zlabel("y")
        ax.set_title(f"{args.result}: frame {k}, t = {t:.3f} s")
        fig.savefig(args.output, dpi=100)
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
