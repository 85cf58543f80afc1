"""Maps of an adaptive run (issue 14: a non-local zone grown by [adaptivity]): α and damage at several
increments, the fraction of cells that ended non-local, and, with --mirror, how symmetric the cracks are.

    /usr/bin/python3 scripts/plot_adaptive_maps.py OUTPUT_DIR [--slice Z] [--mirror X0 Y0] [--png FILE]

OUTPUT_DIR holds one run (BASENAME.pvd, BASENAME.csv). 3D runs are cut at z = Z (default: mid-thickness).
--mirror X0 Y0: the cells whose damage exceeds 1/4 at the end, mirrored about x = X0 and about y = Y0; the
largest distance from a mirrored damaged cell to the nearest damaged cell, in cell sizes (0: symmetric).
Prints a summary and writes OUTPUT_DIR/BASENAME.png (or --png).
"""

import argparse
import csv
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from read_vtu import read_grid as read_vtu  # noqa: E402  (a .vtu, or a distributed run's .pvtu)


def cells_of(path):
    v = read_vtu(path)
    pts = np.array(v["points"], dtype=float)
    con = np.array(v["cells"], dtype=int)
    data = {k: np.array(a["values"], dtype=float).reshape(len(con), a["components"])[:, 0]
            for k, a in v["cell_data"].items()}
    return pts[con].mean(axis=1), pts[con].max(axis=1) - pts[con].min(axis=1), data


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("output")
    ap.add_argument("--slice", type=float, default=None)
    ap.add_argument("--mirror", type=float, nargs=2, default=None)
    ap.add_argument("--png", default=None)
    args = ap.parse_args()
    pvd = glob.glob(os.path.join(args.output, "*.pvd"))
    if len(pvd) != 1:
        sys.exit(f"error: {args.output} holds {len(pvd)} .pvd files (need 1)")
    base = os.path.splitext(os.path.basename(pvd[0]))[0]
    files = [os.path.join(args.output, d.get("file")) for d in ET.parse(pvd[0]).getroot().iter("DataSet")]
    with open(os.path.join(args.output, base + ".csv")) as f:
        rows = list(csv.DictReader(f))
    picks = [files[int(round(q * (len(files) - 1)))] for q in (0.0, 1 / 3, 2 / 3, 1.0)] if len(files) > 3 else files

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, len(picks), figsize=(4.2 * len(picks), 7.5), squeeze=False)
    for j, path in enumerate(picks):
        cen, size, data = cells_of(path)
        keep = np.ones(len(cen), bool)
        if np.ptp(cen[:, 2]) > 0:  # 3D: one layer of cells
            z = args.slice if args.slice is not None else 0.5 * (cen[:, 2].min() + cen[:, 2].max())
            keep = np.abs(cen[:, 2] - z) <= 0.5 * size[:, 2] + 1e-12
        inc = int(re.search(r"_(\d+)\.p?vtu$", path).group(1))
        for i, (name, cmap) in enumerate((("alpha_mean", "viridis"), ("damage", "magma"))):
            peak = float(data[name].max())
            # damage: scaled to its largest value; none yet: on [0, 1] (not [0, 1e-12], whose
            # colorbar's offset label overlapped the title)
            top = 1.0 if i == 0 or peak <= 0.0 else peak
            s = ax[i, j].scatter(cen[keep, 0], cen[keep, 1], c=data[name][keep], cmap=cmap, vmin=0, vmax=top,
                                 marker="s", s=max(2.0, 6000.0 / keep.sum()))
            ax[i, j].set_aspect("equal")
            none = " (none yet)" if i == 1 and peak <= 0.0 else ""
            ax[i, j].set_title(f"{'α' if i == 0 else 'damage'}, increment {inc}{none}")
            fig.colorbar(s, ax=ax[i, j], shrink=0.7)
    png = args.png or os.path.join(args.output, base + ".png")
    fig.tight_layout()
    fig.savefig(png, dpi=90)

    last = rows[-1]
    cen, size, data = cells_of(files[-1])
    n = len(cen)
    print(f"{base}: {n} cells; ended non-local (α > 0): {int(float(last['nonlocal_cells']))} "
          f"({100 * float(last['nonlocal_cells']) / n:.1f}%), DG: {int(float(last['dg_cells']))}; "
          f"balls {int(float(last['alpha_balls']))}; bonds failed {int(float(last['bonds_broken']))}; "
          f"run wall time {float(last['wall_time']):.1f} s (remodel {float(last['remodel_time']):.1f} s)")
    if args.mirror:
        x0, y0 = args.mirror
        hit = cen[data["damage"] > 0.25][:, :2]
        h = float(np.median(size[:, 0]))
        worst = 0.0
        for m in (np.column_stack([2 * x0 - hit[:, 0], hit[:, 1]]), np.column_stack([hit[:, 0], 2 * y0 - hit[:, 1]])):
            d = np.sqrt(((m[:, None, :] - hit[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
            worst = max(worst, float(d.max()) / h if len(d) else 0.0)
        print(f"symmetry: {len(hit)} cells with damage > 1/4; largest distance of a mirrored one to a damaged "
              f"cell: {worst:.2f} cell sizes")
    print(f"wrote {png}")


if __name__ == "__main__":
    main()
