"""The morphing field α (THEORY §3.1): profiles of the normalized distance t ∈ [0, 1] (t = 0 at the outer
border of the transition, 1 where α = 1) and the distance-based shapes of the benchmarks."""

import numpy as np


def profile(name, t):
    t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
    if name == "heaviside":
        return np.where(t < 0.5, 0.0, 1.0)
    if name == "linear":
        return t
    if name == "cubic":
        return 3 * t**2 - 2 * t**3
    raise ValueError(f"unknown profile {name!r}")


def profile_slope(name, t):
    """dα/dt on 0 < t < 1, 0 outside (the heaviside jump at t = 1/2 is a Dirac mass: left to the caller)."""
    t = np.asarray(t, dtype=float)
    inside = (t > 0.0) & (t < 1.0)
    if name == "heaviside":
        return np.zeros_like(t)
    if name == "linear":
        return np.where(inside, 1.0, 0.0)
    if name == "cubic":
        return np.where(inside, 6 * t - 6 * t**2, 0.0)
    raise ValueError(f"unknown profile {name!r}")


def profile_integral(name, t):
    """∫₀^t α(s) ds, t clipped to [0, 1]."""
    t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
    if name == "heaviside":
        return np.maximum(t - 0.5, 0.0)
    if name == "linear":
        return t**2 / 2
    if name == "cubic":
        return t**3 - t**4 / 2
    raise ValueError(f"unknown profile {name!r}")


def from_distance(d, transition, name):
    """α of a shape whose inner part (α = 1) is at distance d ≤ 0 ... and whose transition of width
    `transition` lies at 0 < d < transition (d: distance outside the inner part)."""
    d = np.maximum(np.asarray(d, dtype=float), 0.0)
    return np.where(d >= transition, 0.0, profile(name, 1.0 - d / transition))


def ball(x, centre, radius, transition, name="cubic"):
    """Disk (2D) or sphere (3D): α = 1 for |x − c| ≤ radius."""
    d = np.linalg.norm(np.asarray(x) - np.asarray(centre)[: np.shape(x)[-1]], axis=-1) - radius
    return from_distance(d, transition, name)


def cylinder(x, point, axis, radius, transition, name="cubic"):
    """Infinite cylinder about the line through `point` along `axis`."""
    x, p, a = np.asarray(x, float), np.asarray(point, float), np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    r = x - p
    d = np.linalg.norm(r - np.outer(r @ a, a), axis=-1) - radius
    return from_distance(d, transition, name)


def box(x, lower, upper, transition, name="cubic"):
    """Axis-aligned box: α = 1 inside, distance to the box outside."""
    x = np.asarray(x, float)
    lo, hi = np.asarray(lower, float)[: x.shape[-1]], np.asarray(upper, float)[: x.shape[-1]]
    outside = np.maximum(np.maximum(lo - x, x - hi), 0.0)
    return from_distance(np.linalg.norm(outside, axis=-1), transition, name)
