"""Stress–strain of B8 runs from their CSV files, the phases of each hybrid marked (a damage onset, b non-local
patch, c first failed bond, d reaction below 1 % of its peak), and the dissipated energy (damage + fracture).
For runs in progress or stopped as well as finished ones; the full study is verification/b8_damage_handover.py.

    /usr/bin/python3 plot_runs.py OUT.png LABEL=run.csv[:u_d_mm] ...   (u_d of the last increment, default 3)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

LENGTH, AREA = 18.0, 1.8 * 1.2  # mm, mm² (reduced section)


def read(path):
    rows = list(csv.DictReader(open(path)))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def phases(A):
    def first(mask):
        i = np.nonzero(mask)[0]
        return int(i[0]) if len(i) else None
    R = A["reaction_xmax_x"]
    peak = int(np.argmax(R))
    out = {"a": first(A["damaged_points"] > 0)}
    if "alpha_balls" in A:
        out["b"] = first(A["alpha_balls"] > 0)
        out["c"] = first(A["bonds_broken"] > 0)
    out["d"] = first((np.arange(len(R)) > peak) & (np.abs(R) < 0.01 * R[peak]))
    return out


def main(out, specs):
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for spec in specs:
        label, _, rest = spec.rpartition("=")
        path, _, ud = rest.partition(":")
        A = read(path)
        strain = (float(ud) if ud else 3.0) * A["load_factor"] / LENGTH
        S = A["reaction_xmax_x"] / AREA
        line, = ax[0].plot(strain, S, "-" if "alpha_balls" in A else ":", label=label)
        for k, i in phases(A).items():
            if i is not None:
                ax[0].plot(strain[i], S[i], "o", color=line.get_color(), ms=4)
                ax[0].annotate(k, (strain[i], S[i]), textcoords="offset points", xytext=(-9, 6), fontsize=10,
                               color=line.get_color(), weight="bold")
        D = A["damage_dissipated_energy"] + (A["dissipated_energy"] if "dissipated_energy" in A else 0.0)
        ax[1].plot(strain, D, "-" if "alpha_balls" in A else ":", color=line.get_color(), label=label)
    ax[0].set_xlabel("strain u_d / L")
    ax[0].set_ylabel("reaction / reduced section [MPa]")
    ax[0].legend(fontsize=8)
    ax[1].set_xlabel("strain u_d / L")
    ax[1].set_ylabel("dissipated energy, damage + fracture [mJ]")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
