#!/usr/bin/python3
"""Plots of the edge-cracked plate (examples/plate_tension): the
load–displacement curve from the run's CSV, and σ_yy on the deformed mesh
(displacements magnified) from the last VTU, read by python/read_vtu.py.

Usage: plot.py [OUTPUT_DIR]   (default: examples/plate_tension/output)
Writes OUTPUT_DIR/plate_tension.png.
"""
import csv
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
from read_vtu import read_pvd  # noqa: E402


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "output")
    with open(os.path.join(HERE, "case.toml"), "rb") as f:
        case = tomllib.load(f)
    top_uy = next(d["uy"] for d in case["dirichlet"] if d["set"] == "ymax")
    with open(os.path.join(out, "plate_tension.csv")) as f:
        rows = list(csv.DictReader(f))
    u = [0.0] + [float(r["load_factor"]) * top_uy for r in rows]
    force = [0.0] + [float(r["reaction_ymax_y"]) for r in rows]

    steps = read_pvd(os.path.join(out, "plate_tension.pvd"))
    last = steps[-1][1]
    pts, cells = last["points"], last["cells"]
    disp = last["point_data"]["displacement"]["values"]
    syy = last["cell_data"]["stress"]["values"][4::9]
    umax = max(abs(v) for v in disp) or 1.0
    scale = 2.0 / umax  # largest displacement drawn as 2 µm
    polys = []
    for cell in cells:
        # perimorph quads are written in VTK (counter-clockwise) order.
        polys.append([(pts[n][0] + scale * disp[3 * n], pts[n][1] + scale * disp[3 * n + 1]) for n in cell])

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.6))
    ax1.plot(u, force, "o-", color="C0")
    ax1.set_xlabel("imposed top displacement $u_y$ [µm]")
    ax1.set_ylabel("top reaction $R_y$ [µN per µm thickness]")
    ax1.set_title("Load–displacement (linear elastic, pre-cracked)")
    ax1.grid(alpha=0.3)
    coll = PolyCollection(polys, array=syy, cmap="viridis", edgecolors="face", linewidths=0.2)
    ax2.add_collection(coll)
    ax2.autoscale_view()
    ax2.set_aspect("equal")
    ax2.set_title(f"$\\sigma_{{yy}}$ [MPa], displacements ×{scale:.0f}")
    fig.colorbar(coll, ax=ax2)
    fig.tight_layout()
    path = os.path.join(out, "plate_tension.png")
    fig.savefig(path, dpi=130)
    print(f"wrote {path}")
    print("u_y [µm]   R_y")
    for a, b in zip(u, force):
        print(f"{a:9.5f}  {b:12.6g}")


if __name__ == "__main__":
    main()
