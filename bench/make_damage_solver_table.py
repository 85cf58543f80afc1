"""Secant against Newton (SNES) for the local damage solve: the table and plot of docs/benchmarks/damage-solver.md
from the JSON of bench/damage_solver_bench (bench/results/damage_solver_*.json).

    /usr/bin/python3 bench/make_damage_solver_table.py bench/results/damage_solver_h2_dc1.json ... > table.md
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(paths):
    runs = [json.load(open(p)) for p in paths]
    fig, ax = plt.subplots(1, len(runs), figsize=(6 * len(runs), 4), squeeze=False)
    for k, (p, d) in enumerate(zip(paths, runs)):
        T = d["increments_table"]
        s = [r["secant_solves"] for r in T]
        n = [r["newton_solves"] for r in T]
        damaged = [r for r in T if r["secant_solves"] > 1]  # the increments where d changes
        cells = "×".join(str(c) for c in d["cells"])
        print(f"### {cells} cells, {d['increments']} increments, d_c = {d['d_c']:g} (`{os.path.basename(p)}`)\n")
        print(f"Linear solves over the path: secant **{sum(s)}**, Newton **{sum(n)}** "
              f"(ratio {sum(s) / max(1, sum(n)):.2f}); in the increments where d changes: secant "
              f"{sum(r['secant_solves'] for r in damaged)}, Newton {sum(r['newton_solves'] for r in damaged)}. "
              f"Wall / CPU: secant {d['secant']['wall_s']:.0f} / {d['secant']['cpu_s']:.0f} s, Newton "
              f"{d['newton']['wall_s']:.0f} / {d['newton']['cpu_s']:.0f} s "
              f"(ratio {d['secant']['wall_s'] / max(1e-9, d['newton']['wall_s']):.2f} wall, "
              f"{d['secant']['cpu_s'] / max(1e-9, d['newton']['cpu_s']):.2f} CPU). "
              f"Newton steps {sum(r['newton_steps'] for r in T)}, damage updates after them "
              f"{sum(r['newton_updates'] for r in T)} (secant: {sum(r['secant_updates'] for r in T)}).\n")
        print("| increment | secant solves (updates) | Newton solves (steps, updates) | reaction secant [N] "
              "| reaction Newton [N] | max d |")
        print("|---|---|---|---|---|---|")
        for r in damaged:
            print(f"| {r['increment']} | {r['secant_solves']} ({r['secant_updates']}) | {r['newton_solves']} "
                  f"({r['newton_steps']}, {r['newton_updates']}) | {r['secant_reaction']:.6g} | "
                  f"{r['newton_reaction']:.6g} | {r['newton_max_d']:.3g} |")
        print()
        inc = [r["increment"] for r in T]
        ax[0, k].plot(inc, s, "o-", ms=3, label="secant (fixed point)")
        ax[0, k].plot(inc, n, "s-", ms=3, label="Newton, consistent tangent (SNES), then the fixed point's check")
        ax[0, k].set_xlabel("increment")
        ax[0, k].set_ylabel("linear solves")
        ax[0, k].set_title(f"{cells} cells, d_c = {d['d_c']:g}")
        ax[0, k].legend()
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "benchmarks", "damage-solver.png")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1:])
