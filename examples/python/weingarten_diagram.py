#!/usr/bin/env python3
"""Optimise a B-spline towards a Weingarten surface with gproj and draw its curvature diagram:
mean curvature H against Gaussian curvature K at every sample, before and after. On a Weingarten
surface H and K are functionally related, so the cloud of the input collapses onto a curve.

    PYTHONPATH=build/python python3 examples/python/weingarten_diagram.py \\
        [SURFACE.json] [--preset fig1] [--max-iterations N] [-o weingarten_diagram.png]

SURFACE defaults to the shipped examples/data/freeform_10x10.json (the B-spline JSON of
docs/formats.md). The script prints the misalignment of the curvature isolines before and after and
exits 1 when the run failed.
"""
import argparse
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # a file is written; no window is needed
import matplotlib.pyplot as plt

import gproj

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("surface", nargs="?", default=str(DATA / "freeform_10x10.json"))
    parser.add_argument("--preset", default="fig1", help="weights of 003 Table 1")
    parser.add_argument("--max-iterations", type=int, default=None)
    parser.add_argument("-o", "--output", default="weingarten_diagram.png",
                        help="the picture (.png)")
    args = parser.parse_args()

    with open(args.surface) as f:
        surface = json.load(f)
    print(f"{args.surface}: {len(surface['control_points'])} x "
          f"{len(surface['control_points'][0])} control points, preset {args.preset}")
    run = gproj.weingarten(
        surface, preset=args.preset, max_iterations=args.max_iterations,
        callback=lambda r: print(f"  iteration {r['iteration']:3d}: "
                                 f"misalignment {r.get('misalignment', float('nan')):.3e}"))
    report = run.report
    if run.output is None:
        print(f"the run failed: {report.termination}", file=sys.stderr)
        return 1
    result = run.output  # the optimised B-spline, a dict like its JSON
    print(f"misalignment {report.initial['misalignment']:.3e} -> "
          f"{report.final['misalignment']:.3e}, max deviation "
          f"{report.final['max_deviation']:.3e} ({report.seconds:.1f} s)")

    # The same samples as the optimisation (2 per control point and direction).
    before = gproj.bspline_curvature(surface)
    after = gproj.bspline_curvature(result)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharex=True, sharey=True)
    for ax, c, title in ((axes[0], before, "input"), (axes[1], after, "Weingarten result")):
        ax.scatter(c["H"].ravel(), c["K"].ravel(), s=4, alpha=0.6)
        ax.set_title(f"{title}: {c['H'].size} samples")
        ax.set_xlabel("mean curvature H")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("Gaussian curvature K")
    fig.suptitle("Curvature diagram: a curve when H and K are related")
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"picture: {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
