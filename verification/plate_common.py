"""Helpers shared by the 2D plate benchmarks B2 (b2_plate_uniform.py) and B3
(b3_cracked_plate.py): running the program, reading its last VTU with the
project's independent reader (python/read_vtu.py), templates, tables."""

import json
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from read_vtu import read_pvd  # noqa: E402  (the project's independent VTU reader)


def run_program(exe, args, log):
    """Runs perimorph with `args`, keeps its output in `log`; returns the wall time in seconds."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    t0 = time.time()
    p = subprocess.run([exe] + args, capture_output=True, text=True, env=env)
    wall = time.time() - t0
    with open(log, "w") as f:
        f.write(" ".join([exe] + args) + "\n" + p.stdout + p.stderr + f"\n[wall time {wall:.2f} s]\n")
    if p.returncode != 0:
        raise RuntimeError(f"perimorph {' '.join(args)} failed ({p.returncode}):\n{p.stdout}{p.stderr}")
    return wall


def read_cells(pvd):
    """Cell centroids (n, 2), cell strain (n, 9) and the point/cell arrays of the last VTU of a run."""
    _, vtu = read_pvd(pvd)[-1]
    pts = np.array(vtu["points"])
    cells = np.array(vtu["cells"])
    centre = pts[cells].mean(axis=1)[:, :2]
    out = {"centre": centre, "points": pts, "cells": cells}
    for name, arr in vtu["cell_data"].items():
        out[name] = np.array(arr["values"]).reshape(len(cells), arr["components"])
    for name, arr in vtu["point_data"].items():
        out["point_" + name] = np.array(arr["values"]).reshape(len(pts), arr["components"])
    return out


def grid_image(centre, values, n, lower=(0.0, 0.0), h=1.0):
    """Cell values of a structured n x n box mesh as an (n, n) image (row = y index), from the centroids."""
    img = np.full((n, n), np.nan)
    i = np.floor((centre[:, 0] - lower[0]) / h).astype(int)
    j = np.floor((centre[:, 1] - lower[1]) / h).astype(int)
    img[j, i] = values
    return img


def substitute(template, values, patterns, source):
    """Replaces each regex of `patterns` (must match exactly once) by values[key]."""
    text = template
    for key, pattern in patterns.items():
        if key not in values:
            continue
        text, n = re.subn(pattern, lambda m, v=values[key]: v, text, flags=re.M | re.S)
        if n != 1:
            raise RuntimeError(f"template {source}: pattern {pattern!r} matched {n} times (need 1)")
    return text


def source_state():
    """The commit of the source tree and whether src/ had uncommitted changes (the binary may hold them)."""
    try:
        head = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                              timeout=10).stdout.strip()
        dirty = subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--", "src", "apps"], capture_output=True,
                               text=True, timeout=10).stdout.strip()
        return f"commit {head}" + (" with uncommitted changes in src/" if dirty else "") if head else "unknown source"
    except (OSError, subprocess.SubprocessError):
        return "unknown source"


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def pct(v, spec=".3f"):
    return "—" if v is None or (isinstance(v, float) and math.isnan(v)) else format(100 * v, spec) + "%"


def write_json(path, obj):
    def clean(v):
        if isinstance(v, (np.floating, np.integer)):
            v = v.item()
        if isinstance(v, float) and not math.isfinite(v):
            return str(v)
        if isinstance(v, dict):
            return {k: clean(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [clean(x) for x in v]
        if isinstance(v, np.ndarray):
            return clean(v.tolist())
        return v

    with open(path, "w") as f:
        json.dump(clean(obj), f, indent=1)
