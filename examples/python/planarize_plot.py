#!/usr/bin/env python3
"""Planarise a quad mesh with gproj and look at the result: the mesh coloured by each quad's
planarity before and after, and the distribution of the face planarity on one log axis.

    PYTHONPATH=build/python python3 examples/python/planarize_plot.py \\
        [MESH] [--tolerance 1e-6] [--circular] [-o planarize.png]

MESH defaults to the shipped examples/data/noisy_grid_21x21.obj. The planarity of a quad is
gproj's measure (gproj.face_values): the distance between its two diagonals divided by the
mesh's mean edge length. The script prints the run's summary and exits 1 when the tolerance was
not met or a quad folded.
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # a file is written; no window is needed
import matplotlib.colors as mcolors
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

import gproj

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"


def draw_mesh(ax, V, F, values, norm, title):
    """The quads of (V, F) in 3D, each coloured by its value on the log scale `norm`."""
    colours = plt.cm.viridis(norm(np.maximum(values, norm.vmin)))
    ax.add_collection3d(Poly3DCollection(V[F], facecolors=colours, edgecolors="k",
                                         linewidths=0.2))
    lo, hi = V.min(axis=0), V.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for axis, c in zip("xyz", centre):
        getattr(ax, f"set_{axis}lim")(c - half, c + half)
    ax.set_title(title, fontsize=10)
    ax.set_axis_off()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh", nargs="?", default=str(DATA / "noisy_grid_21x21.obj"))
    parser.add_argument("--tolerance", type=float, default=1e-6)
    parser.add_argument("--circular", action="store_true", help="a circular mesh, not only PQ")
    parser.add_argument("-o", "--output", default="planarize.png", help="the picture (.png)")
    args = parser.parse_args()

    V, F = gproj.read_mesh(args.mesh)
    print(f"{args.mesh}: {len(V)} vertices, {len(F)} quads")
    iterations = []
    result = gproj.planarize(V, F, tolerance=args.tolerance, circular=args.circular,
                             callback=iterations.append)
    report = result.report
    if result.vertices is None:
        print(f"the run failed: {report.termination}", file=sys.stderr)
        return 1
    V_out = result.vertices
    for r in iterations:
        print(f"  iteration {r['iteration']:3d}: max planarity {r['max_planarity']:.3e}")
    before = gproj.face_values(V, F)["planarity"]
    after_values = gproj.face_values(V_out, F)
    after = after_values["planarity"]
    print(f"max planarity {before.max():.3e} -> {after.max():.3e} "
          f"({report.termination}, {report.seconds:.2f} s)")

    floor = max(min(before.min(), after.max(), args.tolerance) / 10, 1e-16)
    norm = mcolors.LogNorm(vmin=floor, vmax=before.max())
    fig = plt.figure(figsize=(13, 4.5))
    draw_mesh(fig.add_subplot(1, 3, 1, projection="3d"), V, F, before, norm,
              f"input: max planarity {before.max():.1e}")
    draw_mesh(fig.add_subplot(1, 3, 2, projection="3d"), V_out, F, after, norm,
              f"gproj.planarize: max {after.max():.1e}")
    ax = fig.add_subplot(1, 3, 3)
    bins = np.logspace(np.log10(floor), np.log10(before.max()), 40)
    ax.hist(np.maximum(before, floor), bins=bins, alpha=0.6, label="input")
    ax.hist(np.maximum(after, floor), bins=bins, alpha=0.6, label="result")
    ax.axvline(args.tolerance, color="k", linestyle="--", label="tolerance")
    ax.set_xscale("log")
    ax.set_xlabel("face planarity (diagonal distance / mean edge)")
    ax.set_ylabel("quads")
    ax.legend()
    fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=fig.axes[:2],
                 shrink=0.7, label="face planarity")
    fig.savefig(args.output, dpi=110)
    print(f"picture: {args.output}")

    folded = int((~after_values["convex"]).sum())
    if not result.converged or folded:
        print(f"not usable: {report.status}, {folded} non-convex quads",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
