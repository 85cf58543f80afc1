#!/usr/bin/python3
"""Plots of the edge-cracked plate with crack growth (examples/fracture_plate_2d):
load–opening and dissipated energy against the opening from the run's CSV, and the
bond damage on the deformed mesh from the last VTU (python/read_vtu.py).

Usage: plot.py [OUTPUT_DIR]   (default: examples/fracture_plate_2d/output)
Writes OUTPUT_DIR/fracture_plate.png and prints the table behind the curves.
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
    top = next(d["uy"] for d in case["dirichlet"] if d["set"] == "ymax")
    bottom = next(d["uy"] for d in case["dirichlet"] if d["set"] == "ymin")
    with open(os.path.join(out, "fracture_plate.csv")) as f:
        rows = list(csv.DictReader(f))
    opening = [0.0] + [float(r["load_factor"]) * (top - bottom) for r in rows]
    force = [0.0] + [float(r["reaction_ymax_y"]) for r in rows]
    dissipated = [0.0] + [float(r["dissipated_energy"]) for r in rows]
    overshoot = [0.0] + [float(r["overshoot_energy"]) for r in rows]
    released = [0.0] + [float(r["released_energy"]) for r in rows]
    work = [0.0] + [float(r["external_work"]) for r in rows]
    energy = [0.0] + [float(r["strain_energy"]) for r in rows]
    broken = [0] + [int(float(r["bonds_broken"])) for r in rows]
    crack = [0.0] + [float(r["crack_area"]) for r in rows]

    steps = read_pvd(os.path.join(out, "fracture_plate.pvd"))
    last = steps[-1][1]
    pts, cells = last["points"], last["cells"]
    disp = last["point_data"]["displacement"]["values"]
    damage = last["cell_data"]["damage"]["values"]
    umax = max(abs(v) for v in disp) or 1.0
    scale = 0.15 / umax  # largest displacement drawn as 0.15 mm
    polys = [[(pts[n][0] + scale * disp[3 * n], pts[n][1] + scale * disp[3 * n + 1]) for n in cell]
             for cell in cells]

    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(16, 4.6))
    ax1.plot(opening, force, "o-", color="C0")
    ax1.set_xlabel("opening $u_y^{top} - u_y^{bottom}$ [mm]")
    ax1.set_ylabel("top reaction $R_y$ [N per mm thickness]")
    ax1.set_title("Load–opening")
    ax1.grid(alpha=0.3)
    ax1b = ax1.twinx()
    ax1b.plot(opening, crack, "s--", color="C3", ms=3)
    ax1b.set_ylabel("crack length [mm] (fully failed faces, projected)", color="C3")
    ax2.plot(opening, work, "s-", label="external work W")
    ax2.plot(opening, energy, "^-", label="elastic energy U")
    ax2.plot(opening, dissipated, "o-", label="dissipated D (failed bonds at $s_{crit}$)")
    ax2.plot(opening, overshoot, ":", color="C2", label="overshoot (failed bonds beyond $s_{crit}$)")
    ax2.plot(opening, released, "--", color="C4", label="released W − U − D − overshoot")
    ax2.set_xlabel("opening [mm]")
    ax2.set_ylabel("energy [N mm per mm thickness]")
    ax2.set_title("Energies (THEORY §5: W − U − D ≥ 0)")
    ax2.legend(fontsize="small", loc="center right")
    ax2.grid(alpha=0.3)
    coll = PolyCollection(polys, array=damage, cmap="magma", edgecolors="face", linewidths=0.2)
    coll.set_clim(0.0, max(0.5, max(damage)))
    ax3.add_collection(coll)
    ax3.autoscale_view()
    ax3.set_aspect("equal")
    ax3.set_title(f"damage (bond weight lost), displacements ×{scale:.0f}")
    fig.colorbar(coll, ax=ax3)
    fig.tight_layout()
    path = os.path.join(out, "fracture_plate.png")
    fig.savefig(path, dpi=130)
    print(f"wrote {path}")
    print("opening [mm]  R_y          W            U            D            overshoot    bonds failed  crack [mm]")
    for row in zip(opening, force, work, energy, dissipated, overshoot, broken, crack):
        print("{:11.5f}  {:11.5g}  {:11.5g}  {:11.5g}  {:11.5g}  {:11.5g}  {:12d}  {:9.4g}".format(*row))


if __name__ == "__main__":
    main()
